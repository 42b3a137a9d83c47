//! Mean errors of every predictor on the same intervals, and the model's skill against the
//! best naive projection and against the frozen assimilation.
//!
//! Errors per 100 m are the seed paper's metric (end error divided by the interval length);
//! the direction error is the angle between the predicted and the measured hole direction at
//! the interval's end. `skill = 1 - model / best naive` and `physics_share = 1 - model /
//! frozen`, both on the mean direction error: positive where the model does better.

use super::references::{Direction, Reference};
use crate::geometry::survey::wrap_pi;

/// The end directions of every predictor on one interval.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EndDirections {
    /// Interval length, m.
    pub length_m: f64,
    /// Measured direction at the end.
    pub measured: Direction,
    /// The model's prediction (the assimilated one when assimilating).
    pub model: Direction,
    /// The references, in the order of [`Reference::all`].
    pub references: [Direction; 5],
    /// The plain model's prediction, when the model is the assimilated one.
    pub plain: Option<Direction>,
    /// The frozen assimilation's prediction, when assimilating.
    pub frozen: Option<Direction>,
}

/// Mean absolute errors per 100 m of interval over a set of intervals.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct ErrorSummary {
    /// Intervals.
    pub intervals: usize,
    /// Mean |inclination error| per 100 m, rad.
    pub inc_err_per_100m_rad: f64,
    /// Mean |azimuth error| per 100 m, rad.
    pub azi_err_per_100m_rad: f64,
    /// Mean direction error (angle) per 100 m, rad.
    pub dir_err_per_100m_rad: f64,
}

impl ErrorSummary {
    /// The mean errors of the predictions `(length m, predicted, measured)`.
    pub fn of(items: &[(f64, Direction, Direction)]) -> ErrorSummary {
        let n = items.len();
        if n == 0 {
            return ErrorSummary::default();
        }
        let mean = |f: &dyn Fn(&(f64, Direction, Direction)) -> f64| {
            items.iter().map(|it| f(it) * 100.0 / it.0).sum::<f64>() / n as f64
        };
        ErrorSummary {
            intervals: n,
            inc_err_per_100m_rad: mean(&|(_, p, m)| (p.inc_rad - m.inc_rad).abs()),
            azi_err_per_100m_rad: mean(&|(_, p, m)| wrap_pi(p.azi_rad - m.azi_rad).abs()),
            dir_err_per_100m_rad: mean(&|(_, p, m)| p.angle_to(m)),
        }
    }
}

/// The comparison of a run's predictors.
#[derive(Debug, Clone, PartialEq)]
pub struct Skill {
    /// The model (the assimilated one when assimilating).
    pub model: ErrorSummary,
    /// Every reference.
    pub references: Vec<(Reference, ErrorSummary)>,
    /// The naive projection (hold or rates) with the smallest mean direction error.
    pub best_naive: Reference,
    /// `1 - model / best naive` on the mean direction error; None when the best naive error is
    /// below [`SKILL_FLOOR_RAD_PER_M`] (the naive projection is exact: no ratio to it means
    /// anything).
    pub skill: Option<f64>,
    /// The plain model, when the model is the assimilated one.
    pub plain: Option<ErrorSummary>,
    /// The frozen assimilation, when assimilating.
    pub frozen: Option<ErrorSummary>,
    /// `1 - model / frozen` on the mean direction error, when assimilating (None also when the
    /// frozen error is below [`SKILL_FLOOR_RAD_PER_M`]).
    pub physics_share: Option<f64>,
}

/// Mean direction error of a reference below which a skill against it is not defined, rad/m
/// (0.001 deg/100 m, far below a survey's resolution: the reference is then exact, as on a
/// synthetic survey of constant rates).
pub const SKILL_FLOOR_RAD_PER_M: f64 = 0.001 * std::f64::consts::PI / 180.0 / 100.0;

impl Skill {
    /// The summary of reference `r`.
    pub fn reference(&self, r: Reference) -> Option<&ErrorSummary> {
        self.references.iter().find(|(q, _)| *q == r).map(|(_, s)| s)
    }
}

/// The skill of the predictors on `ends` (None without intervals).
pub fn skill(ends: &[EndDirections]) -> Option<Skill> {
    if ends.is_empty() {
        return None;
    }
    let of = |pick: &dyn Fn(&EndDirections) -> Option<Direction>| -> Option<ErrorSummary> {
        let items: Vec<(f64, Direction, Direction)> = ends
            .iter()
            .map(|e| pick(e).map(|p| (e.length_m, p, e.measured)))
            .collect::<Option<_>>()?;
        Some(ErrorSummary::of(&items))
    };
    let model = of(&|e| Some(e.model))?;
    let references: Vec<(Reference, ErrorSummary)> = Reference::all()
        .iter()
        .enumerate()
        .map(|(k, &r)| (r, of(&|e| Some(e.references[k])).unwrap_or_default()))
        .collect();
    let (best_naive, best) = references
        .iter()
        .filter(|(r, _)| r.is_naive())
        .min_by(|a, b| a.1.dir_err_per_100m_rad.total_cmp(&b.1.dir_err_per_100m_rad))
        .map(|(r, s)| (*r, *s))?;
    let frozen = of(&|e| e.frozen);
    // the errors are per 100 m, the floor per m
    let ratio = |a: f64, b: f64| (b > SKILL_FLOOR_RAD_PER_M * 100.0).then(|| 1.0 - a / b);
    Some(Skill {
        skill: ratio(model.dir_err_per_100m_rad, best.dir_err_per_100m_rad),
        physics_share: frozen.and_then(|f| ratio(model.dir_err_per_100m_rad, f.dir_err_per_100m_rad)),
        plain: of(&|e| e.plain),
        frozen,
        model,
        references,
        best_naive,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    fn d(i: f64, a: f64) -> Direction {
        Direction {
            inc_rad: i.to_radians(),
            azi_rad: a.to_radians(),
        }
    }

    /// Reference, by hand: two 50 m intervals measured at (30, 100); the model 0.5 deg off in
    /// inclination on both (1 deg/100 m); hold 1 deg off, the rates 2 deg, the statistic 1.5
    /// deg (2, 4, 3 deg/100 m): the best naive is hold, skill 1 - 1/2 = 0.5. Tolerance 1e-9.
    #[test]
    fn skill_against_the_best_naive_projection() {
        let m = d(30.0, 100.0);
        let e = EndDirections {
            length_m: 50.0,
            measured: m,
            model: d(30.5, 100.0),
            references: [
                d(31.0, 100.0),
                d(32.0, 100.0),
                d(32.0, 100.0),
                d(28.0, 100.0),
                d(31.5, 100.0),
            ],
            plain: None,
            frozen: None,
        };
        let s = skill(&[e, e]).unwrap();
        assert!((s.model.dir_err_per_100m_rad.to_degrees() - 1.0).abs() < 1e-9);
        assert!((s.model.inc_err_per_100m_rad.to_degrees() - 1.0).abs() < 1e-9);
        assert_eq!(s.best_naive, Reference::Hold);
        assert!((s.skill.unwrap() - 0.5).abs() < 1e-9);
        assert!(s.physics_share.is_none());
        let st = s.reference(Reference::Statistic).unwrap();
        assert!((st.dir_err_per_100m_rad.to_degrees() - 3.0).abs() < 1e-9);
    }
}
