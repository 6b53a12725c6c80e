//! Physical units of deck numbers: dimensions as exponents of mass,
//! length, time, temperature and angle, the unit names a deck may write
//! after a number (`210 GPa`, `5 mm`, `1e-3 /s`, `7.8e-9 t/mm^3`), and the
//! unit systems of `analysis { units = .. }`.
//!
//! A number without a unit is taken in the deck's unit system, whatever its
//! key; a number with a unit is converted into the system, and its
//! dimension must be the key's ([`crate::keys::Dim`]).

use std::fmt;

/// Exponents of mass, length, time, temperature and plane angle.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default, Hash)]
pub struct Exponents {
    /// Mass.
    pub m: i8,
    /// Length.
    pub l: i8,
    /// Time.
    pub t: i8,
    /// Temperature.
    pub k: i8,
    /// Plane angle (radians are the unit; degrees a scale).
    pub a: i8,
}

impl Exponents {
    /// `M^m L^l T^t`.
    pub const fn mlt(m: i8, l: i8, t: i8) -> Self {
        Exponents {
            m,
            l,
            t,
            k: 0,
            a: 0,
        }
    }

    /// A pure number.
    pub const NONE: Exponents = Exponents::mlt(0, 0, 0);
    /// Length.
    pub const LENGTH: Exponents = Exponents::mlt(0, 1, 0);
    /// Time.
    pub const TIME: Exponents = Exponents::mlt(0, 0, 1);
    /// Mass.
    pub const MASS: Exponents = Exponents::mlt(1, 0, 0);
    /// Force.
    pub const FORCE: Exponents = Exponents::mlt(1, 1, -2);
    /// Stress, pressure.
    pub const STRESS: Exponents = Exponents::mlt(1, -1, -2);
    /// Energy.
    pub const ENERGY: Exponents = Exponents::mlt(1, 2, -2);
    /// Power.
    pub const POWER: Exponents = Exponents::mlt(1, 2, -3);
    /// Temperature.
    pub const TEMPERATURE: Exponents = Exponents {
        m: 0,
        l: 0,
        t: 0,
        k: 1,
        a: 0,
    };
    /// Plane angle.
    pub const ANGLE: Exponents = Exponents {
        m: 0,
        l: 0,
        t: 0,
        k: 0,
        a: 1,
    };

    /// `self * other`.
    pub fn times(self, o: Exponents) -> Exponents {
        Exponents {
            m: self.m + o.m,
            l: self.l + o.l,
            t: self.t + o.t,
            k: self.k + o.k,
            a: self.a + o.a,
        }
    }

    /// `self / other`.
    pub fn per(self, o: Exponents) -> Exponents {
        self.times(o.pow(-1))
    }

    /// `self ^ n`.
    pub fn pow(self, n: i8) -> Exponents {
        Exponents {
            m: self.m * n,
            l: self.l * n,
            t: self.t * n,
            k: self.k * n,
            a: self.a * n,
        }
    }

    /// `self ^ (1/n)`, if every exponent divides.
    pub fn root(self, n: i8) -> Option<Exponents> {
        let all = [self.m, self.l, self.t, self.k, self.a];
        all.iter().all(|e| e % n == 0).then(|| Exponents {
            m: self.m / n,
            l: self.l / n,
            t: self.t / n,
            k: self.k / n,
            a: self.a / n,
        })
    }

    /// A name for the dimension ("a length", "a stress") or its formula.
    pub fn describe(self) -> String {
        for (e, name) in NAMED {
            if *e == self {
                return name.to_string();
            }
        }
        format!("a quantity of dimension {self}")
    }
}

/// Dimensions with a name, for messages.
const NAMED: &[(Exponents, &str)] = &[
    (Exponents::NONE, "a pure number"),
    (Exponents::LENGTH, "a length"),
    (Exponents::TIME, "a time"),
    (Exponents::MASS, "a mass"),
    (Exponents::FORCE, "a force"),
    (Exponents::STRESS, "a stress"),
    (Exponents::ENERGY, "an energy"),
    (Exponents::POWER, "a power"),
    (Exponents::TEMPERATURE, "a temperature"),
    (Exponents::ANGLE, "an angle"),
    (Exponents::mlt(0, 0, -1), "a rate (1/time)"),
    (Exponents::mlt(0, 1, -1), "a velocity"),
    (Exponents::mlt(1, -3, 0), "a density"),
    (
        Exponents::mlt(1, -2, -2),
        "a stiffness per area (stress/length)",
    ),
    (Exponents::mlt(1, 0, -2), "a stiffness (force/length)"),
    (Exponents::mlt(1, -1, -1), "a viscosity (stress x time)"),
];

impl fmt::Display for Exponents {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        for (e, s) in [
            (self.m, "M"),
            (self.l, "L"),
            (self.t, "T"),
            (self.k, "K"),
            (self.a, "rad"),
        ] {
            match e {
                0 => {}
                1 => parts.push(s.to_string()),
                e => parts.push(format!("{s}^{e}")),
            }
        }
        if parts.is_empty() {
            f.write_str("1")
        } else {
            f.write_str(&parts.join(" "))
        }
    }
}

/// A unit name a deck may write: its scale to SI and its dimension.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct UnitAtom {
    /// As written.
    pub name: &'static str,
    /// Value of one of it in SI (radians for angles).
    pub scale: f64,
    /// Dimension.
    pub dim: Exponents,
}

const fn atom(name: &'static str, scale: f64, dim: Exponents) -> UnitAtom {
    UnitAtom { name, scale, dim }
}

/// Every unit name (the grammar's `unit_atom` lists the same names; a test
/// checks they agree).
pub const ATOMS: &[UnitAtom] = &[
    atom("km", 1e3, Exponents::LENGTH),
    atom("m", 1.0, Exponents::LENGTH),
    atom("cm", 1e-2, Exponents::LENGTH),
    atom("mm", 1e-3, Exponents::LENGTH),
    atom("um", 1e-6, Exponents::LENGTH),
    atom("kg", 1.0, Exponents::MASS),
    atom("g", 1e-3, Exponents::MASS),
    atom("t", 1e3, Exponents::MASS),
    atom("s", 1.0, Exponents::TIME),
    atom("ms", 1e-3, Exponents::TIME),
    atom("us", 1e-6, Exponents::TIME),
    atom("N", 1.0, Exponents::FORCE),
    atom("kN", 1e3, Exponents::FORCE),
    atom("MN", 1e6, Exponents::FORCE),
    atom("mN", 1e-3, Exponents::FORCE),
    atom("Pa", 1.0, Exponents::STRESS),
    atom("kPa", 1e3, Exponents::STRESS),
    atom("MPa", 1e6, Exponents::STRESS),
    atom("GPa", 1e9, Exponents::STRESS),
    atom("J", 1.0, Exponents::ENERGY),
    atom("kJ", 1e3, Exponents::ENERGY),
    atom("W", 1.0, Exponents::POWER),
    atom("kW", 1e3, Exponents::POWER),
    atom("K", 1.0, Exponents::TEMPERATURE),
    atom("rad", 1.0, Exponents::ANGLE),
    atom("deg", std::f64::consts::PI / 180.0, Exponents::ANGLE),
];

/// The unit atom called `name`.
pub fn find(name: &str) -> Option<&'static UnitAtom> {
    ATOMS.iter().find(|a| a.name == name)
}

/// A unit as written after a number: a product of atoms with integer
/// powers, e.g. `N/mm^2` or `/s`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Unit {
    /// Value of one of it in SI.
    pub scale: f64,
    /// Dimension.
    pub dim: Exponents,
}

/// Parses a unit written as `atom(^n)? ((*|/|.) atom(^n)?)*`, optionally
/// starting with `/` (`/s` = 1/s). `Err` names the first unknown atom.
pub fn parse(text: &str) -> Result<Unit, String> {
    let mut unit = Unit {
        scale: 1.0,
        dim: Exponents::NONE,
    };
    let mut rest = text.trim();
    let mut divide = false;
    if let Some(r) = rest.strip_prefix('/') {
        divide = true;
        rest = r;
    }
    loop {
        let name_len = rest
            .find(|c: char| !(c.is_ascii_alphabetic()))
            .unwrap_or(rest.len());
        let (name, after) = rest.split_at(name_len);
        let a = find(name).ok_or_else(|| name.to_string())?;
        let mut after = after;
        let mut power: i32 = 1;
        if let Some(r) = after.strip_prefix('^') {
            let digits = r
                .find(|c: char| !(c.is_ascii_digit() || c == '-'))
                .unwrap_or(r.len());
            power = r[..digits].parse().map_err(|_| format!("{name}^"))?;
            after = &r[digits..];
        }
        if divide {
            power = -power;
        }
        let power = i8::try_from(power).map_err(|_| format!("{name}^{power}"))?;
        unit.scale *= a.scale.powi(power as i32);
        unit.dim = unit.dim.times(a.dim.pow(power));
        match after.chars().next() {
            None => break,
            Some('/') => divide = true,
            Some('*') | Some('.') => divide = false,
            Some(c) => return Err(c.to_string()),
        }
        rest = &after[1..];
    }
    Ok(unit)
}

/// A unit system of `analysis { units = .. }`: the SI value of its base
/// units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct System {
    /// Name in the deck.
    pub name: &'static str,
    /// What it is.
    pub doc: &'static str,
    /// SI value of the unit of mass, length, time and temperature.
    pub base: [f64; 4],
    /// Names of its units of length, force, stress, time, temperature and
    /// energy (labels of outputs and plots).
    pub labels: [&'static str; 6],
}

/// The unit systems.
pub const SYSTEMS: &[System] = &[
    System {
        name: "SI",
        doc: "m, kg, s, K (N, Pa)",
        base: [1.0, 1.0, 1.0, 1.0],
        labels: ["m", "N", "Pa", "s", "K", "J"],
    },
    System {
        name: "mm_N_s",
        doc: "mm, t, s, K (N, MPa, t/mm^3)",
        base: [1e3, 1e-3, 1.0, 1.0],
        labels: ["mm", "N", "MPa", "s", "K", "N*mm"],
    },
    System {
        name: "mm_kg_ms",
        doc: "mm, kg, ms, K (kN, GPa)",
        base: [1.0, 1e-3, 1e-3, 1.0],
        labels: ["mm", "kN", "GPa", "ms", "K", "J"],
    },
    System {
        name: "m_kg_s",
        doc: "the same as SI",
        base: [1.0, 1.0, 1.0, 1.0],
        labels: ["m", "N", "Pa", "s", "K", "J"],
    },
];

/// The system called `name`.
pub fn system(name: &str) -> Option<&'static System> {
    SYSTEMS.iter().find(|s| s.name == name)
}

impl System {
    /// The names of this system's units, as the engine's output labels.
    pub fn names(&self) -> ctc_engine::model::UnitNames {
        let [length, force, stress, time, temperature, energy] = self.labels.map(String::from);
        ctc_engine::model::UnitNames {
            system: self.name.to_string(),
            length,
            force,
            stress,
            time,
            temperature,
            energy,
        }
    }

    /// SI value of one unit of dimension `dim` in this system (angles:
    /// radians).
    pub fn scale(&self, dim: Exponents) -> f64 {
        self.base[0].powi(dim.m as i32)
            * self.base[1].powi(dim.l as i32)
            * self.base[2].powi(dim.t as i32)
            * self.base[3].powi(dim.k as i32)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_system_label_is_the_unit_of_its_base_scales() {
        // each label parses to the SI value the system gives that dimension
        let dims = [
            Exponents::LENGTH,
            Exponents::FORCE,
            Exponents::STRESS,
            Exponents::TIME,
            Exponents::TEMPERATURE,
            Exponents::ENERGY,
        ];
        for s in SYSTEMS {
            for (label, dim) in s.labels.iter().zip(dims) {
                let u = parse(label).unwrap_or_else(|e| panic!("{}: {label}: {e}", s.name));
                assert_eq!(u.dim, dim, "{} {label}", s.name);
                let rel = (u.scale / s.scale(dim) - 1.0).abs();
                assert!(
                    rel < 1e-12,
                    "{} {label}: {} vs {}",
                    s.name,
                    u.scale,
                    s.scale(dim)
                );
            }
        }
    }

    #[test]
    fn units_parse_to_si_scales_and_dimensions() {
        let u = parse("GPa").unwrap();
        assert_eq!((u.scale, u.dim), (1e9, Exponents::STRESS));
        let u = parse("N/mm^2").unwrap();
        assert!((u.scale - 1e6).abs() < 1e-6 && u.dim == Exponents::STRESS);
        let u = parse("/s").unwrap();
        assert_eq!(u.dim, Exponents::mlt(0, 0, -1));
        let u = parse("t/mm^3").unwrap();
        assert!((u.scale - 1e12).abs() < 1.0 && u.dim == Exponents::mlt(1, -3, 0));
        assert_eq!(parse("GPaa").unwrap_err(), "GPaa");
        assert_eq!(Exponents::STRESS.describe(), "a stress");
        assert_eq!(Exponents::mlt(2, 0, 0).to_string(), "M^2");
    }

    #[test]
    fn systems_convert_si_values() {
        let mm = system("mm_N_s").unwrap();
        // 1 MPa is the stress unit of mm_N_s
        assert!((mm.scale(Exponents::STRESS) - 1e6).abs() < 1e-6);
        assert!((mm.scale(Exponents::FORCE) - 1.0).abs() < 1e-12);
        assert!((mm.scale(Exponents::mlt(1, -3, 0)) - 1e12).abs() < 1.0);
        let ms = system("mm_kg_ms").unwrap();
        assert!((ms.scale(Exponents::STRESS) - 1e9).abs() < 1e-3);
    }
}
