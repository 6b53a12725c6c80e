//! The comparison side of the meshio cross-checks (`crate::meshio`, cargo
//! feature `meshio`): counting compared values and mismatches, and cells as
//! numbering-independent coordinate cycles. Kept out of the feature so its
//! tests run with the default build.

/// Result of a cross-check: how many values were compared and the
/// mismatches found (empty = agreement).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct CrossCheck {
    /// Numbers compared.
    pub compared: usize,
    /// Description of each mismatch (at most a few per quantity).
    pub mismatches: Vec<String>,
}

impl CrossCheck {
    /// Whether no mismatch was found.
    pub fn passed(&self) -> bool {
        self.mismatches.is_empty()
    }

    /// Compares one value `got` (read back) with `expected` (ctc's) to the
    /// relative tolerance `tol`; keeps at most 20 mismatch descriptions.
    pub fn value(&mut self, what: &str, index: usize, got: f64, expected: f64, tol: f64) {
        self.compared += 1;
        let ok = (got - expected).abs() <= tol * expected.abs().max(1e-300) || got == expected;
        if !ok && self.mismatches.len() < 20 {
            self.mismatches.push(format!(
                "{what}[{index}]: meshio read {got:e}, ctc has {expected:e}"
            ));
        }
    }
}

/// A point as the bits of its coordinates (exact comparison).
pub type Key = [u64; 2];

/// The key of a point.
pub fn key(p: [f64; 2]) -> Key {
    // +0.0 turns -0.0 into 0.0 so both readers' zeros compare equal.
    [(p[0] + 0.0).to_bits(), (p[1] + 0.0).to_bits()]
}

/// A cell as the cyclic sequence of its corner keys, rotated to start at
/// the smallest and walked counter-clockwise (ctc re-orients clockwise
/// cells, meshio keeps the file's order).
pub fn canonical_cell(points: &[[f64; 2]]) -> Vec<Key> {
    let area2: f64 = (0..points.len())
        .map(|i| {
            let (a, b) = (points[i], points[(i + 1) % points.len()]);
            a[0] * b[1] - b[0] * a[1]
        })
        .sum();
    let mut keys: Vec<Key> = points.iter().map(|&p| key(p)).collect();
    if area2 < 0.0 {
        keys.reverse();
    }
    let start = (0..keys.len()).min_by_key(|&i| keys[i]).unwrap_or(0);
    keys.rotate_left(start);
    keys
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn canonical_cell_ignores_start_and_orientation() {
        let a = canonical_cell(&[[0.0, 0.0], [1.0, 0.0], [1.0, 1.0]]);
        let b = canonical_cell(&[[1.0, 1.0], [0.0, 0.0], [1.0, 0.0]]);
        let cw = canonical_cell(&[[0.0, 0.0], [1.0, 1.0], [1.0, 0.0]]);
        assert_eq!(a, b);
        assert_eq!(a, cw);
        let other = canonical_cell(&[[0.0, 0.0], [1.0, 0.0], [0.0, 1.0]]);
        assert_ne!(a, other);
    }

    #[test]
    fn cross_check_value_reports_mismatches() {
        let mut c = CrossCheck::default();
        c.value("u", 0, 1.0, 1.0, 1e-15);
        c.value("u", 1, 1.0 + 1e-9, 1.0, 1e-15);
        assert_eq!(c.compared, 2);
        assert_eq!(c.mismatches.len(), 1);
        assert!(!c.passed());
    }
}
