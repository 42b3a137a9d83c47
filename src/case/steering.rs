//! Steering plans: where a bent housing slides at a toolface and where it rotates (and a rotary
//! steerable system's toolface and ratio), by MD
//! (`[[steering]]` in the case, a slide sheet CSV; docs/guide.md "Steering plans"), SI.

use std::path::PathBuf;

/// One interval of a steering plan.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SteeringInterval {
    /// Top of the interval, m MD.
    pub from_md_m: f64,
    /// Bottom of the interval, m MD (> `from_md_m`).
    pub to_md_m: f64,
    /// The string rotates (else it slides).
    pub rotating: bool,
    /// Toolface while sliding, rad ([`crate::case::Operation::toolface_rad`]); the first of the
    /// revolution when rotating.
    pub toolface_rad: f64,
    /// Steering ratio of a rotary steerable system over the interval, in [0, 1] (None: the
    /// tool's own, [`crate::string::RssTool::ratio`]).
    pub ratio: Option<f64>,
}

/// A steering plan: intervals by increasing MD that do not overlap. Where none covers an MD,
/// the operation's mode and toolface apply.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SteeringPlan {
    /// The intervals, by increasing MD.
    pub intervals: Vec<SteeringInterval>,
    /// The slide sheet the intervals were read from, if any (an input file of the case).
    pub sheet_path: Option<PathBuf>,
}

impl SteeringPlan {
    /// True without intervals.
    pub fn is_empty(&self) -> bool {
        self.intervals.is_empty()
    }
    /// The interval holding `md_m` (its top included, its bottom not), if any.
    pub fn at(&self, md_m: f64) -> Option<&SteeringInterval> {
        self.intervals
            .iter()
            .find(|iv| md_m >= iv.from_md_m - 1e-9 && md_m < iv.to_md_m - 1e-9)
    }
    /// The first interval end (top or bottom) deeper than `md_m` + `min_ahead_m`, m MD.
    pub fn next_boundary(&self, md_m: f64, min_ahead_m: f64) -> Option<f64> {
        self.intervals
            .iter()
            .flat_map(|iv| [iv.from_md_m, iv.to_md_m])
            .filter(|&b| b > md_m + min_ahead_m)
            .fold(None, |best: Option<f64>, b| Some(best.map_or(b, |x| x.min(b))))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn plan() -> SteeringPlan {
        let iv = |a: f64, b: f64, rotating: bool| SteeringInterval {
            from_md_m: a,
            to_md_m: b,
            rotating,
            toolface_rad: 0.0,
            ratio: None,
        };
        SteeringPlan {
            intervals: vec![iv(100.0, 110.0, false), iv(110.0, 140.0, true), iv(200.0, 205.0, false)],
            sheet_path: None,
        }
    }

    /// An interval holds its top, not its bottom; gaps are held by none.
    #[test]
    fn the_interval_at_an_md() {
        let p = plan();
        assert!(p.at(99.9).is_none());
        assert!(!p.at(100.0).unwrap().rotating);
        assert!(p.at(110.0).unwrap().rotating);
        assert!(p.at(139.99).unwrap().rotating);
        assert!(p.at(150.0).is_none());
        assert!(!p.at(204.0).unwrap().rotating);
        assert!(p.at(205.0).is_none());
    }

    /// The next end at least `min_ahead` deeper.
    #[test]
    fn the_next_interval_end() {
        let p = plan();
        assert_eq!(p.next_boundary(90.0, 0.2), Some(100.0));
        assert_eq!(p.next_boundary(99.9, 0.2), Some(110.0));
        assert_eq!(p.next_boundary(140.0, 0.2), Some(200.0));
        assert_eq!(p.next_boundary(205.0, 0.2), None);
    }
}
