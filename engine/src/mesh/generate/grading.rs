//! Division spacing: turns a [`Grading`] and a number of divisions into the
//! node parameters `0 = t_0 < t_1 < ... < t_n = 1`.

use super::Grading;
use crate::mesh::MeshError;

/// Smallest and largest accepted grading ratio: beyond these the smallest
/// division is a rounding error of the largest one.
pub const RATIO_RANGE: (f64, f64) = (1e-6, 1e6);

impl Grading {
    /// Checks the ratio (finite, within [`RATIO_RANGE`]); `what` names the
    /// direction in the error message.
    pub fn check(self, what: &str) -> Result<(), MeshError> {
        let ratio = match self {
            Grading::Uniform => return Ok(()),
            Grading::Geometric { ratio } | Grading::Center { ratio } => ratio,
        };
        if !ratio.is_finite() || ratio < RATIO_RANGE.0 || ratio > RATIO_RANGE.1 {
            return Err(MeshError::new(format!(
                "{what}: grading ratio {ratio} must be a number between {:e} and {:e}",
                RATIO_RANGE.0, RATIO_RANGE.1
            )));
        }
        Ok(())
    }

    /// Relative sizes of the `n` divisions (not normalised).
    fn sizes(self, n: usize) -> Vec<f64> {
        match self {
            Grading::Uniform => vec![1.0; n],
            Grading::Geometric { ratio } => {
                if n == 1 {
                    return vec![1.0];
                }
                let last = (n - 1) as f64;
                (0..n).map(|k| ratio.powf(k as f64 / last)).collect()
            }
            Grading::Center { ratio } => {
                // Divisions 0..m-1 go from the end to the middle; the rest
                // mirror them (the middle division is shared when n is odd).
                let m = n.div_ceil(2);
                let half: Vec<f64> = if m == 1 {
                    vec![1.0]
                } else {
                    let last = (m - 1) as f64;
                    (0..m).map(|k| ratio.powf(1.0 - k as f64 / last)).collect()
                };
                (0..n).map(|k| half[k.min(n - 1 - k)]).collect()
            }
        }
    }

    /// Node parameters `t_0 = 0 < ... < t_n = 1` of `n >= 1` divisions.
    ///
    /// - `Uniform`: `t_i = i / n`;
    /// - `Geometric { ratio }`: sizes in geometric progression with
    ///   last / first = `ratio` (one division: uniform);
    /// - `Center { ratio }`: symmetric, end / middle = `ratio` (fewer than
    ///   three divisions: uniform, there is no middle to refine).
    ///
    /// Symmetric gradings give exactly symmetric parameters
    /// (`t_{n-i} = 1 - t_i`). Call [`Grading::check`] first.
    pub fn points(self, n: usize) -> Vec<f64> {
        debug_assert!(n >= 1);
        let sizes = self.sizes(n);
        let total: f64 = sizes.iter().sum();
        let mut t = Vec::with_capacity(n + 1);
        let mut acc = 0.0;
        t.push(0.0);
        for s in &sizes[..n - 1] {
            acc += s;
            t.push(acc / total);
        }
        t.push(1.0);
        let symmetric = matches!(self, Grading::Uniform | Grading::Center { .. });
        if symmetric {
            for i in 0..=n / 2 {
                t[n - i] = 1.0 - t[i];
            }
            if n.is_multiple_of(2) {
                t[n / 2] = 0.5;
            }
        }
        t
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sizes_of(t: &[f64]) -> Vec<f64> {
        t.windows(2).map(|w| w[1] - w[0]).collect()
    }

    #[test]
    fn uniform_grading_equal_divisions() {
        let t = Grading::Uniform.points(4);
        assert_eq!(t, vec![0.0, 0.25, 0.5, 0.75, 1.0]);
    }

    #[test]
    fn geometric_grading_last_over_first_is_ratio() {
        for &(n, ratio) in &[(10, 0.2), (7, 5.0), (2, 0.5)] {
            let t = Grading::Geometric { ratio }.points(n);
            let s = sizes_of(&t);
            assert_eq!(t.len(), n + 1);
            assert!((s[n - 1] / s[0] - ratio).abs() < 1e-12 * ratio.max(1.0));
            // constant progression
            let q = s[1] / s[0];
            for w in s.windows(2) {
                assert!((w[1] / w[0] - q).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn center_grading_end_over_middle_is_ratio_even_and_odd() {
        for &(n, ratio) in &[(10, 4.0), (11, 4.0), (8, 0.25), (3, 2.0)] {
            let t = Grading::Center { ratio }.points(n);
            let s = sizes_of(&t);
            let mid = s[(n - 1) / 2];
            assert!(
                (s[0] / mid - ratio).abs() < 1e-12 * ratio.max(1.0),
                "{n} {ratio}"
            );
            for i in 0..n {
                assert!((s[i] - s[n - 1 - i]).abs() < 1e-15, "not symmetric");
            }
            for i in 0..=n / 2 {
                assert_eq!(t[n - i], 1.0 - t[i]);
            }
        }
    }

    #[test]
    fn center_grading_two_divisions_is_uniform() {
        assert_eq!(
            Grading::Center { ratio: 9.0 }.points(2),
            vec![0.0, 0.5, 1.0]
        );
        assert_eq!(Grading::Center { ratio: 9.0 }.points(1), vec![0.0, 1.0]);
    }

    #[test]
    fn grading_ratio_out_of_range_is_an_error() {
        assert!(Grading::Geometric { ratio: 0.0 }.check("x").is_err());
        assert!(Grading::Center { ratio: f64::NAN }.check("x").is_err());
        assert!(Grading::Geometric { ratio: 1e7 }.check("x").is_err());
        assert!(Grading::Geometric { ratio: 1e-3 }.check("x").is_ok());
    }

    #[test]
    fn graded_points_strictly_increasing_at_extreme_ratio() {
        for g in [
            Grading::Geometric { ratio: 1e-6 },
            Grading::Geometric { ratio: 1e6 },
            Grading::Center { ratio: 1e6 },
            Grading::Center { ratio: 1e-6 },
        ] {
            let t = g.points(200);
            assert!(t.windows(2).all(|w| w[1] > w[0]), "{g:?}");
        }
    }
}
