//! The naive projections a directional driller makes by hand, against which every prediction
//! is judged: hold the direction at the start, or extrapolate the build and turn rates of the
//! hole behind it; and a damped statistic of those rates. They use only the measured hole at
//! and behind the start (no look-ahead).

use crate::geometry::frame::tangent;
use crate::geometry::survey::wrap_pi;
use crate::geometry::WellPath;

/// Windows of hole behind the start over which the rate references measure build and turn, m.
pub const RATE_WINDOWS_M: [f64; 3] = [30.0, 60.0, 90.0];

/// Window of the statistic's rates, m.
pub const STATISTIC_WINDOW_M: f64 = 30.0;

/// Factor on the statistic's rates: the last 30 m's build and turn, halved (one constant for
/// every well, chosen before any comparison: half way between hold and the rate projection,
/// since from one interval to the next the measured rates of steered wells keep about half
/// their value; never fitted to a well).
pub const STATISTIC_DAMPING: f64 = 0.5;

/// A naive projection of the hole direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Reference {
    /// The direction at the start, held.
    Hold,
    /// The inclination and azimuth rates over the last `window_m` of hole (shortened to the
    /// hole there is), extrapolated.
    Rates {
        /// Window behind the start, m.
        window_m: f64,
    },
    /// The rates over [`STATISTIC_WINDOW_M`] times [`STATISTIC_DAMPING`].
    Statistic,
}

impl Reference {
    /// Every reference, in the order of the outputs: hold, rates over 30, 60, 90 m, statistic.
    pub fn all() -> [Reference; 5] {
        [
            Reference::Hold,
            Reference::Rates {
                window_m: RATE_WINDOWS_M[0],
            },
            Reference::Rates {
                window_m: RATE_WINDOWS_M[1],
            },
            Reference::Rates {
                window_m: RATE_WINDOWS_M[2],
            },
            Reference::Statistic,
        ]
    }
    /// Name in the outputs: `hold`, `rates_30m`, `rates_60m`, `rates_90m`, `statistic`.
    pub fn name(self) -> String {
        match self {
            Reference::Hold => "hold".into(),
            Reference::Rates { window_m } => format!("rates_{window_m:.0}m"),
            Reference::Statistic => "statistic".into(),
        }
    }
    /// True for the naive projections among which the best is chosen (hold and the rates).
    pub fn is_naive(self) -> bool {
        !matches!(self, Reference::Statistic)
    }
}

/// Inclination and azimuth, rad.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Direction {
    /// Inclination, rad.
    pub inc_rad: f64,
    /// Azimuth, rad.
    pub azi_rad: f64,
}

impl Direction {
    /// The angle between this direction and `other`, rad (in [0, pi]).
    pub fn angle_to(&self, other: &Direction) -> f64 {
        let a = tangent(self.inc_rad, self.azi_rad);
        let b = tangent(other.inc_rad, other.azi_rad);
        // atan2 of |a x b| and a.b: accurate for small angles too
        a.cross(&b).norm().atan2(a.dot(&b))
    }
}

/// The direction `reference` projects at `to_md` from the measured `path` at and behind
/// `from_md` (m).
pub fn project(path: &WellPath, from_md: f64, to_md: f64, reference: Reference) -> Direction {
    let start = path.point_at(from_md);
    let (window, damping) = match reference {
        Reference::Hold => {
            return Direction {
                inc_rad: start.inc_rad,
                azi_rad: start.azi_rad,
            }
        }
        Reference::Rates { window_m } => (window_m, 1.0),
        Reference::Statistic => (STATISTIC_WINDOW_M, STATISTIC_DAMPING),
    };
    let w = window.min(from_md - path.md_start());
    if w <= 0.0 {
        return Direction {
            inc_rad: start.inc_rad,
            azi_rad: start.azi_rad,
        };
    }
    let back = path.point_at(from_md - w);
    let ahead = (to_md - from_md) / w * damping;
    Direction {
        inc_rad: start.inc_rad + (start.inc_rad - back.inc_rad) * ahead,
        azi_rad: start.azi_rad + wrap_pi(start.azi_rad - back.azi_rad) * ahead,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Station, Survey, Vec3};

    fn path(st: &[(f64, f64, f64)]) -> WellPath {
        let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
        WellPath::new(&s, Vec3::zeros()).unwrap()
    }

    /// Reference, by hand: a hole building 3 deg per 30 m at constant azimuth 90 deg, from
    /// 30 deg at 300 m: at 390 m hold keeps 39 deg; every rate window projects 42 deg at 420 m
    /// (minimum curvature interpolates the inclination linearly on a plane arc); the statistic
    /// half of the build (40.5 deg). The azimuth stays 90. Tolerance 1e-9 rad.
    #[test]
    fn references_on_a_constant_build() {
        let p = path(&[
            (0.0, 0.0, 90.0),
            (200.0, 20.0, 90.0),
            (300.0, 30.0, 90.0),
            (500.0, 50.0, 90.0),
        ]);
        let want = |r: Reference, deg: f64| {
            let d = project(&p, 390.0, 420.0, r);
            assert!(
                (d.inc_rad - deg.to_radians()).abs() < 1e-9,
                "{r:?}: {}",
                d.inc_rad.to_degrees()
            );
            assert!((d.azi_rad - 90f64.to_radians()).abs() < 1e-9);
        };
        want(Reference::Hold, 39.0);
        for w in RATE_WINDOWS_M {
            want(Reference::Rates { window_m: w }, 42.0);
        }
        want(Reference::Statistic, 40.5);
    }

    /// Reference: the angle between two directions 1 deg apart in inclination (1 deg), and
    /// between azimuths 2 deg apart at 30 deg inclination (2 arcsin(sin 30 sin 1) = 0.99996 deg).
    #[test]
    fn angle_between_directions() {
        let d = |i: f64, a: f64| Direction {
            inc_rad: i.to_radians(),
            azi_rad: a.to_radians(),
        };
        assert!((d(30.0, 10.0).angle_to(&d(31.0, 10.0)).to_degrees() - 1.0).abs() < 1e-12);
        let want = 2.0 * (30f64.to_radians().sin() * 1f64.to_radians().sin()).asin();
        assert!((d(30.0, 9.0).angle_to(&d(30.0, 11.0)) - want).abs() < 1e-12);
    }

    /// No look-ahead: changing the survey below the start changes no reference.
    #[test]
    fn references_use_no_station_below_the_start() {
        let a = path(&[
            (0.0, 0.0, 0.0),
            (300.0, 30.0, 40.0),
            (330.0, 33.0, 42.0),
            (360.0, 35.0, 45.0),
        ]);
        let b = path(&[
            (0.0, 0.0, 0.0),
            (300.0, 30.0, 40.0),
            (330.0, 33.0, 42.0),
            (360.0, 20.0, 80.0),
        ]);
        for r in Reference::all() {
            assert_eq!(project(&a, 330.0, 360.0, r), project(&b, 330.0, 360.0, r), "{r:?}");
        }
    }
}
