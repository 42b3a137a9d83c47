//! Buckling onsets along the string and where it is buckled (issue 5), for the soft string and
//! the stiff FEM alike: the onset loads at each node compared with the model's effective axial
//! force there.
//!
//! Onset at a point (forces are effective compressions, N; physics.md 6.4), for a component
//! of bending stiffness `EI`, buoyed weight `w_b`, radial body clearance `r = (D_hole - D_body)/2`:
//!
//! ```text
//! lateral wall load  q(F) = | w_b (e_D - t t_D) - F dt/ds |         N/m, F compression
//! sinusoidal onset   F_s  = max( 2 sqrt(EI q(F_s) / r),  2.55 (EI w_b^2)^(1/3) )
//! helical onset      F_h  = max( 2 sqrt(2) sqrt(EI q(F_h) / r),  5.55 (EI w_b^2)^(1/3) )
//! ```
//!
//! In a straight hole `q = w_b sin I` and the first terms are Dawson & Paslay (1984) and Chen,
//! Lin & Cheatham (1990). In a curved hole the restoring load of the Dawson-Paslay derivation is
//! the wall force per length of the compressed pipe, which includes the curvature term
//! `F dt/ds` (compression pushes the pipe to the outside of the bend: it raises the onset in a
//! build, lowers it in a drop; the curved-hole form of He & Kyllingstad 1995) **\[uncertain:
//! this form is not in physics.md; solved by fixed-point iteration, falling back to the
//! straight-hole value when the iteration does not settle]**. The second terms are the
//! vertical-hole forms (Wu et al., coefficients \[uncertain] in physics.md 6.4), which keep the
//! onset finite where `q -> 0`. Components with less than
//! [`crate::loads::limits::MIN_BUCKLING_CLEARANCE_M`] of clearance (bit, gauge stabilizers) do
//! not buckle.

use crate::analytical::buckling::{vertical_force_unit, WU_VERTICAL_HELICAL, WU_VERTICAL_SINUSOIDAL};
use crate::geometry::{HoleSize, Vec3, WellPath};
use crate::loads::limits::MIN_BUCKLING_CLEARANCE_M;
use crate::string::{Component, DrillString};
use std::f64::consts::SQRT_2;

/// Buckling state at a node.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum BuckleState {
    /// Compression below the sinusoidal onset (or tension).
    None,
    /// Compression between the sinusoidal and the helical onset.
    Sinusoidal,
    /// Compression above the helical onset.
    Helical,
    /// The component cannot buckle here (no clearance, or no weight/stiffness).
    NotApplicable,
}

impl BuckleState {
    /// Name in `string.csv` and `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            BuckleState::None => "none",
            BuckleState::Sinusoidal => "sinusoidal",
            BuckleState::Helical => "helical",
            BuckleState::NotApplicable => "n/a",
        }
    }
}

/// Onsets and state at one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Mark {
    /// MD of the node, m.
    pub md_m: f64,
    /// Effective compression at the node, N (negative in tension).
    pub compression_n: f64,
    /// Sinusoidal onset, N (None where the component cannot buckle).
    pub sinusoidal_n: Option<f64>,
    /// Helical onset, N.
    pub helical_n: Option<f64>,
    /// State.
    pub state: BuckleState,
}

/// A contiguous buckled zone.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Zone {
    /// Upper (shallower) end, m MD.
    pub top_md_m: f64,
    /// Lower (deeper) end, m MD.
    pub bottom_md_m: f64,
    /// Worst state in the zone (sinusoidal or helical).
    pub state: BuckleState,
    /// Largest compression / sinusoidal onset in the zone.
    pub max_ratio: f64,
}

/// Fixed-point iterations of the curved-hole onset.
const ONSET_ITERATIONS: usize = 60;

/// Onset of the form `c sqrt(EI q(F) / r)` with `q(F) = |g - F k|`: fixed point from the
/// straight-hole value; that value if the iteration does not settle.
fn curved_onset(c: f64, ei: f64, r: f64, g: Vec3, k: Vec3) -> f64 {
    let f0 = c * (ei * g.norm() / r).sqrt();
    let mut f = f0;
    for _ in 0..ONSET_ITERATIONS {
        let next = c * (ei * (g - k * f).norm() / r).sqrt();
        if (next - f).abs() <= 1e-10 * next.abs().max(1.0) {
            return next;
        }
        // damped: the map's slope can approach 1 in sharp bends
        f = 0.5 * (f + next);
    }
    let last = c * (ei * (g - k * f).norm() / r).sqrt();
    if (last - f).abs() <= 1e-6 * last.abs().max(1.0) {
        last
    } else {
        f0
    }
}

/// Sinusoidal and helical onsets (N) of component `c` at `md_m` on `path`, hole diameter
/// `hole_diameter_m`, mud `mud_density_kg_m3`; None where it cannot buckle.
pub fn onset_at(
    c: &Component,
    path: &WellPath,
    md_m: f64,
    hole_diameter_m: f64,
    mud_density_kg_m3: f64,
) -> Option<(f64, f64)> {
    let r = (hole_diameter_m - c.body_od_m) / 2.0;
    if r.is_nan() || r < MIN_BUCKLING_CLEARANCE_M {
        return None;
    }
    let ei = c.ei_nm2();
    let w_b = c.buoyed_weight_n_per_m(mud_density_kg_m3);
    if !(ei > 0.0 && w_b > 0.0) {
        return None;
    }
    let p = path.point_at(md_m);
    let ez = Vec3::new(0.0, 0.0, 1.0);
    let g = (ez - p.tangent * p.tangent.z) * w_b;
    let k = p.dt_ds;
    let unit = vertical_force_unit(ei, w_b);
    let s = curved_onset(2.0, ei, r, g, k).max(WU_VERTICAL_SINUSOIDAL * unit);
    let h = curved_onset(2.0 * SQRT_2, ei, r, g, k).max(WU_VERTICAL_HELICAL * unit);
    Some((s, h))
}

/// Marks at nodes given as `(md_m, distance from the bit m, effective axial force N tension
/// positive)`, for `string` with its bit at the MD the distances are measured from.
pub fn marks(
    nodes: impl IntoIterator<Item = (f64, f64, f64)>,
    string: &DrillString,
    path: &WellPath,
    hole: &HoleSize,
    mud_density_kg_m3: f64,
) -> Vec<Mark> {
    nodes
        .into_iter()
        .map(|(md, s, axial)| {
            let c = string.component_at(s.max(0.0));
            let compression = -axial;
            match onset_at(c, path, md, hole.diameter_at(md), mud_density_kg_m3) {
                None => Mark {
                    md_m: md,
                    compression_n: compression,
                    sinusoidal_n: None,
                    helical_n: None,
                    state: BuckleState::NotApplicable,
                },
                Some((fs, fh)) => Mark {
                    md_m: md,
                    compression_n: compression,
                    sinusoidal_n: Some(fs),
                    helical_n: Some(fh),
                    state: if compression > fh {
                        BuckleState::Helical
                    } else if compression > fs {
                        BuckleState::Sinusoidal
                    } else {
                        BuckleState::None
                    },
                },
            }
        })
        .collect()
}

/// Contiguous buckled zones of `marks` (nodes in order along the string).
pub fn zones(marks: &[Mark]) -> Vec<Zone> {
    let mut out: Vec<Zone> = Vec::new();
    let mut open: Option<Zone> = None;
    for m in marks {
        let buckled = matches!(m.state, BuckleState::Sinusoidal | BuckleState::Helical);
        if buckled {
            let ratio = m.compression_n / m.sinusoidal_n.unwrap_or(f64::INFINITY);
            let z = open.get_or_insert(Zone {
                top_md_m: m.md_m,
                bottom_md_m: m.md_m,
                state: m.state,
                max_ratio: ratio,
            });
            z.top_md_m = z.top_md_m.min(m.md_m);
            z.bottom_md_m = z.bottom_md_m.max(m.md_m);
            z.max_ratio = z.max_ratio.max(ratio);
            if m.state == BuckleState::Helical {
                z.state = BuckleState::Helical;
            }
        } else if let Some(z) = open.take() {
            out.push(z);
        }
    }
    out.extend(open);
    out
}

/// MD intervals `(top, bottom)` where the marks are in `state`: each run of neighbouring marks
/// in that state, extended half way to the marks on either side (the tributary lengths that
/// the buckled lengths of `summary.json` add up). Marks in order along the string.
pub fn spans(marks: &[Mark], state: BuckleState) -> Vec<(f64, f64)> {
    let mut out: Vec<(f64, f64)> = Vec::new();
    let mut prev_in = false;
    for (i, m) in marks.iter().enumerate() {
        let here = m.state == state;
        if here {
            let half = |j: Option<usize>| j.map(|j| 0.5 * (marks[j].md_m - m.md_m)).unwrap_or(0.0);
            let a = m.md_m + half(i.checked_sub(1));
            let b = m.md_m + half((i + 1 < marks.len()).then_some(i + 1));
            let (lo, hi) = (a.min(b), a.max(b));
            match out.last_mut() {
                Some(s) if prev_in => {
                    s.0 = s.0.min(lo);
                    s.1 = s.1.max(hi);
                }
                _ => out.push((lo, hi)),
            }
        }
        prev_in = here;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::analytical::buckling::{helical_chen_lin_cheatham, sinusoidal_dawson_paslay};
    use crate::geometry::{Station, Survey};
    use crate::string::material::steel;
    use crate::string::ComponentKind;

    fn pipe() -> Component {
        let m = steel();
        let (od, id): (f64, f64) = (0.127, 4.276 * 0.0254);
        Component {
            kind: ComponentKind::Pipe,
            name: "pipe".into(),
            length_m: 3000.0,
            bottom_m: 0.0,
            body_od_m: od,
            contact_od_m: od,
            id_m: id,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: m,
            weight_air_n_per_m: 29.0 * crate::units::G,
        }
    }

    fn path(st: &[(f64, f64, f64)]) -> WellPath {
        let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
        WellPath::new(&s, Vec3::zeros()).unwrap()
    }

    /// Reference: Dawson & Paslay and Chen-Lin-Cheatham (analytical::buckling, physics.md 6.4)
    /// in a straight hole at 45 and 90 deg; tolerance 1e-12 relative.
    #[test]
    fn straight_hole_onsets_are_dawson_paslay_and_clc() {
        let c = pipe();
        let d = 8.5 * 0.0254;
        let r = (d - c.body_od_m) / 2.0;
        let w_b = c.buoyed_weight_n_per_m(1200.0);
        for inc in [45.0_f64, 90.0] {
            let p = path(&[(0.0, inc, 10.0), (1000.0, inc, 10.0)]);
            let (s, h) = onset_at(&c, &p, 500.0, d, 1200.0).unwrap();
            let s_ref = sinusoidal_dawson_paslay(c.ei_nm2(), w_b, inc.to_radians(), r).unwrap();
            let h_ref = helical_chen_lin_cheatham(c.ei_nm2(), w_b, inc.to_radians(), r).unwrap();
            assert!((s / s_ref - 1.0).abs() < 1e-12, "{s} {s_ref}");
            assert!((h / h_ref - 1.0).abs() < 1e-12);
        }
    }

    /// Reference: the vertical-hole floor 2.55 / 5.55 (EI w_b^2)^(1/3) (physics.md 6.4) in a
    /// vertical hole; and the curvature term: a build raises, a drop lowers the onset relative
    /// to the straight hole at the same inclination, and the fixed point satisfies its own
    /// equation to 1e-9.
    #[test]
    fn vertical_floor_and_curved_hole_form() {
        let c = pipe();
        let d = 8.5 * 0.0254;
        let w_b = c.buoyed_weight_n_per_m(1200.0);
        let v = path(&[(0.0, 0.0, 0.0), (1000.0, 0.0, 0.0)]);
        let (s, h) = onset_at(&c, &v, 500.0, d, 1200.0).unwrap();
        let u = vertical_force_unit(c.ei_nm2(), w_b);
        assert!((s / (WU_VERTICAL_SINUSOIDAL * u) - 1.0).abs() < 1e-12);
        assert!((h / (WU_VERTICAL_HELICAL * u) - 1.0).abs() < 1e-12);
        let straight = path(&[(0.0, 45.0, 0.0), (1000.0, 45.0, 0.0)]);
        let build = path(&[(0.0, 40.0, 0.0), (100.0, 50.0, 0.0)]);
        let drop = path(&[(0.0, 50.0, 0.0), (100.0, 40.0, 0.0)]);
        let s0 = onset_at(&c, &straight, 50.0, d, 1200.0).unwrap().0;
        let sb = onset_at(&c, &build, 50.0, d, 1200.0).unwrap().0;
        let sd = onset_at(&c, &drop, 50.0, d, 1200.0).unwrap().0;
        assert!(sb > s0 * 1.05 && sd < s0 * 0.95, "build {sb}, straight {s0}, drop {sd}");
        let p = build.point_at(50.0);
        let g = (Vec3::new(0.0, 0.0, 1.0) - p.tangent * p.tangent.z) * w_b;
        let r = (d - c.body_od_m) / 2.0;
        let q = (g - p.dt_ds * sb).norm();
        assert!((2.0 * (c.ei_nm2() * q / r).sqrt() / sb - 1.0).abs() < 1e-9);
    }

    /// Reference: hand-made marks: zones are the contiguous buckled runs, helical wins.
    #[test]
    fn zones_group_contiguous_runs() {
        let mk = |md: f64, st: BuckleState, c: f64| Mark {
            md_m: md,
            compression_n: c,
            sinusoidal_n: Some(100.0),
            helical_n: Some(141.0),
            state: st,
        };
        let m = [
            mk(10.0, BuckleState::None, 0.0),
            mk(9.0, BuckleState::Sinusoidal, 120.0),
            mk(8.0, BuckleState::Helical, 150.0),
            mk(7.0, BuckleState::None, 50.0),
            mk(6.0, BuckleState::Sinusoidal, 110.0),
        ];
        let z = zones(&m);
        assert_eq!(z.len(), 2);
        assert_eq!(
            (z[0].top_md_m, z[0].bottom_md_m, z[0].state),
            (8.0, 9.0, BuckleState::Helical)
        );
        assert!((z[0].max_ratio - 1.5).abs() < 1e-12);
        assert_eq!(
            (z[1].top_md_m, z[1].bottom_md_m, z[1].state),
            (6.0, 6.0, BuckleState::Sinusoidal)
        );
        // spans: half way to the neighbours, one per run and state (nodes 1 m apart)
        assert_eq!(spans(&m, BuckleState::Sinusoidal), vec![(8.5, 9.5), (6.0, 6.5)]);
        assert_eq!(spans(&m, BuckleState::Helical), vec![(7.5, 8.5)]);
        assert!(spans(&m[..1], BuckleState::Helical).is_empty());
    }
}
