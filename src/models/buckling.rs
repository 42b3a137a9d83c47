//! Buckling onsets along the string and where it is buckled, for the soft string and
//! the stiff FEM alike: the onset loads at each node compared with the model's effective axial
//! force there.
//!
//! Onset at a point (forces are effective compressions, N; docs/theory.md 7.1), for a component
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
//! build, lowers it in a drop): Dawson-Paslay with the curved-hole wall load, drillpath's own
//! form (docs/theory.md 7.2) **\[uncertain: not checked against the published curved-hole
//! criteria of He & Kyllingstad (1995) or Mitchell; solved by fixed-point iteration, falling
//! back to the straight-hole value when the iteration does not settle]**. The second terms are the
//! vertical-hole forms (Wu et al., coefficients \[uncertain] in docs/theory.md 7.1), which keep the
//! onset finite where `q -> 0`.
//!
//! **Stabilizers are supports.** Between the bit face and the stabilizers' blade centres (each
//! taken as a pinned lateral support \[uncertain for an under-gauge blade, which holds the
//! string only once its clearance is taken up]) the bottom-hole assembly is a column of span
//! `L`: its buckling modes must vanish at both supports, which restricts the sinusoidal mode's
//! wavenumber to `n pi / L` and gives [`span_sinusoidal_onset`] (the Euler load of the span
//! plus the wall's restoring term; Dawson-Paslay again for a long span). Above the highest
//! stabilizer the unsupported onset applies. Components with less than
//! [`MIN_BUCKLING_CLEARANCE_M`] of clearance (bit, gauge stabilizers) do
//! not buckle.

use crate::geometry::{HoleSize, Vec3, WellPath};
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
    /// Mitchell's helical contact force per length at the node's compression `F`,
    /// `r F^2 / (4 EI)` (N/m, `r` the radial clearance): where the compression exceeds the
    /// helical onset (0 below it; None where the component cannot buckle). The wall force the
    /// helix adds to a soft string's (docs/theory.md 7.4).
    pub helical_wall_force_n_per_m: Option<f64>,
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

/// Sinusoidal buckling onset in a straight inclined hole, Dawson & Paslay (1984):
/// `2 sqrt(EI q / r)`, N compression, for bending stiffness `ei` N.m2, lateral wall load `q`
/// N/m (`w_b sin I` in a straight hole) and radial clearance `r` m.
pub fn dawson_paslay(ei: f64, q: f64, r: f64) -> f64 {
    2.0 * (ei * q / r).sqrt()
}

/// Helical buckling onset, Chen, Lin & Cheatham (1990): `2 sqrt(2) sqrt(EI q / r)`, N
/// compression; inputs as [`dawson_paslay`].
pub fn chen_lin_cheatham(ei: f64, q: f64, r: f64) -> f64 {
    2.0 * SQRT_2 * (ei * q / r).sqrt()
}

/// Force unit of vertical-hole buckling `(EI w_b^2)^(1/3)`, N (`ei` N.m2, `w_b` N/m); multiply by
/// [`WU_VERTICAL_SINUSOIDAL`] or [`WU_VERTICAL_HELICAL`].
pub fn vertical_force_unit(ei: f64, w_b: f64) -> f64 {
    (ei * w_b * w_b).cbrt()
}

/// Vertical hole, sinusoidal buckling after Wu et al.: `2.55 (EI w_b^2)^(1/3)` (dimensionless
/// coefficient). **\[uncertain\]** commonly quoted value (docs/theory.md, buckling).
pub const WU_VERTICAL_SINUSOIDAL: f64 = 2.55;

/// Vertical hole, helical buckling after Wu et al.: `5.55 (EI w_b^2)^(1/3)` (dimensionless
/// coefficient). **\[uncertain\]** commonly quoted value (docs/theory.md, buckling).
pub const WU_VERTICAL_HELICAL: f64 = 5.55;

/// Radial clearance below which a component is taken as unable to buckle, m.
pub const MIN_BUCKLING_CLEARANCE_M: f64 = 1e-3;

/// Fixed-point iterations of the curved-hole onset.
const ONSET_ITERATIONS: usize = 60;

/// Onset `F = phi(q(F))` with `q(F) = |g - F k|` (N): fixed point from the straight-hole value
/// `phi(|g|)`; that value if the iteration does not settle.
fn curved_onset(phi: impl Fn(f64) -> f64, g: Vec3, k: Vec3) -> f64 {
    let f0 = phi(g.norm());
    let mut f = f0;
    for _ in 0..ONSET_ITERATIONS {
        let next = phi((g - k * f).norm());
        if (next - f).abs() <= 1e-10 * next.abs().max(1.0) {
            return next;
        }
        // damped: the map's slope can approach 1 in sharp bends
        f = 0.5 * (f + next);
    }
    let last = phi((g - k * f).norm());
    if (last - f).abs() <= 1e-6 * last.abs().max(1.0) {
        last
    } else {
        f0
    }
}

/// Sinusoidal onset of a span `span_m` (m) between lateral supports (pinned: the bit face and
/// stabilizer blades), for bending stiffness `ei` (N.m2), lateral wall load `q` (N/m, >= 0) and
/// radial clearance `r` (m): the modes of docs/theory.md 7.1's `EI y'''' + F y'' + (q/r) y = 0`
/// that vanish at both supports are `sin(n pi x / L)`, `n = 1, 2, ...`, each needing
/// `F_n = EI k_n^2 + q / (r k_n^2)`, `k_n = n pi / L`; the onset is the smallest, N. It is
/// the Euler load `pi^2 EI / L^2` when `q = 0`, tends to Dawson-Paslay `2 sqrt(EI q / r)` for
/// a long span, and is never below either.
pub fn span_sinusoidal_onset(ei: f64, q: f64, r: f64, span_m: f64) -> f64 {
    let f = |n: f64| {
        let k = n * std::f64::consts::PI / span_m;
        ei * k * k + q / (r * k * k)
    };
    // F_n is convex in k^2: the best integer n is next to the continuous optimum
    let n_star = (q / (r * ei)).powf(0.25) * span_m / std::f64::consts::PI;
    let lo = n_star.floor().max(1.0);
    f(lo).min(f(lo + 1.0))
}

/// Length of the span between lateral supports (the bit face and the stabilizers' blade
/// centres) that holds the point `s_m` m above the bit of `string`, m; `None` above the
/// highest stabilizer (no support above: the string there is a long column on the wall).
pub fn support_span_m(string: &DrillString, s_m: f64) -> Option<f64> {
    let mut supports = string.stabilizer_contacts_m();
    supports.push(0.0);
    supports.sort_by(f64::total_cmp);
    supports
        .windows(2)
        .find(|w| s_m >= w[0] && s_m <= w[1])
        .map(|w| w[1] - w[0])
}

/// Sinusoidal and helical onsets (N) of component `c` at `md_m` on `path`, hole diameter
/// `hole_diameter_m`, mud `mud_density_kg_m3`, in a span of `span_m` between supports (None: no
/// support above, see [`support_span_m`]); None where it cannot buckle. In a span the
/// sinusoidal onset is [`span_sinusoidal_onset`] with the curved-hole wall load (never below
/// the unsupported value), and the helical onset is not below it **\[uncertain: docs/theory.md 7.3 has
/// no helical form for a supported span; a helix cannot form before the sinusoid]**.
pub fn onset_at(
    c: &Component,
    path: &WellPath,
    md_m: f64,
    hole_diameter_m: f64,
    mud_density_kg_m3: f64,
    span_m: Option<f64>,
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
    let mut s = curved_onset(|q| dawson_paslay(ei, q, r), g, k);
    let mut h = curved_onset(|q| chen_lin_cheatham(ei, q, r), g, k);
    if let Some(l) = span_m.filter(|l| *l > 0.0) {
        s = s.max(curved_onset(|q| span_sinusoidal_onset(ei, q, r, l), g, k));
        h = h.max(s);
    }
    Some((s.max(WU_VERTICAL_SINUSOIDAL * unit), h.max(WU_VERTICAL_HELICAL * unit)))
}

/// Mitchell's (1988) helical contact force per length of component `c` in a hole of
/// `hole_diameter_m` under the compression `compression_n`: `r F^2 / (4 EI)`, N/m.
pub fn mitchell_wall_force(c: &Component, hole_diameter_m: f64, compression_n: f64) -> f64 {
    let r = (hole_diameter_m - c.body_od_m) / 2.0;
    r * compression_n * compression_n / (4.0 * c.ei_nm2())
}

/// Runs of consecutive `marks` beyond the helical onset ([`BuckleState::Helical`]), as index
/// ranges (inclusive) in the marks' order.
pub fn helical_runs(marks: &[Mark]) -> Vec<(usize, usize)> {
    let mut runs = Vec::new();
    let mut first: Option<usize> = None;
    for i in 0..=marks.len() {
        let helical = marks.get(i).is_some_and(|m| m.state == BuckleState::Helical);
        match (helical, first) {
            (true, None) => first = Some(i),
            (false, Some(a)) => {
                runs.push((a, i - 1));
                first = None;
            }
            _ => {}
        }
    }
    runs
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
            let span = support_span_m(string, s);
            match onset_at(c, path, md, hole.diameter_at(md), mud_density_kg_m3, span) {
                None => Mark {
                    md_m: md,
                    compression_n: compression,
                    sinusoidal_n: None,
                    helical_n: None,
                    state: BuckleState::NotApplicable,
                    helical_wall_force_n_per_m: None,
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
                    helical_wall_force_n_per_m: Some(if compression > fh {
                        mitchell_wall_force(c, hole.diameter_at(md), compression)
                    } else {
                        0.0
                    }),
                },
            }
        })
        .collect()
}

/// Shortest run of stiff nodes beyond the helical onset checked by [`unbuckled_helical_runs`], m.
pub const MIN_HELICAL_RUN_M: f64 = 10.0;

/// Spread of the wall contact angles (deg) below which a run beyond the helical onset is taken
/// as unbuckled: a helix turns its contact once round the wall every pitch.
pub const UNBUCKLED_SPREAD_DEG: f64 = 60.0;

/// The runs (upper and lower MD, m) of the stiff model's nodes `nodes` whose `marks` say helical
/// (compression beyond the helical onset) over at least [`MIN_HELICAL_RUN_M`], where the solved
/// string lies unbuckled: its wall contacts stay within [`UNBUCKLED_SPREAD_DEG`] of one another
/// (or it touches nowhere). The static solve can converge to the straight string on one side of
/// the hole, an equilibrium past its stability limit, and then misses the helix's wall force
/// (Mitchell's `r F^2 / (4 EI)`) and its drag.
pub fn unbuckled_helical_runs(marks: &[Mark], nodes: &[crate::models::fem::results::NodeResult]) -> Vec<(f64, f64)> {
    let mut out = Vec::new();
    let mut run: Vec<usize> = Vec::new();
    let flush = |run: &mut Vec<usize>, out: &mut Vec<(f64, f64)>| {
        if let (Some(&a), Some(&b)) = (run.first(), run.last()) {
            let (top, bottom) = (marks[a].md_m.min(marks[b].md_m), marks[a].md_m.max(marks[b].md_m));
            let angles: Vec<f64> = run
                .iter()
                .filter(|&&i| nodes[i].contact_force_n > 1.0)
                .map(|&i| nodes[i].contact_angle_deg)
                .collect();
            if bottom - top >= MIN_HELICAL_RUN_M && circular_spread_deg(&angles) < UNBUCKLED_SPREAD_DEG {
                out.push((top, bottom));
            }
        }
        run.clear();
    };
    for (i, m) in marks.iter().enumerate().take(nodes.len()) {
        if m.state == BuckleState::Helical {
            run.push(i);
        } else {
            flush(&mut run, &mut out);
        }
    }
    flush(&mut run, &mut out);
    out
}

/// The smallest arc (deg) holding every angle of `angles` (deg); 0 for none or one.
fn circular_spread_deg(angles: &[f64]) -> f64 {
    let mut a: Vec<f64> = angles.iter().map(|x| x.rem_euclid(360.0)).collect();
    if a.len() < 2 {
        return 0.0;
    }
    a.sort_by(f64::total_cmp);
    let largest_gap = a
        .windows(2)
        .map(|w| w[1] - w[0])
        .chain(std::iter::once(360.0 - a[a.len() - 1] + a[0]))
        .fold(0.0, f64::max);
    360.0 - largest_gap
}

/// Marks at the nodes of a stiff solve of `case`: the results `nodes` (bit first, possibly
/// fewer than the mesh's) on the mesh of `model`.
pub fn stiff_marks(
    case: &crate::case::Case,
    model: &crate::models::fem::model::Model,
    nodes: &[crate::models::fem::results::NodeResult],
) -> Vec<Mark> {
    marks(
        nodes
            .iter()
            .zip(&model.mesh.nodes)
            .map(|(n, m)| (n.md_m, m.s_m, n.axial_force_n)),
        &case.string,
        &case.well.path,
        &case.well.hole,
        case.mud.density_kg_m3,
    )
}

/// Marks at the points of the soft-string result `soft` of `case`, from point `skip` on.
pub fn soft_marks(
    case: &crate::case::Case,
    soft: &crate::models::softstring::SoftStringResult,
    skip: usize,
) -> Vec<Mark> {
    let bit = case.operation.bit_md_m;
    marks(
        soft.points[skip..].iter().map(|p| (p.md_m, bit - p.md_m, p.tension_n)),
        &case.string,
        &case.well.path,
        &case.well.hole,
        case.mud.density_kg_m3,
    )
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

/// Buckled lengths and zones along a string, from its marks.
#[derive(Debug, Clone, PartialEq)]
pub struct BucklingSummary {
    /// Length where the compression exceeds the sinusoidal onset (helical included), m: the
    /// tributary lengths of the marks (half the distance to each neighbour) added up.
    pub sinusoidal_length_m: f64,
    /// Length where the compression exceeds the helical onset, m.
    pub helical_length_m: f64,
    /// Largest effective compression, N (0 when all in tension).
    pub max_compression_n: f64,
    /// The buckled zones ([`zones`]).
    pub zones: Vec<Zone>,
}

/// Total helical contact force of `marks` (nodes in order along the string), N: Mitchell's
/// force per length ([`Mark::helical_wall_force_n_per_m`]) times each mark's tributary length,
/// summed; the wall force the helix adds over the helically buckled intervals.
pub fn helical_wall_force_n(marks: &[Mark]) -> f64 {
    marks
        .iter()
        .zip(tributary(marks))
        .map(|(m, l)| m.helical_wall_force_n_per_m.unwrap_or(0.0) * l)
        .sum()
}

/// Tributary length (m) of each mark along the string: half the distance to each neighbour.
pub fn tributary(marks: &[Mark]) -> Vec<f64> {
    (0..marks.len())
        .map(|i| {
            let lo = if i > 0 {
                (marks[i].md_m - marks[i - 1].md_m).abs()
            } else {
                0.0
            };
            let up = if i + 1 < marks.len() {
                (marks[i + 1].md_m - marks[i].md_m).abs()
            } else {
                0.0
            };
            0.5 * (lo + up)
        })
        .collect()
}

/// Buckled lengths, largest compression and zones of `marks` (in order along the string).
pub fn summarize(marks: &[Mark]) -> BucklingSummary {
    let mut sinusoidal_length_m = 0.0;
    let mut helical_length_m = 0.0;
    for (m, l) in marks.iter().zip(tributary(marks)) {
        match m.state {
            BuckleState::Sinusoidal => sinusoidal_length_m += l,
            BuckleState::Helical => {
                sinusoidal_length_m += l;
                helical_length_m += l;
            }
            _ => {}
        }
    }
    BucklingSummary {
        sinusoidal_length_m,
        helical_length_m,
        max_compression_n: marks.iter().map(|m| m.compression_n).fold(0.0, f64::max),
        zones: zones(marks),
    }
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
    use crate::geometry::{HoleSize, Station, Survey};
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
            contact_length_m: 0.0,
            id_m: id,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: m,
            weight_air_n_per_m: 29.0 * crate::units::G,
            sensor_to_bit_m: None,
            bend: None,
            rss: None,
        }
    }

    fn path(st: &[(f64, f64, f64)]) -> WellPath {
        let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
        WellPath::new(&s, Vec3::zeros()).unwrap()
    }

    /// Reference: Dawson & Paslay and Chen-Lin-Cheatham (analytical::buckling, docs/theory.md 7.1)
    /// in a straight hole at 45 and 90 deg; tolerance 1e-12 relative.
    #[test]
    fn straight_hole_onsets_are_dawson_paslay_and_clc() {
        let c = pipe();
        let d = 8.5 * 0.0254;
        let r = (d - c.body_od_m) / 2.0;
        let w_b = c.buoyed_weight_n_per_m(1200.0);
        for inc in [45.0_f64, 90.0] {
            let p = path(&[(0.0, inc, 10.0), (1000.0, inc, 10.0)]);
            let (s, h) = onset_at(&c, &p, 500.0, d, 1200.0, None).unwrap();
            let s_ref = sinusoidal_dawson_paslay(c.ei_nm2(), w_b, inc.to_radians(), r).unwrap();
            let h_ref = helical_chen_lin_cheatham(c.ei_nm2(), w_b, inc.to_radians(), r).unwrap();
            assert!((s / s_ref - 1.0).abs() < 1e-12, "{s} {s_ref}");
            assert!((h / h_ref - 1.0).abs() < 1e-12);
        }
    }

    /// Reference: the vertical-hole floor 2.55 / 5.55 (EI w_b^2)^(1/3) (docs/theory.md 7.1) in a
    /// vertical hole; and the curvature term: a build raises, a drop lowers the onset relative
    /// to the straight hole at the same inclination, and the fixed point satisfies its own
    /// equation to 1e-9.
    #[test]
    fn vertical_floor_and_curved_hole_form() {
        let c = pipe();
        let d = 8.5 * 0.0254;
        let w_b = c.buoyed_weight_n_per_m(1200.0);
        let v = path(&[(0.0, 0.0, 0.0), (1000.0, 0.0, 0.0)]);
        let (s, h) = onset_at(&c, &v, 500.0, d, 1200.0, None).unwrap();
        let u = vertical_force_unit(c.ei_nm2(), w_b);
        assert!((s / (WU_VERTICAL_SINUSOIDAL * u) - 1.0).abs() < 1e-12);
        assert!((h / (WU_VERTICAL_HELICAL * u) - 1.0).abs() < 1e-12);
        let straight = path(&[(0.0, 45.0, 0.0), (1000.0, 45.0, 0.0)]);
        let build = path(&[(0.0, 40.0, 0.0), (100.0, 50.0, 0.0)]);
        let drop = path(&[(0.0, 50.0, 0.0), (100.0, 40.0, 0.0)]);
        let s0 = onset_at(&c, &straight, 50.0, d, 1200.0, None).unwrap().0;
        let sb = onset_at(&c, &build, 50.0, d, 1200.0, None).unwrap().0;
        let sd = onset_at(&c, &drop, 50.0, d, 1200.0, None).unwrap().0;
        assert!(sb > s0 * 1.05 && sd < s0 * 0.95, "build {sb}, straight {s0}, drop {sd}");
        let p = build.point_at(50.0);
        let g = (Vec3::new(0.0, 0.0, 1.0) - p.tangent * p.tangent.z) * w_b;
        let r = (d - c.body_od_m) / 2.0;
        let q = (g - p.dt_ds * sb).norm();
        assert!((2.0 * (c.ei_nm2() * q / r).sqrt() / sb - 1.0).abs() < 1e-9);
    }

    /// Reference: hand-made marks: zones are the contiguous buckled runs, helical wins.
    #[test]
    fn circular_spread_spans_the_smallest_arc() {
        assert_eq!(circular_spread_deg(&[]), 0.0);
        assert_eq!(circular_spread_deg(&[170.0, 190.0, 180.0]), 20.0);
        assert_eq!(circular_spread_deg(&[350.0, 10.0]), 20.0);
        assert!((circular_spread_deg(&[0.0, 90.0, 180.0, 270.0]) - 270.0).abs() < 1e-12);
    }

    #[test]
    fn helical_wall_force_sums_mitchell_over_the_tributary_lengths() {
        // Reference: a uniform force per length w over marks every 2 m from 100 to 90 m MD, the
        // end marks with half a spacing: the total is w times the 10 m they span (1e-12); marks
        // without the helix (0 or None) add nothing.
        let mk = |md: f64, w: Option<f64>| Mark {
            md_m: md,
            compression_n: 1.0,
            sinusoidal_n: None,
            helical_n: None,
            state: BuckleState::None,
            helical_wall_force_n_per_m: w,
        };
        let uniform: Vec<Mark> = (0..6).map(|k| mk(100.0 - 2.0 * k as f64, Some(250.0))).collect();
        assert!((helical_wall_force_n(&uniform) - 2500.0).abs() < 1e-9);
        let mut part = uniform.clone();
        part.extend([mk(88.0, Some(0.0)), mk(86.0, None)]);
        // with the two marks below, the mark at 90 m has a full 2 m tributary length, half of it
        // beside the mark at 0
        assert!((helical_wall_force_n(&part) - 2750.0).abs() < 1e-9);
    }

    #[test]
    fn zones_group_contiguous_runs() {
        let mk = |md: f64, st: BuckleState, c: f64| Mark {
            md_m: md,
            compression_n: c,
            sinusoidal_n: Some(100.0),
            helical_n: Some(141.0),
            state: st,
            helical_wall_force_n_per_m: None,
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
    /// 7 in x 2.8125 in steel collar, weight from its section (7850 kg/m3).
    fn collar(kind: ComponentKind, bottom: f64, len: f64) -> Component {
        let (od, id): (f64, f64) = (7.0 * 0.0254, 2.8125 * 0.0254);
        let area = std::f64::consts::PI / 4.0 * (od * od - id * id);
        Component {
            kind,
            name: kind.name().into(),
            length_m: len,
            bottom_m: bottom,
            body_od_m: od,
            contact_od_m: if kind == ComponentKind::Stabilizer {
                8.4375 * 0.0254
            } else {
                od
            },
            contact_length_m: 0.0,
            id_m: id,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: steel(),
            weight_air_n_per_m: area * 7850.0 * crate::units::G,
            sensor_to_bit_m: None,
            bend: None,
            rss: None,
        }
    }

    /// Reference, by hand (7 in x 2.8125 in collar, 1.2 sg, 8.5 in hole, I = 20 deg, straight):
    /// EI = 9.89007e6 N.m2, w_b = 1357.79 N/m, r = 19.05 mm, q = w_b sin I = 464.393 N/m;
    /// Dawson-Paslay 2 sqrt(EI q / r) = 982.03 kN. Span L = 10.7 m between stabilizers: the
    /// optimum n* = (q/(r EI))^(1/4) L / pi = 0.759 -> n = 1, F_1 = pi^2 EI / L^2 + q L^2 /
    /// (r pi^2) = 852.57 + 282.79 = 1135.36 kN. Span 60 m: n* = 4.26, F_4 = 989.57 kN (F_5 =
    /// 1033.6). q = 0 (vertical): the Euler load 852.57 kN. Tolerance 0.01 kN.
    #[test]
    fn span_onset_matches_hand_computation() {
        let c = collar(ComponentKind::Collar, 0.0, 100.0);
        let (ei, w_b) = (c.ei_nm2(), c.buoyed_weight_n_per_m(1200.0));
        let r = (8.5 - 7.0) * 0.0254 / 2.0;
        assert!(
            (ei / 9.89007e6 - 1.0).abs() < 1e-6 && (w_b - 1357.79).abs() < 0.01,
            "{ei} {w_b}"
        );
        let q = w_b * 20f64.to_radians().sin();
        let kn = |f: f64| f / 1e3;
        assert!((kn(span_sinusoidal_onset(ei, q, r, 10.7)) - 1135.36).abs() < 0.01);
        assert!((kn(span_sinusoidal_onset(ei, q, r, 60.0)) - 989.57).abs() < 0.01);
        assert!((kn(span_sinusoidal_onset(ei, 0.0, r, 10.7)) - 852.57).abs() < 0.01);
        // through onset_at: the span raises the sinusoidal onset; the helical one stays CLC
        // (2 sqrt(2) sqrt(EI q / r) = 1388.80 kN, above the span's sinusoidal onset)
        let p = path(&[(0.0, 20.0, 0.0), (1000.0, 20.0, 0.0)]);
        let d = 8.5 * 0.0254;
        let (s, h) = onset_at(&c, &p, 500.0, d, 1200.0, Some(10.7)).unwrap();
        assert!(
            (kn(s) - 1135.36).abs() < 0.01 && (kn(h) - 1388.80).abs() < 0.01,
            "{s} {h}"
        );
        let (s, _) = onset_at(&c, &p, 500.0, d, 1200.0, None).unwrap();
        assert!((kn(s) - 982.03).abs() < 0.01, "{s}");
    }

    /// Reference, by hand: in a plane build of curvature kappa the wall load is w_b sin I + F
    /// kappa, and F = 2 sqrt(EI q(F) / r) solves to F = (2 EI kappa / r)(1 + sqrt(1 + r w_b sin
    /// I / (EI kappa^2))) (Dawson-Paslay with the curved-hole wall load); in a drop
    /// q = w_b sin I - F kappa gives F = (2 EI kappa / r)(sqrt(1 + r w_b sin I / (EI kappa^2)) -
    /// 1). 5 in pipe (29 kg/m, 1.2 sg, 8.5 in hole: EI = 1.22943e6 N.m2, w_b = 240.919 N/m, r =
    /// 44.45 mm), I = 45 deg, kappa = 10 deg/100 m: build 264.38 kN, drop 71.29 kN, straight
    /// 137.29 kN. Tolerance 0.01 kN.
    #[test]
    fn curved_hole_onset_matches_hand_computation() {
        let c = pipe();
        let d = 8.5 * 0.0254;
        let build = path(&[(0.0, 40.0, 0.0), (100.0, 50.0, 0.0)]);
        let drop = path(&[(0.0, 50.0, 0.0), (100.0, 40.0, 0.0)]);
        let sb = onset_at(&c, &build, 50.0, d, 1200.0, None).unwrap().0;
        let sd = onset_at(&c, &drop, 50.0, d, 1200.0, None).unwrap().0;
        assert!((sb / 1e3 - 264.38).abs() < 0.01, "{sb}");
        assert!((sd / 1e3 - 71.29).abs() < 0.01, "{sd}");
    }

    /// Reference, by hand: bit 0.3 m, near-bit stabilizer 1.6 m (centre 1.1 m), collar 9.1 m,
    /// stabilizer 1.6 m (centre 11.8 m), collar 9.1 m, stabilizer 1.6 m (centre 22.5 m), collars
    /// above: spans 1.1, 10.7, 10.7 m, none above 22.5 m. A compression of 1000 kN in a
    /// straight 20 deg hole is above Dawson-Paslay (982.03 kN) but below the 10.7 m span's
    /// onset (1135.36 kN): not buckled at 6 m above the bit (between stabilizers), buckled at
    /// 40 m (above the top stabilizer).
    #[test]
    fn stabilizers_are_supports_of_the_bha() {
        use ComponentKind::{Bit, Collar, Stabilizer};
        let parts = [
            (Bit, 0.3),
            (Stabilizer, 1.6),
            (Collar, 9.1),
            (Stabilizer, 1.6),
            (Collar, 9.1),
            (Stabilizer, 1.6),
            (Collar, 100.0),
        ];
        let mut bottom = 0.0;
        let mut components = Vec::new();
        for (k, l) in parts {
            components.push(collar(k, bottom, l));
            bottom += l;
        }
        let string = DrillString { components };
        let near = |a: Option<f64>, b: f64| a.is_some_and(|a| (a - b).abs() < 1e-9);
        assert!(near(support_span_m(&string, 0.5), 1.1));
        assert!(near(support_span_m(&string, 6.0), 10.7));
        assert!(near(support_span_m(&string, 15.0), 10.7));
        assert_eq!(support_span_m(&string, 40.0), None);
        let p = path(&[(0.0, 20.0, 0.0), (1000.0, 20.0, 0.0)]);
        let hole = HoleSize::uniform(8.5 * 0.0254);
        let bit_md = 500.0;
        let m = marks(
            [(bit_md - 6.0, 6.0, -1000e3), (bit_md - 40.0, 40.0, -1000e3)],
            &string,
            &p,
            &hole,
            1200.0,
        );
        assert_eq!(m[0].state, BuckleState::None, "{:?}", m[0]);
        assert!((m[0].sinusoidal_n.unwrap() / 1e3 - 1135.36).abs() < 0.01);
        assert_eq!(m[1].state, BuckleState::Sinusoidal, "{:?}", m[1]);
    }
}
