//! Hertz contact: elastic cylinder (plane strain, load per unit length) and
//! elastic sphere (load = total force), frictionless, small strain, a << R.
//!
//! Notation of `VERIFICATION-CASES.md` §1-2: E* combined modulus,
//! `1/E* = (1 - nu1^2)/E1 + (1 - nu2^2)/E2` (a rigid body contributes 0);
//! R combined radius, `1/R = 1/R1 + 1/R2` (a plane contributes 0).
//! Reference: K. L. Johnson, *Contact Mechanics*, 1985, §4.2 (sphere) and
//! §4.3 (cylinder).

use std::f64::consts::PI;

/// Combined (contact) modulus E* of two elastic bodies.
/// Pass `f64::INFINITY` as `e2` for a rigid body.
pub fn combined_modulus(e1: f64, nu1: f64, e2: f64, nu2: f64) -> f64 {
    let c2 = if e2.is_infinite() {
        0.0
    } else {
        (1.0 - nu2 * nu2) / e2
    };
    1.0 / ((1.0 - nu1 * nu1) / e1 + c2)
}

/// Combined radius R of two convex bodies. Pass `f64::INFINITY` as `r2`
/// for a plane.
pub fn combined_radius(r1: f64, r2: f64) -> f64 {
    let c2 = if r2.is_infinite() { 0.0 } else { 1.0 / r2 };
    1.0 / (1.0 / r1 + c2)
}

/// Hertz line contact of a cylinder in plane strain.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzCylinder {
    /// Combined modulus E*.
    pub e_star: f64,
    /// Combined radius R.
    pub radius: f64,
    /// Load per unit length P (> 0, pressing the bodies together).
    pub load: f64,
}

impl HertzCylinder {
    /// The load per unit length that produces the half-width `a`.
    pub fn from_half_width(e_star: f64, radius: f64, a: f64) -> Self {
        HertzCylinder {
            e_star,
            radius,
            load: PI * a * a * e_star / (4.0 * radius),
        }
    }

    /// Half-width of the contact strip, `a = sqrt(4 P R / (pi E*))`.
    pub fn half_width(&self) -> f64 {
        (4.0 * self.load * self.radius / (PI * self.e_star)).sqrt()
    }

    /// Peak pressure `p0 = 2 P / (pi a) = sqrt(P E* / (pi R))`.
    pub fn peak_pressure(&self) -> f64 {
        (self.load * self.e_star / (PI * self.radius)).sqrt()
    }

    /// Pressure `p(x) = p0 sqrt(1 - x^2/a^2)` inside the strip, 0 outside.
    pub fn pressure(&self, x: f64) -> f64 {
        let a = self.half_width();
        let s = 1.0 - (x / a).powi(2);
        if s <= 0.0 {
            0.0
        } else {
            self.peak_pressure() * s.sqrt()
        }
    }
}

/// Hertz point contact of a sphere (axisymmetric).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzSphere {
    /// Combined modulus E*.
    pub e_star: f64,
    /// Combined radius R.
    pub radius: f64,
    /// Total normal force P (> 0).
    pub load: f64,
}

impl HertzSphere {
    /// The load for a mutual approach `delta`:
    /// `P = (4/3) E* sqrt(R) delta^(3/2)`.
    pub fn from_approach(e_star: f64, radius: f64, delta: f64) -> Self {
        HertzSphere {
            e_star,
            radius,
            load: 4.0 / 3.0 * e_star * radius.sqrt() * delta.powf(1.5),
        }
    }

    /// Contact radius `a = (3 P R / (4 E*))^(1/3)`.
    pub fn contact_radius(&self) -> f64 {
        (3.0 * self.load * self.radius / (4.0 * self.e_star)).cbrt()
    }

    /// Mutual approach of distant points `delta = a^2 / R`.
    pub fn approach(&self) -> f64 {
        self.contact_radius().powi(2) / self.radius
    }

    /// Peak pressure `p0 = 3 P / (2 pi a^2) = 2 E* a / (pi R)`.
    pub fn peak_pressure(&self) -> f64 {
        let a = self.contact_radius();
        3.0 * self.load / (2.0 * PI * a * a)
    }

    /// Pressure `p(r) = p0 sqrt(1 - r^2/a^2)` inside the disc, 0 outside.
    pub fn pressure(&self, r: f64) -> f64 {
        let a = self.contact_radius();
        let s = 1.0 - (r / a).powi(2);
        if s <= 0.0 {
            0.0
        } else {
            self.peak_pressure() * s.sqrt()
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Composite Simpson rule with `n` (rounded up to even) intervals.
    fn simpson(f: impl Fn(f64) -> f64, a: f64, b: f64, n: usize) -> f64 {
        let n = n + n % 2;
        let h = (b - a) / n as f64;
        let mut s = f(a) + f(b);
        for i in 1..n {
            let w = if i % 2 == 1 { 4.0 } else { 2.0 };
            s += w * f(a + i as f64 * h);
        }
        s * h / 3.0
    }

    fn rel(a: f64, b: f64) -> f64 {
        ((a - b) / b).abs()
    }

    /// VERIFICATION-CASES §2 instance: two spheres R = 2 each,
    /// E = 1.40625e7, nu = 0.25, F = 1e4.
    #[test]
    fn hertz_sphere_two_spheres_instance() {
        let e_star = combined_modulus(1.40625e7, 0.25, 1.40625e7, 0.25);
        assert!(rel(e_star, 7.5e6) < 1e-14, "E* = {e_star}");
        let r = combined_radius(2.0, 2.0);
        assert!(rel(r, 1.0) < 1e-14);
        let h = HertzSphere {
            e_star,
            radius: r,
            load: 1e4,
        };
        assert!(
            rel(h.contact_radius(), 0.1) < 1e-12,
            "a = {}",
            h.contact_radius()
        );
        assert!(rel(h.approach(), 0.01) < 1e-12, "delta = {}", h.approach());
        assert!(
            rel(h.peak_pressure(), 4.775e5) < 1e-4,
            "p0 = {}",
            h.peak_pressure()
        );
        // p0 = 2 E* a / (pi R), the second form of the same number.
        let p0_alt = 2.0 * e_star * h.contact_radius() / (PI * r);
        assert!(rel(h.peak_pressure(), p0_alt) < 1e-12);
        // P = (4/3) E* sqrt(R) delta^(3/2) closes the loop.
        let back = HertzSphere::from_approach(e_star, r, 0.01);
        assert!(rel(back.load, 1e4) < 1e-12, "P = {}", back.load);
    }

    #[test]
    fn hertz_sphere_pressure_integrates_to_load() {
        let h = HertzSphere {
            e_star: 7.5e6,
            radius: 1.0,
            load: 1e4,
        };
        let a = h.contact_radius();
        // Substitute r = a sin(t) to remove the square-root end singularity.
        let total = simpson(
            |t| {
                let r = a * t.sin();
                2.0 * PI * r * h.pressure(r) * a * t.cos()
            },
            0.0,
            PI / 2.0,
            2000,
        );
        assert!(rel(total, 1e4) < 1e-8, "integral = {total}");
        assert_eq!(h.pressure(1.01 * a), 0.0);
    }

    /// Rigid plane (E2 = inf, R2 = inf) reduces to the body's own constants.
    #[test]
    fn hertz_rigid_plane_combined_constants() {
        let e_star = combined_modulus(1e3, 0.3, f64::INFINITY, 0.0);
        assert!(rel(e_star, 1e3 / 0.91) < 1e-14);
        assert_eq!(combined_radius(1.0, f64::INFINITY), 1.0);
    }

    /// Cylinder with the sphere instance's constants, load chosen for
    /// a = 0.1: P = pi a^2 E* / (4 R) = 58904.86, p0 = a E* / (2 R) = 3.75e5.
    #[test]
    fn hertz_cylinder_instance_a_0_1() {
        let h = HertzCylinder::from_half_width(7.5e6, 1.0, 0.1);
        assert!(rel(h.load, 58_904.862_254_808_63) < 1e-12, "P = {}", h.load);
        assert!(rel(h.half_width(), 0.1) < 1e-12);
        assert!(
            rel(h.peak_pressure(), 3.75e5) < 1e-12,
            "p0 = {}",
            h.peak_pressure()
        );
        // Both forms of p0.
        assert!(rel(h.peak_pressure(), 2.0 * h.load / (PI * 0.1)) < 1e-12);
    }

    #[test]
    fn hertz_cylinder_pressure_integrates_to_load() {
        let h = HertzCylinder {
            e_star: 1e3 / 0.91,
            radius: 1.0,
            load: 5.0,
        };
        let a = h.half_width();
        let total = simpson(
            |t| h.pressure(a * t.sin()) * a * t.cos(),
            -PI / 2.0,
            PI / 2.0,
            2000,
        );
        assert!(rel(total, 5.0) < 1e-8, "integral = {total}");
        assert!(rel(h.pressure(0.0), h.peak_pressure()) < 1e-15);
        assert!(rel(h.pressure(0.6 * a), 0.8 * h.peak_pressure()) < 1e-12);
        assert_eq!(h.pressure(-1.001 * a), 0.0);
    }
}
