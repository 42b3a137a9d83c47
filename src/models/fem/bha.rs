//! The bottom-hole-assembly model (`bha` fidelity): the stiff string from the bit up to a cut
//! where it lies steadily on the wall, held there on the wall and parallel to the hole
//! ([`TopCondition::Cut`]). Bit forces and tilt depend on the string within a few contact spans
//! of the last stabilizer only, so this model gives them at a fraction of the whole string's
//! cost; hook load and surface torque need the whole string.
//!
//! Cut rule (documented default): `s_cut = s_stab + 6 L_t`, where `s_stab` is the distance from
//! the bit to the highest stabilizer (0 without one) and `L_t = (24 EI r / (w sin I))^(1/4)` is
//! Lubinski's tangency length of the component above it (docs/theory.md 9.2; inclination at least
//! 5 deg in the formula so a vertical hole gets a finite length), clamped to
//! [[`MIN_CUT_M`], [`MAX_CUT_M`]] and to the string length.

use super::model::{Model, TopCondition};
use crate::case::Case;
use crate::geometry::{HoleSize, Vec3, WellPath};
use crate::string::{Component, DrillString};

/// Shortest cut, m from the bit.
pub const MIN_CUT_M: f64 = 30.0;
/// Longest cut, m from the bit.
pub const MAX_CUT_M: f64 = 250.0;
/// Tangency lengths kept above the highest stabilizer.
pub const TANGENCY_LENGTHS_ABOVE: f64 = 6.0;
/// Lateral load per length (as a fraction of the buoyed weight) below which the cut node is
/// centred instead of lying on the wall (a near-vertical straight hole); linear in between.
pub const CENTRED_LOAD_FRACTION: f64 = 0.02;

/// Lubinski's tangency length `L_t = (24 EI r / (w_b sin I))^(1/4)` of component `c`, m, in a
/// hole of diameter `hole_diameter_m` (m) at inclination `inc_rad` (rad; at least 5 deg in the
/// formula) in mud of density `mud_density_kg_m3` (kg/m3); `r` is the radial clearance of its
/// contact OD (at least 1 mm), `w_b` its buoyed weight per length (at least 1 N/m).
pub fn tangency_length_m(c: &Component, hole_diameter_m: f64, inc_rad: f64, mud_density_kg_m3: f64) -> f64 {
    let w = c.buoyed_weight_n_per_m(mud_density_kg_m3).abs().max(1.0);
    let r = ((hole_diameter_m - c.contact_od_m) / 2.0).max(1e-3);
    let sin_i = inc_rad.sin().abs().max(5f64.to_radians().sin());
    (24.0 * c.ei_nm2() * r / (w * sin_i)).powf(0.25)
}

/// Default cut distance from the bit, m, for `string` in a hole of diameter `hole_diameter_m`
/// at inclination `inc_rad`.
pub fn default_cut_m(string: &DrillString, hole_diameter_m: f64, inc_rad: f64, mud_density_kg_m3: f64) -> f64 {
    let s_stab = string.stabilizer_contacts_m().into_iter().fold(0.0, f64::max);
    // the component above the highest stabilizer (the bit when there is none)
    let top_of_stab = string
        .components
        .iter()
        .filter(|c| c.kind == crate::string::ComponentKind::Stabilizer)
        .map(|c| c.top_m())
        .fold(0.0, f64::max);
    let above = string.component_at(top_of_stab + 1e-6);
    let lt = tangency_length_m(above, hole_diameter_m, inc_rad, mud_density_kg_m3);
    (s_stab + TANGENCY_LENGTHS_ABOVE * lt)
        .clamp(MIN_CUT_M, MAX_CUT_M)
        .min(string.length_m())
}

/// Whether a cut `cut_m` (m) above the bit keeps the whole of `string` ([`bha_model`] then
/// builds the whole string, held at the surface).
pub fn cut_is_whole(string: &DrillString, cut_m: f64) -> bool {
    cut_m >= string.length_m() - 1e-6
}

/// The cut model of `case`'s string with the bit at `bit_md_m` in the hole `path`/`hole`, cut
/// `cut_m` above the bit (the whole string, held at the surface, if it is not longer).
pub fn bha_model(case: &Case, path: &WellPath, hole: &HoleSize, bit_md_m: f64, cut_m: f64) -> Model {
    let whole = cut_is_whole(&case.string, cut_m);
    let string = if whole {
        case.string.clone()
    } else {
        case.string.truncated(cut_m)
    };
    let mut model = Model::for_string(case, &string, path, hole, bit_md_m);
    if !whole {
        model.top = TopCondition::Cut {
            offset_m: resting_offset(&model),
        };
    }
    model
}

/// Where the string rests at the model's top node: the soft-string lateral load
/// `T dt/ds + w (e_z - t t_z)` (axial force `T` integrated from the bit without friction)
/// pushes it against the wall on that side; centred when that load is negligible.
pub fn resting_offset(model: &Model) -> Vec3 {
    let nn = model.nodes();
    let mut tension = -model.loads.wob_n;
    for e in 0..nn - 1 {
        let t = model
            .path
            .axis_at(0.5 * (model.md_ref[e] + model.md_ref[e + 1]))
            .tangent;
        tension += model.mesh.elements[e].buoyed_weight_n_per_m * model.sections[e].l0 * t.z;
    }
    let top = nn - 1;
    let p = model.path.axis_at(model.md_ref[top]);
    let w = model.mesh.elements[nn - 2].buoyed_weight_n_per_m;
    let ez = Vec3::new(0.0, 0.0, 1.0);
    let load = p.dt_ds * tension + (ez - p.tangent * p.tangent.z) * w;
    let n = load.norm();
    let reference = CENTRED_LOAD_FRACTION * w.abs().max(1e-9);
    if n < 1e-12 {
        return Vec3::zeros();
    }
    let clearance = ((model.hole.diameter_at(model.md_ref[top]) - model.mesh.nodes[top].contact_od_m) / 2.0).max(0.0);
    load / n * clearance * (n / reference).min(1.0)
}
