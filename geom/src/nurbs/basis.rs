//! B-spline basis functions and their derivatives (The NURBS Book, Piegl &
//! Tiller, algorithms A2.1 "find span" and A2.3 "derivatives of the basis
//! functions", reimplemented on the stack).

/// Highest supported degree (keeps the basis on the stack).
pub const MAX_DEGREE: usize = 15;

/// Values and first two derivatives of the `p + 1` non-zero basis functions
/// at one parameter: `ders[k][r]` is the `k`-th derivative of `N_{span-p+r}`.
pub type Ders = [[f64; MAX_DEGREE + 1]; 3];

/// The knot span index `s` with `knots[s] <= u < knots[s + 1]` for `n`
/// control points of degree `p`. Parameters outside `[knots[p], knots[n]]`
/// get the first or last span: evaluation there extends the end polynomial
/// pieces (used when a Newton step leaves the domain).
pub fn find_span(n: usize, p: usize, u: f64, knots: &[f64]) -> usize {
    if u >= knots[n] {
        // Last non-empty span.
        let mut s = n - 1;
        while s > p && knots[s] >= knots[s + 1] {
            s -= 1;
        }
        return s;
    }
    if u <= knots[p] {
        let mut s = p;
        while s + 1 < n && knots[s] >= knots[s + 1] {
            s += 1;
        }
        return s;
    }
    let (mut lo, mut hi) = (p, n);
    while hi - lo > 1 {
        let mid = (lo + hi) / 2;
        if u < knots[mid] {
            hi = mid;
        } else {
            lo = mid;
        }
    }
    lo
}

/// Basis functions of degree `p` on `span` at `u` and their derivatives up
/// to order `nd <= 2`.
#[allow(clippy::needless_range_loop)] // indices follow the algorithm's notation
pub fn ders_basis(span: usize, u: f64, p: usize, nd: usize, knots: &[f64]) -> Ders {
    debug_assert!(p <= MAX_DEGREE && nd <= 2);
    let mut ndu = [[0.0; MAX_DEGREE + 1]; MAX_DEGREE + 1];
    let mut left = [0.0; MAX_DEGREE + 1];
    let mut right = [0.0; MAX_DEGREE + 1];
    ndu[0][0] = 1.0;
    for j in 1..=p {
        left[j] = u - knots[span + 1 - j];
        right[j] = knots[span + j] - u;
        let mut saved = 0.0;
        for r in 0..j {
            // Lower triangle: knot differences; upper triangle: basis values.
            ndu[j][r] = right[r + 1] + left[j - r];
            let temp = ndu[r][j - 1] / ndu[j][r];
            ndu[r][j] = saved + right[r + 1] * temp;
            saved = left[j - r] * temp;
        }
        ndu[j][j] = saved;
    }
    let mut ders: Ders = [[0.0; MAX_DEGREE + 1]; 3];
    for (j, d) in ders[0].iter_mut().enumerate().take(p + 1) {
        *d = ndu[j][p];
    }
    let nd = nd.min(p);
    // Coefficients of the derivative recurrences, two alternating rows.
    let mut a = [[0.0; MAX_DEGREE + 1]; 2];
    for r in 0..=p {
        let (mut s1, mut s2) = (0usize, 1usize);
        a[0][0] = 1.0;
        for k in 1..=nd {
            let mut d = 0.0;
            let rk = r as isize - k as isize;
            let pk = p - k;
            if r >= k {
                let rk = rk as usize;
                a[s2][0] = a[s1][0] / ndu[pk + 1][rk];
                d = a[s2][0] * ndu[rk][pk];
            }
            let j1 = if rk >= -1 { 1 } else { (-rk) as usize };
            let j2 = if r as isize - 1 <= pk as isize {
                k - 1
            } else {
                p - r
            };
            for j in j1..=j2 {
                let idx = (rk + j as isize) as usize;
                a[s2][j] = (a[s1][j] - a[s1][j - 1]) / ndu[pk + 1][idx];
                d += a[s2][j] * ndu[idx][pk];
            }
            if r <= pk {
                a[s2][k] = -a[s1][k - 1] / ndu[pk + 1][r];
                d += a[s2][k] * ndu[r][pk];
            }
            ders[k][r] = d;
            std::mem::swap(&mut s1, &mut s2);
        }
    }
    let mut factor = p as f64;
    for k in 1..=nd {
        for d in ders[k].iter_mut().take(p + 1) {
            *d *= factor;
        }
        factor *= (p - k) as f64;
    }
    ders
}

/// Checks a knot vector for `n` control points of degree `p`; the message
/// names `what`.
pub fn check_knots(what: &str, n: usize, p: usize, knots: &[f64]) -> Result<(), String> {
    if p == 0 || p > MAX_DEGREE {
        return Err(format!(
            "{what}: degree must be between 1 and {MAX_DEGREE} (got {p})"
        ));
    }
    if n < p + 1 {
        return Err(format!(
            "{what}: degree {p} needs at least {} control points (got {n})",
            p + 1
        ));
    }
    if knots.len() != n + p + 1 {
        return Err(format!(
            "{what}: the knot vector has {} values; {n} control points of degree {p} need {}",
            knots.len(),
            n + p + 1
        ));
    }
    if knots.iter().any(|k| !k.is_finite()) {
        return Err(format!("{what}: knots must be finite"));
    }
    if let Some(i) = knots.windows(2).position(|w| w[1] < w[0]) {
        return Err(format!(
            "{what}: knots must not decrease (knot {} = {} > knot {} = {})",
            i + 1,
            knots[i],
            i + 2,
            knots[i + 1]
        ));
    }
    if knots[p] >= knots[n] {
        return Err(format!(
            "{what}: the knot vector gives an empty parameter range"
        ));
    }
    for k in p + 1..n {
        let mult = knots.iter().filter(|&&v| v == knots[k]).count();
        if mult > p {
            return Err(format!(
                "{what}: interior knot {} has multiplicity {mult} > degree {p}: the geometry would be disconnected",
                knots[k]
            ));
        }
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn partition_of_unity_and_derivatives_by_differences() {
        let knots = [0.0, 0.0, 0.0, 0.0, 0.3, 0.5, 0.5, 0.8, 1.0, 1.0, 1.0, 1.0];
        let (n, p) = (8, 3);
        for &u in &[0.0, 0.1, 0.3, 0.42, 0.5, 0.77, 0.95, 1.0] {
            let s = find_span(n, p, u, &knots);
            assert!(knots[s] <= u && (u < knots[s + 1] || s == n - 1));
            let d = ders_basis(s, u, p, 2, &knots);
            let sum: f64 = d[0][..=p].iter().sum();
            assert!((sum - 1.0).abs() < 1e-14);
            let sum1: f64 = d[1][..=p].iter().sum();
            assert!(sum1.abs() < 1e-12);
            // First derivative by central differences inside the span.
            let h = 1e-6;
            if u - h >= knots[s] && u + h <= knots[s + 1] {
                let dp = ders_basis(s, u + h, p, 0, &knots);
                let dm = ders_basis(s, u - h, p, 0, &knots);
                for r in 0..=p {
                    let fd = (dp[0][r] - dm[0][r]) / (2.0 * h);
                    assert!((fd - d[1][r]).abs() < 1e-6 * (1.0 + d[1][r].abs()));
                }
                let d1p = ders_basis(s, u + h, p, 1, &knots);
                let d1m = ders_basis(s, u - h, p, 1, &knots);
                for r in 0..=p {
                    let fd = (d1p[1][r] - d1m[1][r]) / (2.0 * h);
                    assert!((fd - d[2][r]).abs() < 1e-5 * (1.0 + d[2][r].abs()));
                }
            }
        }
    }

    #[test]
    fn bad_knot_vectors_are_named() {
        assert!(check_knots("s", 3, 2, &[0.0, 0.0, 0.0, 1.0, 1.0, 1.0]).is_ok());
        assert!(check_knots("s", 3, 2, &[0.0, 0.0, 1.0, 1.0, 1.0])
            .unwrap_err()
            .contains("need 6"));
        assert!(check_knots("s", 3, 2, &[0.0, 0.0, 0.0, 1.0, 0.5, 1.0])
            .unwrap_err()
            .contains("decrease"));
        assert!(check_knots("s", 3, 0, &[0.0; 4])
            .unwrap_err()
            .contains("degree"));
        assert!(check_knots("s", 3, 2, &[0.0; 6])
            .unwrap_err()
            .contains("empty"));
    }
}
