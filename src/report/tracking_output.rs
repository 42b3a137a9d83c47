//! Tracking outputs: the model against the naive projections (`baselines`, `skill`,
//! `physics_share` in `summary.json`), the assimilation's estimates and coverage, and the
//! per-interval columns that back-analysis adds to `trajectory.csv`.

use super::{num, Finite};
use crate::predict::tracking::assimilate::Assimilation;
use crate::predict::tracking::bank::{FilterBank, Trust};
use crate::predict::tracking::references::{Reference, STATISTIC_DAMPING, STATISTIC_WINDOW_M};
use crate::predict::tracking::skill::{EndDirections, ErrorSummary, Skill};
use serde::Serialize;

/// Mean errors per 100 m of one predictor, deg.
#[derive(Serialize)]
pub struct ErrorJson {
    intervals: usize,
    inc_err_per_100m_deg: Finite,
    azi_err_per_100m_deg: Finite,
    dir_err_per_100m_deg: Finite,
}

impl From<&ErrorSummary> for ErrorJson {
    fn from(e: &ErrorSummary) -> ErrorJson {
        ErrorJson {
            intervals: e.intervals,
            inc_err_per_100m_deg: Finite(e.inc_err_per_100m_rad.to_degrees()),
            azi_err_per_100m_deg: Finite(e.azi_err_per_100m_rad.to_degrees()),
            dir_err_per_100m_deg: Finite(e.dir_err_per_100m_rad.to_degrees()),
        }
    }
}

/// The statistic's errors with its definition.
#[derive(Serialize)]
pub struct StatisticJson {
    #[serde(flatten)]
    errors: ErrorJson,
    window_m: Finite,
    damping: Finite,
}

/// The `baselines` key: every reference on the same intervals as the model.
#[derive(Serialize)]
pub struct BaselinesJson {
    hold: ErrorJson,
    rates_30m: ErrorJson,
    rates_60m: ErrorJson,
    rates_90m: ErrorJson,
    statistic: StatisticJson,
    /// Name of the naive projection with the smallest mean direction error.
    best_naive: String,
    /// The plain model, when the model is the assimilated one.
    #[serde(skip_serializing_if = "Option::is_none")]
    plain: Option<ErrorJson>,
    /// The frozen assimilation, when assimilating.
    #[serde(skip_serializing_if = "Option::is_none")]
    frozen: Option<ErrorJson>,
}

impl BaselinesJson {
    /// The baselines of `s`.
    pub fn new(s: &Skill) -> BaselinesJson {
        let r = |q: Reference| ErrorJson::from(s.reference(q).expect("every reference is summarized"));
        let rates = |w: f64| r(Reference::Rates { window_m: w });
        BaselinesJson {
            hold: r(Reference::Hold),
            rates_30m: rates(30.0),
            rates_60m: rates(60.0),
            rates_90m: rates(90.0),
            statistic: StatisticJson {
                errors: r(Reference::Statistic),
                window_m: Finite(STATISTIC_WINDOW_M),
                damping: Finite(STATISTIC_DAMPING),
            },
            best_naive: s.best_naive.name(),
            plain: s.plain.as_ref().map(ErrorJson::from),
            frozen: s.frozen.as_ref().map(ErrorJson::from),
        }
    }
}

/// A (build, right) pair in deg/30 m.
#[derive(Serialize)]
pub struct TurnJson {
    build: Finite,
    right: Finite,
}

impl TurnJson {
    fn per_30m(x: [f64; 2]) -> TurnJson {
        TurnJson {
            build: Finite((x[0] * 30.0).to_degrees()),
            right: Finite((x[1] * 30.0).to_degrees()),
        }
    }
}

/// One estimated law parameter (walk angle in degrees).
#[derive(Serialize)]
pub struct EstimatedJson {
    name: &'static str,
    value: Finite,
    std_dev: Finite,
    prior: Finite,
    prior_std_dev: Finite,
    /// False when the data did not shrink its uncertainty (it stays at its prior).
    identified: bool,
}

/// Share of the measured end directions within one standard deviation.
#[derive(Serialize)]
pub struct CoverageJson {
    inclination: Finite,
    azimuth: Finite,
    both: Finite,
}

/// One filter of the bank with its weight at the end.
#[derive(Serialize)]
pub struct VariantJson {
    correlation_length_m: Finite,
    /// `offset` (a lasting offset and a fading fluctuation), `fluctuation` (a fading
    /// fluctuation only) or `steered` (a fading fluctuation, the hole turned back toward its
    /// recent mean direction).
    behaviour: &'static str,
    /// True where the variant takes the model's changing tendency, false where it holds it.
    model: bool,
    weight: Finite,
}

/// One naive member of the mixture with its weight at the end.
#[derive(Serialize)]
pub struct NaiveJson {
    /// `no_correction`, `statistic` or `hold`.
    name: String,
    weight: Finite,
}

/// The scales of the stated standard deviations (toward the high side, toward the right).
#[derive(Serialize)]
pub struct SdScaleJson {
    high_side: Finite,
    right: Finite,
}

/// The `assimilation` key.
#[derive(Serialize)]
pub struct AssimilationJson {
    /// The bank's filters and their weights at the end (in the whole mixture).
    variants: Vec<VariantJson>,
    /// The naive members and their weights at the end (with the filters' summing to 1).
    naive_members: Vec<NaiveJson>,
    /// The factors on the predicted standard deviations from the mixture's past errors.
    sd_scale: SdScaleJson,
    /// Survey stations within one standard deviation (back-analysis only).
    #[serde(skip_serializing_if = "Option::is_none")]
    coverage: Option<CoverageJson>,
    tendency_offset_deg_per_30m: TurnJson,
    tendency_offset_sd_deg_per_30m: TurnJson,
    fluctuation_sd_deg_per_30m: TurnJson,
    frozen_model_tendency_deg_per_30m: TurnJson,
    parameters: Vec<EstimatedJson>,
    /// Share of the weight on the variants that take the model's changing tendency.
    model_trust: Finite,
}

impl AssimilationJson {
    /// The summary of assimilation `a` whose law started at `case_values` (natural units, in
    /// the order of its parameters).
    pub fn new(a: &Assimilation, case_values: &[f64]) -> AssimilationJson {
        let [inc, azi, both] = a.coverage();
        let mut j = AssimilationJson::of_bank(&a.filter, a.frozen_model_tendency, case_values);
        j.coverage = Some(CoverageJson {
            inclination: Finite(inc),
            azimuth: Finite(azi),
            both: Finite(both),
        });
        j
    }

    /// The summary of `bank` with the model's tendency held at `frozen_tendency` (rad/m).
    pub fn of_bank(bank: &FilterBank, frozen_tendency: [f64; 2], case_values: &[f64]) -> AssimilationJson {
        let (offset, offset_sd) = bank.offset();
        let parameters = bank
            .parameters()
            .into_iter()
            .zip(case_values)
            .map(|((p, u, sd, prior_sd), &prior)| {
                let deg = |x: f64| {
                    if p == crate::case::bit_rock::LawParameter::WalkAngle {
                        x.to_degrees()
                    } else {
                        x
                    }
                };
                EstimatedJson {
                    name: p.name(),
                    value: Finite(deg(p.natural(u))),
                    std_dev: Finite(deg(sd * p.slope(u).abs())),
                    prior: Finite(deg(prior)),
                    prior_std_dev: Finite(deg(prior_sd * p.slope(p.unbounded(prior)).abs())),
                    identified: sd < crate::predict::tracking::estimator::IDENTIFIED_BELOW * prior_sd,
                }
            })
            .collect();
        AssimilationJson {
            variants: bank
                .variants()
                .into_iter()
                .map(|(l, b, t, w)| VariantJson {
                    correlation_length_m: Finite(l),
                    behaviour: b.name(),
                    model: t == Trust::Model,
                    weight: Finite(w),
                })
                .collect(),
            naive_members: bank
                .naive_weights()
                .into_iter()
                .map(|(m, w)| NaiveJson {
                    name: m.name(),
                    weight: Finite(w),
                })
                .collect(),
            sd_scale: {
                let s = bank.sd_scales();
                SdScaleJson {
                    high_side: Finite(s[0]),
                    right: Finite(s[1]),
                }
            },
            coverage: None,
            tendency_offset_deg_per_30m: TurnJson::per_30m(offset),
            tendency_offset_sd_deg_per_30m: TurnJson::per_30m(offset_sd),
            fluctuation_sd_deg_per_30m: TurnJson::per_30m(bank.fluctuation_sd()),
            frozen_model_tendency_deg_per_30m: TurnJson::per_30m(frozen_tendency),
            parameters,
            model_trust: Finite(bank.model_trust()),
        }
    }
}

/// The model against the references at the stations drilled ahead of a prediction.
#[derive(Serialize)]
pub struct TrackingSkillJson {
    /// The model's mean direction error per 100 m of hole from the start, deg.
    dir_err_per_100m_deg: Finite,
    baselines: BaselinesJson,
    skill: Option<Finite>,
    physics_share: Option<Finite>,
}

impl TrackingSkillJson {
    /// The summary of `s`.
    pub fn new(s: &Skill) -> TrackingSkillJson {
        TrackingSkillJson {
            dir_err_per_100m_deg: Finite(s.model.dir_err_per_100m_rad.to_degrees()),
            baselines: BaselinesJson::new(s),
            skill: s.skill.map(Finite),
            physics_share: s.physics_share.map(Finite),
        }
    }
}

/// Header of the columns back-analysis adds to `trajectory.csv`: the direction errors of the
/// model and the references at each interval's end (deg).
pub const REFERENCE_COLUMNS: &str = "dir_err_deg,hold_dir_err_deg,rates_30m_dir_err_deg,rates_60m_dir_err_deg,rates_90m_dir_err_deg,statistic_dir_err_deg";

/// Header of the columns an assimilating back-analysis adds after [`REFERENCE_COLUMNS`].
pub const ASSIMILATION_COLUMNS: &str =
    "plain_inc_deg,plain_azi_deg,frozen_inc_deg,frozen_azi_deg,frozen_dir_err_deg,inc_sd_deg,azi_sd_deg";

/// The reference columns of one interval end.
pub fn reference_cells(e: &EndDirections) -> Result<Vec<String>, String> {
    let mut out = vec![num(e.model.angle_to(&e.measured).to_degrees(), 4)?];
    for r in &e.references {
        out.push(num(r.angle_to(&e.measured).to_degrees(), 4)?);
    }
    Ok(out)
}

/// The assimilation columns of interval `k` of `a` with end directions `e`.
pub fn assimilation_cells(a: &Assimilation, k: usize, e: &EndDirections) -> Result<Vec<String>, String> {
    let i = &a.intervals[k];
    let deg = |x: f64| num(x.to_degrees(), 4);
    let azi = |x: f64| num(crate::geometry::survey::degrees_in_turn(x.to_degrees(), 4), 4);
    Ok(vec![
        deg(i.plain.inc_rad)?,
        azi(i.plain.azi_rad)?,
        deg(i.frozen.inc_rad)?,
        azi(i.frozen.azi_rad)?,
        deg(i.frozen.angle_to(&e.measured))?,
        deg(i.inc_sd_rad)?,
        deg(i.azi_sd_rad)?,
    ])
}
