//! Small 2D vector helpers on `[f64; 2]` used by the contact kernels.

/// `a + b`.
#[inline]
pub fn add(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] + b[0], a[1] + b[1]]
}

/// `a - b`.
#[inline]
pub fn sub(a: [f64; 2], b: [f64; 2]) -> [f64; 2] {
    [a[0] - b[0], a[1] - b[1]]
}

/// `s * a`.
#[inline]
pub fn scale(s: f64, a: [f64; 2]) -> [f64; 2] {
    [s * a[0], s * a[1]]
}

/// Dot product.
#[inline]
pub fn dot(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[0] + a[1] * b[1]
}

/// z component of the cross product `a x b`.
#[inline]
pub fn cross(a: [f64; 2], b: [f64; 2]) -> f64 {
    a[0] * b[1] - a[1] * b[0]
}

/// Euclidean norm.
#[inline]
pub fn norm(a: [f64; 2]) -> f64 {
    a[0].hypot(a[1])
}

/// `a` rotated by +90 degrees (the left normal of a tangent).
#[inline]
pub fn left(a: [f64; 2]) -> [f64; 2] {
    [-a[1], a[0]]
}

/// `a / |a|`, or `None` when `|a|` is zero or not finite.
#[inline]
pub fn unit(a: [f64; 2]) -> Option<[f64; 2]> {
    let n = norm(a);
    if n > 0.0 && n.is_finite() {
        Some([a[0] / n, a[1] / n])
    } else {
        None
    }
}

/// Outer product `a ⊗ b`.
#[inline]
pub fn outer(a: [f64; 2], b: [f64; 2]) -> [[f64; 2]; 2] {
    [[a[0] * b[0], a[0] * b[1]], [a[1] * b[0], a[1] * b[1]]]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn left_normal_of_x_axis_is_y_axis() {
        assert_eq!(left([1.0, 0.0]), [-0.0, 1.0]);
        assert_eq!(cross([1.0, 0.0], [0.0, 1.0]), 1.0);
        assert_eq!(unit([0.0, 0.0]), None);
        assert_eq!(unit([3.0, 4.0]), Some([0.6, 0.8]));
        assert_eq!(outer([1.0, 2.0], [3.0, 4.0]), [[3.0, 4.0], [6.0, 8.0]]);
    }
}
