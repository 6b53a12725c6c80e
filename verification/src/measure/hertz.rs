//! Hertz quantities: a, p0, the pressure profile and the force balance.
//!
//! The load P entering the closed form is the one the run produced: the
//! total contact force in the direction of the axis (y), per unit length in
//! plane strain (divided by the thickness, doubled for a half model), total
//! over 2*pi for the axisymmetric sphere. Hertz is then evaluated for that
//! P, and a, p0 and p(x) are compared with it. The half-width is measured
//! twice: at the edge of the pressure profile
//! ([`ContactProfile::half_width`]) and from the first moment of the contact
//! forces ([`ContactProfile::moment_ratio`]).

use super::{relative_error, total_reaction, Measured, ProfileData, Value};
use crate::analytical::hertz::{combined_modulus, HertzCylinder, HertzSphere};
use crate::capture::FinalState;
use crate::case::Quantity;
use crate::profile::{Abscissa, ContactProfile};
use ctc_engine::model::Model;

/// Which Hertz solution and how the model maps onto it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct HertzSetup {
    /// Combined modulus (the elastic body against a rigid one).
    pub e_star: f64,
    /// Radius of the cylinder or sphere.
    pub radius: f64,
    /// Contact pair index.
    pub pair: usize,
    /// Abscissa of the axis of symmetry.
    pub axis: f64,
    /// Line contact (plane strain) or point contact (axisymmetric).
    pub sphere: bool,
    /// Half model: the force of the modelled half is doubled (cylinder).
    pub half_model: bool,
    /// Coordinate the profile is read in.
    pub abscissa: Abscissa,
}

impl HertzSetup {
    /// An elastic body (E, nu) against a rigid cylinder or plane.
    pub fn cylinder(
        young: f64,
        poisson: f64,
        radius: f64,
        pair: usize,
        axis: f64,
        half_model: bool,
        abscissa: Abscissa,
    ) -> Self {
        HertzSetup {
            e_star: combined_modulus(young, poisson, f64::INFINITY, 0.0),
            radius,
            pair,
            axis,
            sphere: false,
            half_model,
            abscissa,
        }
    }

    /// An elastic sphere (E, nu) on a rigid plane, axis r = 0.
    pub fn sphere(young: f64, poisson: f64, radius: f64, pair: usize) -> Self {
        HertzSetup {
            e_star: combined_modulus(young, poisson, f64::INFINITY, 0.0),
            radius,
            pair,
            axis: 0.0,
            sphere: true,
            half_model: false,
            abscissa: Abscissa::Reference,
        }
    }
}

/// Measures a, p0, the force balance and the profile error.
pub fn measure(model: &Model, state: &FinalState, setup: &HertzSetup) -> Result<Measured, String> {
    let profile = ContactProfile::extract(model, state, setup.pair, setup.axis, setup.abscissa)?;
    let force_y = profile.force[1];
    let load = if setup.sphere {
        force_y.abs()
    } else {
        let factor = if setup.half_model { 2.0 } else { 1.0 };
        factor * force_y.abs() / model.analysis.thickness
    };
    if load <= 0.0 || !load.is_finite() {
        return Err(format!(
            "the total contact force is {force_y:e}: no load went through the contact"
        ));
    }
    let (a_ref, p0_ref, pressure): (f64, f64, Box<dyn Fn(f64) -> f64>) = if setup.sphere {
        let h = HertzSphere {
            e_star: setup.e_star,
            radius: setup.radius,
            load,
        };
        (
            h.contact_radius(),
            h.peak_pressure(),
            Box::new(move |x| h.pressure(x)),
        )
    } else {
        let h = HertzCylinder {
            e_star: setup.e_star,
            radius: setup.radius,
            load,
        };
        (
            h.half_width(),
            h.peak_pressure(),
            Box::new(move |x| h.pressure(x)),
        )
    };
    let a = profile.half_width()?;
    let a_moment = profile.moment_ratio()
        * if setup.sphere {
            16.0 / (3.0 * std::f64::consts::PI)
        } else {
            0.75 * std::f64::consts::PI
        };
    let p0 = profile.axis_pressure()?;
    // against a rigid tool all reactions balance the contact force; between
    // two deformable bodies only the slave body's reactions do (the master
    // body's supports carry the opposite force)
    let reaction = match model.contacts.get(setup.pair).map(|c| (&c.master, c.body)) {
        Some((ctc_engine::model::ContactMaster::Surface { .. }, body)) => {
            let nodes = model.bodies[body].nodes.clone();
            state.reaction[nodes]
                .iter()
                .fold([0.0, 0.0], |s, r| [s[0] + r[0], s[1] + r[1]])
        }
        _ => total_reaction(state),
    };
    let extent = (1.5 * a_ref).min(profile.points.last().map_or(0.0, |p| p.x));
    let l2 = profile.l2_error(&pressure, a_ref, p0_ref, extent);
    let values = vec![
        Value {
            quantity: Quantity::HalfWidth,
            reference: Some(a_ref),
            computed: a,
            error: relative_error(a, a_ref),
        },
        Value {
            quantity: Quantity::HalfWidthMoment,
            reference: Some(a_ref),
            computed: a_moment,
            error: relative_error(a_moment, a_ref),
        },
        Value {
            quantity: Quantity::PeakPressure,
            reference: Some(p0_ref),
            computed: p0,
            error: relative_error(p0, p0_ref),
        },
        Value {
            quantity: Quantity::ContactForce,
            reference: Some(-reaction[1]),
            computed: force_y,
            error: relative_error(force_y, -reaction[1]),
        },
        Value {
            quantity: Quantity::PressureL2,
            reference: None,
            computed: l2,
            error: l2,
        },
    ];
    let h = profile.zone_mesh_size(a_ref);
    let data = ProfileData {
        points: profile.points.iter().map(|p| [p.x, p.pressure]).collect(),
        a: a_ref,
        p0: p0_ref,
        a_computed: a,
    };
    Ok(Measured {
        values,
        h,
        profile: Some(data),
    })
}
