//! The hole of a prediction: the measured hole behind the start, the hole sizes ahead, and
//! the predicted hole, whose station tangents follow the bit's motion.

use super::{PredictError, StepScheme};
use crate::case::Case;
use crate::geometry::frame::inc_azi;
use crate::geometry::{HoleSection, HoleSize, Station, Survey, Vec3, WellPath};

/// The measured hole up to `md_m`: the survey's stations up to it, plus a station
/// interpolated at `md_m` if it falls between stations.
pub fn hole_to(path: &WellPath, md_m: f64) -> Result<WellPath, PredictError> {
    let mut st: Vec<Station> = path
        .stations()
        .iter()
        .copied()
        .filter(|s| s.md_m <= md_m + 1e-9)
        .collect();
    if st.last().is_none_or(|s| md_m - s.md_m > 1e-6) {
        let p = path.point_at(md_m);
        st.push(Station {
            md_m,
            inc_rad: p.inc_rad,
            azi_rad: p.azi_rad,
        });
    }
    let survey = Survey::new(st).map_err(|p| PredictError::Geometry(p.message))?;
    WellPath::new(&survey, path.station_position(0)).map_err(|p| PredictError::Geometry(p.message))
}

/// Hole size for a prediction to `to_md_m`: the case's sections, continued below the deepest
/// one at the bit diameter (the new hole is drilled by this bit).
pub fn hole_for_prediction(case: &Case, to_md_m: f64) -> HoleSize {
    let hole = &case.well.hole;
    if hole.deepest_md() >= to_md_m {
        return hole.clone();
    }
    let mut sections = hole.sections().to_vec();
    let friction = sections.last().and_then(|s| s.friction);
    sections.push(HoleSection {
        to_md_m,
        diameter_m: case.string.components[0].contact_od_m,
        friction,
    });
    HoleSize::new(sections, hole.caliper().to_vec())
}

/// The predicted hole: the measured stations up to the start, then one point per step joined
/// by minimum-curvature arcs whose station tangents follow the bit's motion: at an interior
/// predicted station the chord directions interpolated linearly in MD between the middles of
/// the adjacent steps (their mean for equal steps); at the bit the last chord direction
/// ([`StepScheme::Chord`]) or its linear extrapolation from the previous chord
/// ([`StepScheme::Arc`]).
pub(super) struct PredictedHole {
    /// The measured stations up to the start.
    pub(super) measured: Vec<Station>,
    /// Position of the first station (north, east, TVD), m.
    pub(super) origin: Vec3,
    /// MD (m) and hole tangent at the start of the prediction.
    pub(super) start: (f64, Vec3),
    /// (end MD of the segment, chord direction) per predicted segment.
    pub(super) chords: Vec<(f64, Vec3)>,
    /// How the tangent at the bit is taken.
    pub(super) scheme: StepScheme,
}

impl PredictedHole {
    /// The hole through the measured stations and the chords, with `extra` (end MD, chord
    /// direction) appended as the step being tried.
    pub(super) fn path_with(&self, extra: Option<(f64, Vec3)>) -> Result<WellPath, PredictError> {
        let mut st = self.measured.clone();
        let chords: Vec<(f64, Vec3)> = self.chords.iter().copied().chain(extra).collect();
        let fallback = st.last().map(|s| s.azi_rad).unwrap_or(0.0);
        // (middle MD, direction) of segment k; the start tangent counts as a chord at the start MD
        let mid = |k: usize| -> (f64, Vec3) {
            let begin = if k == 0 { self.start.0 } else { chords[k - 1].0 };
            ((begin + chords[k].0) / 2.0, chords[k].1)
        };
        for (k, &(md, c)) in chords.iter().enumerate() {
            let t = match (self.scheme, chords.get(k + 1)) {
                (StepScheme::Chord, Some(&(_, next))) => (c + next).normalize(),
                (StepScheme::Chord, None) => c,
                (StepScheme::Arc, Some(_)) => {
                    // direction linear in MD between the middles of the adjacent chords
                    let ((m0, c0), (m1, c1)) = (mid(k), mid(k + 1));
                    (c0 + (c1 - c0) * ((md - m0) / (m1 - m0))).normalize()
                }
                (StepScheme::Arc, None) => {
                    // extrapolated from the previous chord (or the start tangent) and this one
                    let (m1, c1) = mid(k);
                    let (m0, c0) = if k == 0 { self.start } else { mid(k - 1) };
                    (c1 + (c1 - c0) * ((md - m1) / (m1 - m0))).normalize()
                }
            };
            let (inc, azi) = inc_azi(&t, fallback);
            st.push(Station {
                md_m: md,
                inc_rad: inc,
                azi_rad: azi,
            });
        }
        let survey = Survey::new(st).map_err(|p| PredictError::Geometry(p.message))?;
        WellPath::new(&survey, self.origin).map_err(|p| PredictError::Geometry(p.message))
    }
}
