//! Surface roughness of a node set at the current configuration
//! (`output { history = [roughness(sheet.rolled)] }`): the profile
//! parameters of ISO 4287 on the deformed positions of the set's nodes.
//!
//! The surface's *length* axes are the `D - 1` axes along which the set's
//! reference positions spread most; the remaining axis is the *height*
//! `z`. The mean line (plane in 3D) is the weighted least-squares fit `z
//! = c0 + c . s` of the heights on the length coordinates `s`
//! (detrending: a tilted or displaced surface has no roughness), and
//!
//! ```text
//! Ra = sum w_i |z_i - m(s_i)| / sum w_i     (arithmetic mean deviation)
//! Rq = sqrt(sum w_i (z_i - m(s_i))^2 / sum w_i)   (root mean square)
//! mean = sum w_i z_i / sum w_i            (the mean height of the surface)
//! ```
//!
//! Weights: in 2D the tributary length of each node along the deformed
//! profile's length axis (half the distance to each neighbour after
//! sorting by `s`, the trapezoidal rule of the profile integral, so a
//! refined stretch of the profile does not weigh more); in 3D every node
//! weighs 1 (the set is taken as evenly sampled).

/// Ra, Rq and the mean height of one surface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Roughness {
    /// Arithmetic mean deviation from the mean line.
    pub ra: f64,
    /// Root-mean-square deviation from the mean line.
    pub rq: f64,
    /// Weighted mean of the heights.
    pub mean: f64,
}

/// The height axis of a surface whose reference positions are `points`:
/// the axis of smallest extent (the last one on ties).
pub fn height_axis<const D: usize>(points: &[[f64; D]]) -> usize {
    let extent = |c: usize| {
        let (lo, hi) = points
            .iter()
            .fold((f64::INFINITY, f64::NEG_INFINITY), |(l, h), p| {
                (l.min(p[c]), h.max(p[c]))
            });
        if hi >= lo {
            hi - lo
        } else {
            0.0
        }
    };
    (0..D)
        .rev()
        .min_by(|&a, &b| extent(a).total_cmp(&extent(b)))
        .unwrap_or(D - 1)
}

/// Ra, Rq and mean height of the surface through `points` (current
/// positions), heights along `axis`. Fewer than 2 points, or points whose
/// length coordinates do not span the fit, give the plain deviation from
/// the mean (no tilt removed); no point gives zeros.
pub fn roughness<const D: usize>(points: &[[f64; D]], axis: usize) -> Roughness {
    let zero = Roughness {
        ra: 0.0,
        rq: 0.0,
        mean: 0.0,
    };
    if points.is_empty() || axis >= D {
        return zero;
    }
    let lengths: Vec<usize> = (0..D).filter(|&c| c != axis).collect();
    let weights = weights(points, &lengths);
    let total: f64 = weights.iter().sum();
    if total.is_nan() || total <= 0.0 {
        return zero;
    }
    let mean = points
        .iter()
        .zip(&weights)
        .map(|(p, w)| w * p[axis])
        .sum::<f64>()
        / total;
    let line = mean_line(points, &weights, &lengths, axis);
    let (mut a, mut q) = (0.0, 0.0);
    for (p, w) in points.iter().zip(&weights) {
        let m = line.0
            + lengths
                .iter()
                .zip(&line.1)
                .map(|(&c, k)| k * p[c])
                .sum::<f64>();
        let d = p[axis] - m;
        a += w * d.abs();
        q += w * d * d;
    }
    Roughness {
        ra: a / total,
        rq: (q / total).sqrt(),
        mean,
    }
}

/// The weights of the points: 2D tributary lengths along the length
/// axis, 3D ones.
fn weights<const D: usize>(points: &[[f64; D]], lengths: &[usize]) -> Vec<f64> {
    let n = points.len();
    if D != 2 || n < 2 {
        return vec![1.0; n];
    }
    let c = lengths[0];
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| points[a][c].total_cmp(&points[b][c]).then(a.cmp(&b)));
    let mut w = vec![0.0; n];
    for pair in order.windows(2) {
        let half = 0.5 * (points[pair[1]][c] - points[pair[0]][c]);
        w[pair[0]] += half;
        w[pair[1]] += half;
    }
    if w.iter().sum::<f64>() > 0.0 {
        w
    } else {
        vec![1.0; n]
    }
}

/// The weighted least-squares mean line (plane): `z = c0 + sum_k c_k
/// s_k`, solved in coordinates centred on the weighted centroid; the
/// length axes that do not span (a singular normal matrix) get no slope.
fn mean_line<const D: usize>(
    points: &[[f64; D]],
    weights: &[f64],
    lengths: &[usize],
    axis: usize,
) -> (f64, Vec<f64>) {
    let total: f64 = weights.iter().sum();
    let centre = |c: usize| {
        points
            .iter()
            .zip(weights)
            .map(|(p, w)| w * p[c])
            .sum::<f64>()
            / total
    };
    let zc = centre(axis);
    let sc: Vec<f64> = lengths.iter().map(|&c| centre(c)).collect();
    let k = lengths.len();
    // normal equations A c = b of the centred problem (k <= 2)
    let mut a = [[0.0; 2]; 2];
    let mut b = [0.0; 2];
    for (p, w) in points.iter().zip(weights) {
        let s: Vec<f64> = lengths.iter().zip(&sc).map(|(&c, m)| p[c] - m).collect();
        for i in 0..k {
            b[i] += w * s[i] * (p[axis] - zc);
            for j in 0..k {
                a[i][j] += w * s[i] * s[j];
            }
        }
    }
    let scale = (0..k).map(|i| a[i][i]).fold(0.0, f64::max);
    let tiny = 1e-12 * scale;
    let slope: Vec<f64> = match k {
        1 if a[0][0] > tiny && a[0][0] > 0.0 => vec![b[0] / a[0][0]],
        2 => {
            let det = a[0][0] * a[1][1] - a[0][1] * a[1][0];
            if det > tiny * scale && det > 0.0 {
                vec![
                    (b[0] * a[1][1] - b[1] * a[0][1]) / det,
                    (a[0][0] * b[1] - a[1][0] * b[0]) / det,
                ]
            } else {
                // one direction at most: fit along the wider one
                let i = if a[0][0] >= a[1][1] { 0 } else { 1 };
                let mut s = vec![0.0; 2];
                if a[i][i] > 0.0 {
                    s[i] = b[i] / a[i][i];
                }
                s
            }
        }
        _ => vec![0.0; k],
    };
    let c0 = zc - slope.iter().zip(&sc).map(|(k, m)| k * m).sum::<f64>();
    (c0, slope)
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A sampled cosine `z = a cos(2 pi x / l)` over whole periods,
    /// symmetric about the window's centre (so the mean line of the
    /// cosine alone is flat), has Ra = 2 a / pi and Rq = a / sqrt 2 (the
    /// profile integrals), whatever tilt and offset are added.
    #[test]
    fn a_tilted_cosine_has_the_ra_of_the_cosine() {
        let (a, l) = (0.3, 2.0);
        let n = 6000;
        let pts: Vec<[f64; 2]> = (0..=n)
            .map(|i| {
                let x = 3.0 * l * i as f64 / n as f64;
                [
                    x,
                    5.0 + 0.01 * x + a * (2.0 * std::f64::consts::PI * x / l).cos(),
                ]
            })
            .collect();
        let axis = height_axis(&pts);
        assert_eq!(axis, 1);
        let r = roughness(&pts, axis);
        let ra = 2.0 * a / std::f64::consts::PI;
        assert!((r.ra - ra).abs() < 1e-4 * ra, "{} vs {ra}", r.ra);
        let rq = a / 2f64.sqrt();
        assert!((r.rq - rq).abs() < 1e-4 * rq, "{} vs {rq}", r.rq);
        // the mean height is the line's value at the centroid
        assert!((r.mean - (5.0 + 0.01 * 3.0)).abs() < 1e-3, "{}", r.mean);
    }

    /// Nonuniform sampling: the tributary weights keep Ra the profile's;
    /// equal weights would not (the dense stretches are the crests).
    #[test]
    fn dense_sampling_of_a_stretch_does_not_bias_ra() {
        let a = 1.0;
        let mut xs: Vec<f64> = (0..=400).map(|i| 4.0 * i as f64 / 400.0).collect();
        // 10 times denser over the crest of each period, x in [p - 0.1, p + 0.1]
        for p in 1..4 {
            for i in 0..20 {
                xs.push(p as f64 - 0.1 + 0.2 * (i as f64 + 0.5) / 20.0);
            }
        }
        let pts: Vec<[f64; 2]> = xs
            .iter()
            .map(|&x| [x, a * (2.0 * std::f64::consts::PI * x).cos()])
            .collect();
        let r = roughness(&pts, 1);
        let ra = 2.0 * a / std::f64::consts::PI;
        assert!((r.ra - ra).abs() < 1e-3 * ra, "{} vs {ra}", r.ra);
        // equal weights: biased towards the crests
        let equal: f64 = pts.iter().map(|p| p[1].abs()).sum::<f64>() / pts.len() as f64;
        assert!(equal > 1.03 * ra, "{equal} vs {ra}");
    }

    /// A flat tilted plane in 3D has no roughness; a plane with a bump
    /// does.
    #[test]
    fn a_tilted_plane_in_3d_is_smooth() {
        let mut pts = Vec::new();
        for i in 0..10 {
            for j in 0..10 {
                let (x, y) = (i as f64, j as f64);
                pts.push([x, y, 2.0 + 0.1 * x - 0.2 * y]);
            }
        }
        let axis = height_axis(&pts);
        assert_eq!(axis, 2);
        let r = roughness(&pts, axis);
        assert!(r.ra < 1e-12 && r.rq < 1e-12, "{r:?}");
        pts[55][2] += 1.0;
        assert!(roughness(&pts, axis).ra > 1e-3);
    }

    /// Degenerate sets: no point, one point, points on a vertical line:
    /// finite numbers, no panic.
    #[test]
    fn degenerate_sets_give_finite_numbers() {
        assert_eq!(roughness::<2>(&[], 1).ra, 0.0);
        let one = roughness(&[[1.0, 2.0]], 1);
        assert_eq!((one.ra, one.mean), (0.0, 2.0));
        let column = [[0.0, 0.0], [0.0, 1.0], [0.0, 3.0]];
        let r = roughness(&column, 1);
        assert!(r.ra.is_finite() && r.rq.is_finite() && r.mean.is_finite());
    }
}
