//! Pressure-cycle control (superplastic forming): a follower pressure
//! whose factor is adjusted after every converged increment so that the
//! largest equivalent plastic strain rate of a body follows a target
//! ([`crate::model::RateControl`]).
//!
//! The update is multiplicative, `c <- c (target / rate)^exponent`, bounded
//! per increment: for a Norton-Hoff body (`q ~ rate^m`) under a pressure
//! that sets the stress, `exponent = m` lands on the target in one step
//! once the elastic transient is over; a smaller exponent under-relaxes.
//! The pressure is piecewise constant per increment in the factor (the
//! deck's time function still varies within it), as in Abaqus' creep
//! strain-rate control.

use crate::element::MaterialPoint;
use crate::model::{Load, Model, RateControl};

/// The controlled loads of `model`: index into `model.loads` and control.
pub fn controls<const D: usize>(model: &Model<D>) -> Vec<(usize, RateControl)> {
    model
        .loads
        .iter()
        .enumerate()
        .filter_map(|(i, l)| match l {
            Load::FollowerPressure {
                control: Some(c), ..
            } => Some((i, *c)),
            _ => None,
        })
        .collect()
}

/// The equivalent plastic strain of every integration point of `body`
/// (cell by cell, point by point; empty for a body without stored points).
pub fn body_ep<const D: usize>(
    model: &Model<D>,
    points: &[Vec<MaterialPoint>],
    body: usize,
) -> Vec<f64> {
    let Some(b) = model.bodies.get(body) else {
        return Vec::new();
    };
    points
        .get(b.cells.clone())
        .unwrap_or(&[])
        .iter()
        .flat_map(|cell| cell.iter().map(|p| p.history.ep))
        .collect()
}

/// The largest equivalent plastic strain rate between two snapshots of
/// [`body_ep`] over the time increment `dt`.
pub fn max_rate(before: &[f64], after: &[f64], dt: f64) -> f64 {
    if dt <= 0.0 {
        return 0.0;
    }
    before
        .iter()
        .zip(after)
        .map(|(a, b)| (b - a) / dt)
        .fold(0.0, f64::max)
}

/// The factor multiplying the controlled pressure for the next increment,
/// given the rate measured over the last one.
pub fn factor(control: &RateControl, rate: f64) -> f64 {
    let (lo, hi) = (1.0 / control.max_factor, control.max_factor);
    if rate.is_nan() || rate <= 0.0 || rate.is_infinite() {
        // nothing flowed (elastic start): raise the pressure at the bound
        return hi;
    }
    (control.target / rate).powf(control.exponent).clamp(lo, hi)
}

/// What a controller did in one converged increment.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ControlRecord {
    /// The pressure applied in the increment (factor x the deck's value at
    /// the end of the increment).
    pub pressure: f64,
    /// The largest equivalent plastic strain rate measured over it.
    pub rate: f64,
}

#[cfg(test)]
mod tests {
    use super::*;

    fn control() -> RateControl {
        RateControl {
            body: 0,
            target: 1e-3,
            exponent: 0.5,
            max_factor: 2.0,
        }
    }

    #[test]
    fn the_factor_lands_on_the_target_of_a_power_law_and_is_bounded() {
        let c = control();
        // q ~ rate^m with m = exponent: the factor is the stress ratio
        assert!((factor(&c, 4e-3) - 0.5).abs() < 1e-15);
        assert!((factor(&c, 0.25e-3) - 2.0).abs() < 1e-15);
        // bounded
        assert_eq!(factor(&c, 1.0), 0.5);
        assert_eq!(factor(&c, 1e-9), 2.0);
        // nothing flowed
        assert_eq!(factor(&c, 0.0), 2.0);
        assert_eq!(factor(&c, f64::NAN), 2.0);
    }

    #[test]
    fn the_largest_rate_is_the_largest_increase_over_dt() {
        assert_eq!(max_rate(&[0.0, 0.1, 0.2], &[0.01, 0.13, 0.2], 0.5), 0.06);
        assert_eq!(max_rate(&[0.0], &[0.01], 0.0), 0.0);
        assert_eq!(max_rate(&[], &[], 1.0), 0.0);
    }
}
