//! Minimum curvature: positions, dogleg, DLS, and the hole axis at any measured depth.
//!
//! Between two stations the axis is the circular arc tangent to both station tangents
//! (docs/theory.md 2.1): dogleg `beta = atan2(|t1 x t2|, t1.t2)`, ratio factor
//! `RF = (2/beta) tan(beta/2)` (series below 1e-4), `dp = (dM/2)(t1 + t2) RF`. Inside an
//! interval the tangent is interpolated along the arc (spherical linear interpolation) and the
//! position by the same formula on the sub-arc (1.3), so interpolating at a station returns the
//! station. Beyond the first and last stations the axis continues as a straight line.
//!
//! The FEM uses a parallel-transported (Bishop) frame `(t, b1, b2)` that has no singularity
//! at inclination 0; `(t, h, r)` is only for output.

use super::frame::{inc_azi, rotate_about, tangent, Frame, Vec3};
use super::survey::{Station, Survey};

/// Dogleg below which an interval counts as straight (rad).
const STRAIGHT: f64 = 1e-9;

/// Ratio factor `(2/beta) tan(beta/2)` of minimum curvature, with its series near 0.
pub fn ratio_factor(beta: f64) -> f64 {
    if beta < 1e-4 {
        let b2 = beta * beta;
        1.0 + b2 / 12.0 + b2 * b2 / 120.0
    } else {
        2.0 / beta * (beta / 2.0).tan()
    }
}

/// Dogleg angle between two unit tangents (rad), robust for all angles.
pub fn dogleg(t1: &Vec3, t2: &Vec3) -> f64 {
    t1.cross(t2).norm().atan2(t1.dot(t2))
}

/// A point of the hole axis with its direction.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisPoint {
    /// Measured depth, m.
    pub md_m: f64,
    /// Position (north, east, tvd), m.
    pub position: Vec3,
    /// Unit tangent down the hole.
    pub tangent: Vec3,
    /// Inclination, rad.
    pub inc_rad: f64,
    /// Azimuth, rad in [0, 2 pi) (the interval's reference azimuth where vertical).
    pub azi_rad: f64,
    /// Curvature of the axis here, rad/m (0 outside the survey).
    pub curvature_per_m: f64,
    /// `dt/ds` here (curvature vector), 1/m.
    pub dt_ds: Vec3,
}

/// Position, tangent and curvature of the axis at one MD (an [`AxisPoint`] without the
/// angles).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct AxisGeometry {
    /// Position (north, east, tvd), m.
    pub position: Vec3,
    /// Unit tangent down the hole.
    pub tangent: Vec3,
    /// Curvature of the axis here, rad/m (0 outside the survey).
    pub curvature_per_m: f64,
    /// `dt/ds` here (curvature vector), 1/m.
    pub dt_ds: Vec3,
}

/// Why a survey cannot be turned into a well path.
#[derive(Debug, Clone, PartialEq)]
pub struct GeometryProblem {
    /// Index of the station that ends the bad interval.
    pub index: usize,
    /// What is wrong.
    pub message: String,
}

/// The hole axis of a survey by minimum curvature, queryable at any measured depth.
#[derive(Debug, Clone)]
pub struct WellPath {
    stations: Vec<Station>,
    md: Vec<f64>,
    pos: Vec<Vec3>,
    tan: Vec<Vec3>,
    /// Dogleg of interval k (stations k -> k+1), rad.
    dogleg: Vec<f64>,
    /// `sin` of the dogleg of interval k (the slerp's denominator).
    sin_dogleg: Vec<f64>,
    /// Unit rotation axis `t_k x t_k+1 / |.|` of interval k (zero if straight).
    axis: Vec<Vec3>,
    /// Bishop normal b1 at each station (b2 = t x b1).
    b1: Vec<Vec3>,
    /// Azimuth used as high-side reference where the hole is vertical, per station.
    ref_azi: Vec<f64>,
}

impl WellPath {
    /// Build the path; `origin` is the position (north, east, tvd) of the first station.
    /// An interval whose dogleg is 180 degrees (direction reversal) has no unique arc and is
    /// rejected.
    pub fn new(survey: &Survey, origin: Vec3) -> Result<WellPath, GeometryProblem> {
        let st = survey.stations().to_vec();
        let n = st.len();
        let md: Vec<f64> = st.iter().map(|s| s.md_m).collect();
        let tan: Vec<Vec3> = st.iter().map(|s| tangent(s.inc_rad, s.azi_rad)).collect();
        // Reference azimuth for vertical stations: the station's own azimuth as surveyed.
        let ref_azi: Vec<f64> = st.iter().map(|s| s.azi_rad).collect();
        let mut pos = Vec::with_capacity(n);
        let mut dl = Vec::with_capacity(n.saturating_sub(1));
        let mut axis = Vec::with_capacity(n.saturating_sub(1));
        let mut b1 = Vec::with_capacity(n);
        pos.push(origin);
        b1.push(Frame::from_tangent(&tan[0], ref_azi[0]).h);
        for k in 0..n.saturating_sub(1) {
            let (t1, t2) = (tan[k], tan[k + 1]);
            let beta = dogleg(&t1, &t2);
            if beta > std::f64::consts::PI - 1e-6 {
                return Err(GeometryProblem {
                    index: k + 1,
                    message: format!(
                        "the hole reverses direction between MD {} m and {} m (dogleg 180 deg): no minimum-curvature arc",
                        md[k],
                        md[k + 1]
                    ),
                });
            }
            let dm = md[k + 1] - md[k];
            pos.push(pos[k] + (t1 + t2) * (dm / 2.0 * ratio_factor(beta)));
            let a = if beta > STRAIGHT {
                t1.cross(&t2).normalize()
            } else {
                Vec3::zeros()
            };
            let next_b1 = if beta > STRAIGHT {
                rotate_about(&b1[k], &a, beta)
            } else {
                b1[k]
            };
            // re-orthogonalize against accumulated round-off
            let next_b1 = (next_b1 - t2 * t2.dot(&next_b1)).normalize();
            b1.push(next_b1);
            dl.push(beta);
            axis.push(a);
        }
        Ok(WellPath {
            stations: st,
            md,
            pos,
            tan,
            sin_dogleg: dl.iter().map(|b: &f64| b.sin()).collect(),
            dogleg: dl,
            axis,
            b1,
            ref_azi,
        })
    }

    /// The survey stations the path was built from.
    pub fn stations(&self) -> &[Station] {
        &self.stations
    }

    /// MD of the first station, m.
    pub fn md_start(&self) -> f64 {
        self.md[0]
    }

    /// MD of the last station, m.
    pub fn md_end(&self) -> f64 {
        *self.md.last().expect("a survey has at least one station")
    }

    /// Position of station `k`, m.
    pub fn station_position(&self, k: usize) -> Vec3 {
        self.pos[k]
    }

    /// Dogleg of the interval ending at station `k` (rad; 0 for k = 0).
    pub fn dogleg_before(&self, k: usize) -> f64 {
        if k == 0 {
            0.0
        } else {
            self.dogleg[k - 1]
        }
    }

    /// Dogleg severity of the interval ending at station `k`, rad/m (0 for k = 0).
    pub fn dls_before(&self, k: usize) -> f64 {
        if k == 0 {
            0.0
        } else {
            self.dogleg[k - 1] / (self.md[k] - self.md[k - 1])
        }
    }

    /// Index k of the interval [k, k+1] holding `md` (clamped to the first/last interval).
    fn interval(&self, md: f64) -> usize {
        let n = self.md.len();
        if n < 2 {
            return 0;
        }
        let k = self.md.partition_point(|&m| m <= md);
        k.saturating_sub(1).min(n - 2)
    }

    /// The axis point at measured depth `md_m` (any value: straight extrapolation outside).
    pub fn point_at(&self, md_m: f64) -> AxisPoint {
        let (g, k) = self.axis_geometry(md_m);
        let (inc, azi) = inc_azi(&g.tangent, self.ref_azi[k]);
        AxisPoint {
            md_m,
            position: g.position,
            tangent: g.tangent,
            inc_rad: inc,
            azi_rad: azi,
            curvature_per_m: g.curvature_per_m,
            dt_ds: g.dt_ds,
        }
    }

    /// Position, tangent and curvature of the axis at `md_m`: [`WellPath::point_at`] without
    /// the inclination and azimuth (two `atan2`), for the solver's nearest-point searches.
    pub fn axis_at(&self, md_m: f64) -> AxisGeometry {
        self.axis_geometry(md_m).0
    }

    /// [`WellPath::interval`], tried first at `hint` (the interval of a nearby MD): the same
    /// index without the binary search when `md` lies in that interval.
    fn interval_from(&self, md: f64, hint: usize) -> usize {
        if hint < self.md.len().saturating_sub(1) && self.md[hint] <= md && md < self.md[hint + 1] {
            hint
        } else {
            self.interval(md)
        }
    }

    /// The axis geometry at `md_m` and the index of the station interval (or end) used.
    fn axis_geometry(&self, md_m: f64) -> (AxisGeometry, usize) {
        self.axis_geometry_from(md_m, usize::MAX)
    }

    /// [`WellPath::axis_geometry`] with the interval searched from `hint` first (see
    /// [`WellPath::interval_from`]); the same result bit for bit.
    fn axis_geometry_from(&self, md_m: f64, hint: usize) -> (AxisGeometry, usize) {
        let n = self.md.len();
        let (position, t, kappa, dt_ds, k) = if n == 1 || md_m <= self.md[0] {
            let t = self.tan[0];
            (self.pos[0] + t * (md_m - self.md[0]), t, 0.0, Vec3::zeros(), 0)
        } else if md_m >= self.md[n - 1] {
            let t = self.tan[n - 1];
            (
                self.pos[n - 1] + t * (md_m - self.md[n - 1]),
                t,
                0.0,
                Vec3::zeros(),
                n - 1,
            )
        } else {
            let k = self.interval_from(md_m, hint);
            let dm = self.md[k + 1] - self.md[k];
            let lam = (md_m - self.md[k]) / dm;
            let beta = self.dogleg[k];
            let (t1, t2) = (self.tan[k], self.tan[k + 1]);
            let t = if beta > 1e-6 {
                (t1 * ((1.0 - lam) * beta).sin() + t2 * (lam * beta).sin()) / self.sin_dogleg[k]
            } else {
                (t1 * (1.0 - lam) + t2 * lam).normalize()
            };
            let p = self.pos[k] + (t1 + t) * (lam * dm / 2.0 * ratio_factor(lam * beta));
            let kappa = beta / dm;
            let dt = if beta > STRAIGHT {
                self.axis[k].cross(&t) * kappa
            } else {
                Vec3::zeros()
            };
            (p, t, kappa, dt, k)
        };
        (
            AxisGeometry {
                position,
                tangent: t,
                curvature_per_m: kappa,
                dt_ds,
            },
            k,
        )
    }

    /// Borehole frame (t, h, r) at `md_m`; where vertical, h points to the surveyed azimuth of
    /// the station at or above `md_m`.
    pub fn frame_at(&self, md_m: f64) -> Frame {
        let p = self.axis_at(md_m);
        let k = if md_m <= self.md[0] {
            0
        } else {
            self.md.partition_point(|&m| m <= md_m).saturating_sub(1)
        };
        Frame::from_tangent(&p.tangent, self.ref_azi[k.min(self.md.len() - 1)])
    }

    /// Parallel-transported (Bishop) frame `(t, b1, b2)` at `md_m`: `b1` starts as the high
    /// side at the first station and is carried along the arcs without twisting about `t`.
    pub fn bishop_at(&self, md_m: f64) -> (Vec3, Vec3, Vec3) {
        let p = self.axis_at(md_m);
        let n = self.md.len();
        let b1 = if n == 1 || md_m <= self.md[0] {
            self.b1[0]
        } else if md_m >= self.md[n - 1] {
            self.b1[n - 1]
        } else {
            let k = self.interval(md_m);
            let lam = (md_m - self.md[k]) / (self.md[k + 1] - self.md[k]);
            let beta = self.dogleg[k];
            if beta > STRAIGHT {
                rotate_about(&self.b1[k], &self.axis[k], lam * beta)
            } else {
                self.b1[k]
            }
        };
        let t = p.tangent;
        let b1 = (b1 - t * t.dot(&b1)).normalize();
        (t, b1, t.cross(&b1))
    }

    /// Largest dogleg severity over the intervals, rad/m, and the MD of the interval's end.
    pub fn max_dls(&self) -> (f64, f64) {
        let mut best = (0.0, self.md[0]);
        for k in 1..self.md.len() {
            let d = self.dls_before(k);
            if d > best.0 {
                best = (d, self.md[k]);
            }
        }
        best
    }

    /// Measured depth of the axis point nearest to `x` (the foot of the perpendicular from `x`
    /// to the axis), found by Newton from `md_guess` (docs/theory.md 2.2).
    pub fn nearest_md(&self, x: &Vec3, md_guess: f64) -> f64 {
        self.nearest_md_from(x, md_guess).0
    }

    /// [`WellPath::nearest_md`] and the axis geometry there (the same as `axis_at` of that
    /// MD, bit for bit), the station interval searched from the last one used.
    pub fn nearest_axis(&self, x: &Vec3, md_guess: f64) -> (f64, AxisGeometry) {
        let (md, k) = self.nearest_md_from(x, md_guess);
        (md, self.axis_geometry_from(md, k).0)
    }

    /// Nearest MD and the last station interval used (each step searches from the last).
    fn nearest_md_from(&self, x: &Vec3, md_guess: f64) -> (f64, usize) {
        let mut s = md_guess;
        let mut k = usize::MAX;
        for _ in 0..30 {
            let (p, kp) = self.axis_geometry_from(s, k);
            k = kp;
            let d = p.position - x;
            let g = d.dot(&p.tangent);
            let dg = 1.0 + d.dot(&p.dt_ds);
            let step = if dg > 0.2 { g / dg } else { g };
            s -= step;
            if step.abs() < 1e-10 {
                break;
            }
        }
        (s, k)
    }

    /// The same path moved by `shift_m` (every position plus `shift_m`, m): the solver works
    /// in a frame whose origin lies at the bit, where absolute coordinates (a bit kilometres
    /// from the first station, or a map-grid `origin`) would put a rounding floor under the
    /// residual.
    pub fn translated(&self, shift_m: Vec3) -> WellPath {
        let mut moved = self.clone();
        for p in &mut moved.pos {
            *p += shift_m;
        }
        moved
    }

    /// A new path with `station` appended (for drilling ahead); errors as [`WellPath::new`].
    pub fn extended(&self, station: Station) -> Result<WellPath, GeometryProblem> {
        let mut st = self.stations.clone();
        st.push(station);
        let survey = Survey::new(st).map_err(|p| GeometryProblem {
            index: p.index,
            message: p.message,
        })?;
        WellPath::new(&survey, self.pos[0])
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn path(st: &[(f64, f64, f64)]) -> WellPath {
        let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
        WellPath::new(&s, Vec3::zeros()).unwrap()
    }

    #[test]
    fn physics_md_worked_example() {
        // docs/theory.md 2.1: (1000 m, 10 deg, 338 deg) -> (1030 m, 15 deg, 340 deg).
        let w = path(&[(1000.0, 10.0, 338.0), (1030.0, 15.0, 340.0)]);
        let beta = w.dogleg_before(1).to_degrees();
        assert!((beta - 5.01797).abs() < 1e-5, "{beta}");
        let d = w.station_position(1);
        assert!((d.x - 6.06709).abs() < 1e-5);
        assert!((d.y + 2.30504).abs() < 1e-5);
        assert!((d.z - 29.27972).abs() < 1e-5);
        // 1.3: interpolation at 1015 m.
        let p = w.point_at(1015.0);
        assert!((p.inc_rad.to_degrees() - 12.49823).abs() < 1e-5);
        assert!((p.azi_rad.to_degrees() - 339.19696).abs() < 1e-5);
        assert!((p.position - Vec3::new(2.72522, -1.06449, 14.71068)).norm() < 2e-5);
    }

    #[test]
    fn hand_computed_arc_500m_0_to_30deg() {
        // Arc of 500 m building 0 -> 30 deg: R = 500/(pi/6); TVD = R sin 30, north = R (1 - cos 30).
        let w = path(&[(0.0, 0.0, 0.0), (500.0, 30.0, 0.0)]);
        let r = 500.0 / (30f64.to_radians());
        let p = w.station_position(1);
        assert!((p.z - r * 0.5).abs() < 1e-3);
        assert!((p.x - r * (1.0 - 30f64.to_radians().cos())).abs() < 1e-3);
        // and half way along the arc
        let h = w.point_at(250.0).position;
        assert!((h.z - r * 15f64.to_radians().sin()).abs() < 1e-3);
    }

    #[test]
    fn straight_and_reversal() {
        let w = path(&[(0.0, 45.0, 30.0), (100.0, 45.0, 30.0)]);
        assert!((w.station_position(1).norm() - 100.0).abs() < 1e-12);
        let s = Survey::new(vec![
            Station::from_deg(0.0, 0.0, 0.0),
            Station::from_deg(10.0, 180.0, 0.0),
        ])
        .unwrap();
        assert!(WellPath::new(&s, Vec3::zeros()).is_err());
        // near 180 deg (179.9) still works and stays on an arc of length dM
        let w = path(&[(0.0, 0.0, 0.0), (100.0, 179.9, 0.0)]);
        let chord = w.station_position(1).norm();
        let beta = w.dogleg_before(1);
        let r = 100.0 / beta;
        assert!((chord - 2.0 * r * (beta / 2.0).sin()).abs() < 1e-9);
    }

    #[test]
    fn nearest_md_recovers_axis_points() {
        let w = path(&[
            (0.0, 0.0, 0.0),
            (300.0, 0.0, 0.0),
            (600.0, 30.0, 45.0),
            (900.0, 60.0, 90.0),
        ]);
        for &s in &[100.0, 450.0, 612.3, 880.0] {
            let p = w.point_at(s);
            let (_, b1, _) = w.bishop_at(s);
            let x = p.position + b1 * 0.05;
            assert!((w.nearest_md(&x, s + 1.5) - s).abs() < 1e-6);
        }
    }

    #[test]
    fn bishop_frame_is_orthonormal_and_continuous() {
        let w = path(&[
            (0.0, 0.0, 0.0),
            (300.0, 0.0, 0.0),
            (600.0, 30.0, 45.0),
            (900.0, 60.0, 90.0),
        ]);
        let mut prev = w.bishop_at(0.0);
        let mut s = 0.0;
        while s < 900.0 {
            s += 1.0;
            let f = w.bishop_at(s);
            assert!(f.0.dot(&f.1).abs() < 1e-12 && (f.1.norm() - 1.0).abs() < 1e-12);
            assert!((f.1 - prev.1).norm() < 0.01, "b1 jumps at {s}");
            prev = f;
        }
    }
}
