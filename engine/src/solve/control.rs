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
//!
//! The factor that would have held the target over the last increment,
//! `c* = c (target / rate)^exponent`, drifts as the geometry changes (a
//! bulge needs a rising, then falling pressure): the update extrapolates
//! its trend over the last two increments of equal length, `c_next = c*_n
//! (c*_n / c*_(n-1))` when that drift is below [`MAX_DRIFT`] (within the
//! same bound), which removes the lag of
//! the plain update (free bulge: the pole rate 2 % low for 40 increments
//! and 0.9 % high at the end without it; `ctc verify
//! superplastic_free_bulge`).
//!
//! The applied pressure is capped at `max_pressure` ([`capped`]): once the
//! body needs more than the gas supply gives (a die corner), the pressure
//! stays there and the rate falls below the target.

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
            } => Some((i, c.clone())),
            _ => None,
        })
        .collect()
}

/// The equivalent plastic strain of every integration point the control
/// monitors: the cells of its body, or those touching its nodes `at` (cell
/// by cell, point by point; empty for a body without stored points).
pub fn monitored_ep<const D: usize>(
    model: &Model<D>,
    points: &[Vec<MaterialPoint>],
    control: &RateControl,
) -> Vec<f64> {
    let Some(b) = model.bodies.get(control.body) else {
        return Vec::new();
    };
    let watched = |c: &usize| {
        control.at.is_empty()
            || model
                .mesh
                .cells
                .nodes(*c)
                .iter()
                .any(|n| control.at.binary_search(n).is_ok())
    };
    b.cells
        .clone()
        .filter(watched)
        .filter_map(|c| points.get(c))
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

/// The largest relative change of the estimate between two increments
/// that is extrapolated: a smooth drift of the need, not the start-up
/// transient (where the estimate still jumps by the bound).
pub const MAX_DRIFT: f64 = 0.1;

/// A controller's memory: its last estimate `c*` of the factor holding the
/// target, and the length of the increment it was measured over.
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Trend {
    /// `(c*, dt)` of the last converged increment (`None` before the
    /// first, or when nothing flowed).
    last: Option<(f64, f64)>,
}

/// The factor for the next increment: `scale` the factor applied over the
/// last one (length `dt`, measured `rate`), extrapolated along the trend of
/// the estimates when the two last increments have the same length, and
/// bounded by `max_factor` around `scale`.
pub fn next_scale(control: &RateControl, scale: f64, rate: f64, dt: f64, trend: &mut Trend) -> f64 {
    let plain = factor(control, rate);
    let flowed = rate.is_finite() && rate > 0.0;
    let estimate = scale * plain;
    let mut next = estimate;
    if let (true, Some((previous, last_dt))) = (flowed, trend.last) {
        let drift = estimate / previous;
        if (last_dt - dt).abs() <= 1e-12 * dt && (drift - 1.0).abs() <= MAX_DRIFT {
            next = estimate * drift;
        }
    }
    trend.last = flowed.then_some((estimate, dt));
    let (lo, hi) = (scale / control.max_factor, scale * control.max_factor);
    next.clamp(lo, hi)
}

/// `scale` limited so that the applied pressure `scale x value` (`value`
/// the deck's pressure) stays within `max_pressure` in magnitude: the gas
/// supply's limit. At the cap the rate falls below the target (a die
/// corner filling by creep at the largest pressure).
pub fn capped(control: &RateControl, scale: f64, value: f64) -> f64 {
    if value == 0.0 || !control.max_pressure.is_finite() {
        return scale;
    }
    scale.min(control.max_pressure / value.abs())
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
            at: Vec::new(),
            target: 1e-3,
            exponent: 0.5,
            max_factor: 2.0,
            max_pressure: f64::INFINITY,
        }
    }

    #[test]
    fn the_cap_holds_the_applied_pressure_and_keeps_its_sign() {
        let mut c = control();
        assert_eq!(capped(&c, 3.0, 0.5), 3.0);
        c.max_pressure = 1.2;
        assert_eq!(capped(&c, 3.0, 0.5), 2.4);
        assert_eq!(capped(&c, 2.0, 0.5), 2.0);
        // a negative deck value (suction): the magnitude is capped
        assert_eq!(capped(&c, 3.0, -0.5), 2.4);
        // a deck value of zero: nothing to cap
        assert_eq!(capped(&c, 3.0, 0.0), 3.0);
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
    fn the_trend_follows_a_drifting_need_and_keeps_a_steady_one() {
        let c = control();
        // a steady need: the plain update, unchanged
        let mut t = Trend::default();
        let s1 = next_scale(&c, 1.0, 4e-3, 1.0, &mut t);
        assert!((s1 - 0.5).abs() < 1e-15);
        let s2 = next_scale(&c, s1, 1e-3, 1.0, &mut t);
        assert!((s2 - 0.5).abs() < 1e-15);
        // a need growing by 1 % per increment (power law, exponent = m):
        // after two increments the prediction is exact
        let need = |n: i32| 1.01f64.powi(n);
        let mut t = Trend::default();
        let mut s = 1.0;
        for n in 0..6 {
            let rate = 1e-3 * (s / need(n)).powi(2);
            s = next_scale(&c, s, rate, 0.5, &mut t);
        }
        assert!((s / need(6) - 1.0).abs() < 1e-12, "{s} vs {}", need(6));
        // increments of different lengths: no extrapolation
        let mut t = Trend::default();
        let a = next_scale(&c, 1.0, 1e-3 / 1.01f64.powi(2), 0.5, &mut t);
        assert!((a - 1.01).abs() < 1e-12);
        let b = next_scale(&c, a, 1e-3 * (a / 1.02f64).powi(2), 0.25, &mut t);
        assert!((b - 1.02).abs() < 1e-12);
        // nothing flowed: the bound, and no memory
        let mut t = Trend::default();
        assert_eq!(next_scale(&c, 1.0, 0.0, 1.0, &mut t), 2.0);
        assert_eq!(t, Trend::default());
    }

    #[test]
    fn the_largest_rate_is_the_largest_increase_over_dt() {
        assert_eq!(max_rate(&[0.0, 0.1, 0.2], &[0.01, 0.13, 0.2], 0.5), 0.06);
        assert_eq!(max_rate(&[0.0], &[0.01], 0.0), 0.0);
        assert_eq!(max_rate(&[], &[], 1.0), 0.0);
    }
}
