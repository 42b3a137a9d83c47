//! Limit curves of the torque-and-drag chart: buckling onset along the string and pipe-body
//! yield limits.
//!
//! **Buckling** (physics.md 6.4; forces are effective compressions, N). For a component of
//! bending stiffness `EI`, buoyed weight `w_b` and radial clearance `r = (D_hole - D_body)/2`
//! at inclination `I`:
//!
//! ```text
//! sinusoidal onset  F_s = max( 2 sqrt(EI w_b sin I / r),          Dawson & Paslay (1984)
//!                              2.55 (EI w_b^2)^(1/3) )            vertical hole (Wu et al.)
//! helical onset     F_h = max( 2 sqrt(2) sqrt(EI w_b sin I / r),  Chen, Lin & Cheatham (1990)
//!                              5.55 (EI w_b^2)^(1/3) )            vertical hole (Wu et al.)
//! ```
//!
//! The vertical-hole floor keeps the onset finite where `sin I -> 0`; its coefficients are
//! marked \[uncertain\] in physics.md 6.4. The clearance uses the body OD (tool joints make `r`
//! ambiguous, physics.md 6.4); components with less than [`MIN_BUCKLING_CLEARANCE_M`] of
//! clearance (bit, gauge stabilizers) are taken as unable to buckle. The buckled length is the
//! length where the soft-string effective compression exceeds the onset, interpolated linearly
//! inside an element. The curvature of the hole (which raises the onset in builds and lowers it
//! in drops) is not included.
//!
//! **Yield** of the pipe body (API RP 7G section 4 / API TR 5C3 minimum values of new pipe,
//! nominal dimensions; `sigma_y` the minimum yield strength, `A` the body area, `J` the polar
//! moment `pi (D^4 - d^4)/32`, `D` the body OD):
//!
//! ```text
//! tension yield            P_y = sigma_y A
//! torsional yield          T_y = sigma_y / sqrt(3) * 2 J / D        (RP 7G: 0.096167 J Y_m / D)
//! combined, tension P      T_y(P) = (2 J / (sqrt(3) D)) sqrt(sigma_y^2 - (P/A)^2)
//!                          i.e. von Mises  (P/A)^2 + 3 tau^2 = sigma_y^2 with tau = T D / (2J)
//! ```
//!
//! `P` is the true axial force, `F_true = F_eff - p A` for the same mud inside and outside
//! (physics.md 2.2, `p` the hydrostatic pressure at the point); at the surface `F_true = F_eff`.
//! Bending stress, internal/external pressure stresses and wear are not included: these are
//! body limits of new pipe, not a design check.

use crate::analytical::buckling::{
    helical_chen_lin_cheatham, sinusoidal_dawson_paslay, vertical_force_unit, WU_VERTICAL_HELICAL,
    WU_VERTICAL_SINUSOIDAL,
};
use crate::geometry::{HoleSize, WellPath};
use crate::softstring::SoftStringResult;
use crate::string::{Component, DrillString};
use crate::units::G;

/// Radial clearance below which a component is taken as unable to buckle, m.
pub const MIN_BUCKLING_CLEARANCE_M: f64 = 1e-3;

/// Buckling onset loads (effective compression, N) of a component at one point of the hole.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Onset {
    /// Sinusoidal (lateral) buckling onset, N.
    pub sinusoidal_n: f64,
    /// Helical buckling onset, N.
    pub helical_n: f64,
}

/// Buckling onset of `c` in mud of `mud_density_kg_m3` where the hole has diameter
/// `hole_diameter_m` and inclination `inc_rad` (see the module documentation); `None` when the
/// clearance is below [`MIN_BUCKLING_CLEARANCE_M`].
pub fn onset(c: &Component, mud_density_kg_m3: f64, hole_diameter_m: f64, inc_rad: f64) -> Option<Onset> {
    let r = (hole_diameter_m - c.body_od_m) / 2.0;
    if r.is_nan() || r < MIN_BUCKLING_CLEARANCE_M {
        return None;
    }
    let ei = c.ei_nm2();
    let w_b = c.buoyed_weight_n_per_m(mud_density_kg_m3);
    if !(ei > 0.0 && w_b > 0.0) {
        return None;
    }
    let unit = vertical_force_unit(ei, w_b);
    let s = sinusoidal_dawson_paslay(ei, w_b, inc_rad, r).unwrap_or(0.0);
    let h = helical_chen_lin_cheatham(ei, w_b, inc_rad, r).unwrap_or(0.0);
    Some(Onset {
        sinusoidal_n: s.max(WU_VERTICAL_SINUSOIDAL * unit),
        helical_n: h.max(WU_VERTICAL_HELICAL * unit),
    })
}

/// Buckling along a soft-string result.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct Buckling {
    /// Length where the compression exceeds the sinusoidal onset (helical included), m.
    pub sinusoidal_length_m: f64,
    /// Length where the compression exceeds the helical onset, m.
    pub helical_length_m: f64,
    /// Largest effective compression along the string, N (0 when all in tension).
    pub max_compression_n: f64,
    /// Largest ratio compression / sinusoidal onset along the string (0 when all in tension).
    pub max_sinusoidal_ratio: f64,
}

/// Length of an element of length `dl` where a linearly varying margin (`a` at one end, `b`
/// at the other) is positive.
fn positive_length(a: f64, b: f64, dl: f64) -> f64 {
    match (a > 0.0, b > 0.0) {
        (true, true) => dl,
        (false, false) => 0.0,
        (true, false) => dl * a / (a - b),
        (false, true) => dl * b / (b - a),
    }
}

/// Buckled lengths of the soft-string result `res` of `string` with its bit at `bit_md_m`
/// (the onset evaluated at both ends of each element, with that element's component).
pub fn buckling_along(
    res: &SoftStringResult,
    string: &DrillString,
    path: &WellPath,
    hole: &HoleSize,
    bit_md_m: f64,
    mud_density_kg_m3: f64,
) -> Buckling {
    let mut out = Buckling::default();
    let mut inc_lo = path.point_at(res.points[0].md_m).inc_rad;
    for w in res.points.windows(2) {
        let (lo, up) = (&w[0], &w[1]);
        let inc_up = path.point_at(up.md_m).inc_rad;
        let dl = lo.md_m - up.md_m;
        let (c_lo, c_up) = (-lo.tension_n, -up.tension_n);
        out.max_compression_n = out.max_compression_n.max(c_lo).max(c_up);
        if dl > 0.0 && (c_lo > 0.0 || c_up > 0.0) {
            let comp = string.component_at(bit_md_m - 0.5 * (lo.md_m + up.md_m));
            let o_lo = onset(comp, mud_density_kg_m3, hole.diameter_at(lo.md_m), inc_lo);
            let o_up = onset(comp, mud_density_kg_m3, hole.diameter_at(up.md_m), inc_up);
            if let (Some(a), Some(b)) = (o_lo, o_up) {
                out.sinusoidal_length_m += positive_length(c_lo - a.sinusoidal_n, c_up - b.sinusoidal_n, dl);
                out.helical_length_m += positive_length(c_lo - a.helical_n, c_up - b.helical_n, dl);
                out.max_sinusoidal_ratio = out
                    .max_sinusoidal_ratio
                    .max(c_lo / a.sinusoidal_n)
                    .max(c_up / b.sinusoidal_n);
            }
        }
        inc_lo = inc_up;
    }
    out
}

/// Pipe-body yield limits of a component.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YieldLimits {
    /// Tension at yield `sigma_y A`, N.
    pub tension_n: f64,
    /// Torque at yield without tension `2 J sigma_y / (sqrt(3) D)`, N.m.
    pub torque_nm: f64,
}

/// Yield limits of `c`, `None` when its material has no yield strength.
pub fn yield_limits(c: &Component) -> Option<YieldLimits> {
    let sy = c.material.yield_strength_pa?;
    let j = 2.0 * c.inertia_m4();
    Some(YieldLimits {
        tension_n: sy * c.area_m2(),
        torque_nm: 2.0 * j * sy / (3f64.sqrt() * c.body_od_m),
    })
}

/// Torque at yield of `c` under the true axial force `tension_n` (N, either sign), N.m (0 when
/// the axial stress alone reaches yield); `None` without a yield strength.
pub fn combined_torque_limit(c: &Component, tension_n: f64) -> Option<f64> {
    let sy = c.material.yield_strength_pa?;
    let sa = tension_n / c.area_m2();
    let j = 2.0 * c.inertia_m4();
    Some(2.0 * j / (3f64.sqrt() * c.body_od_m) * (sy * sy - sa * sa).max(0.0).sqrt())
}

/// Von Mises stress of axial force and torque over the yield strength,
/// `sqrt((P/A)^2 + 3 (T D / 2J)^2) / sigma_y` (dimensionless); `None` without a yield strength.
pub fn stress_ratio(c: &Component, true_tension_n: f64, torque_nm: f64) -> Option<f64> {
    let sy = c.material.yield_strength_pa?;
    let sa = true_tension_n / c.area_m2();
    let tau = torque_nm * c.body_od_m / (4.0 * c.inertia_m4());
    Some((sa * sa + 3.0 * tau * tau).sqrt() / sy)
}

/// Largest [`stress_ratio`] along a soft-string result (nodes of components with a yield
/// strength; true force `F_eff - p A`, `p = rho g (TVD - TVD_top)`), `None` if no component
/// has a yield strength.
pub fn max_stress_ratio(
    res: &SoftStringResult,
    string: &DrillString,
    path: &WellPath,
    bit_md_m: f64,
    mud_density_kg_m3: f64,
) -> Option<f64> {
    let top_md = res.points.last()?.md_m;
    let tvd_top = path.point_at(top_md).position.z;
    let mut worst: Option<f64> = None;
    let n = res.points.len();
    for (k, p) in res.points.iter().enumerate() {
        // the component just below the node (the topmost one for the top node)
        let x = if k + 1 == n {
            string.length_m() - 1e-9
        } else {
            bit_md_m - p.md_m
        };
        let c = string.component_at(x.max(0.0));
        if c.material.yield_strength_pa.is_none() {
            continue;
        }
        let pressure = mud_density_kg_m3 * G * (path.point_at(p.md_m).position.z - tvd_top);
        let f_true = p.tension_n - pressure * c.area_m2();
        if let Some(r) = stress_ratio(c, f_true, p.torque_nm) {
            worst = Some(worst.map_or(r, |w: f64| w.max(r)));
        }
    }
    worst
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::string::material::{grade_yield_strength_pa, steel};
    use crate::string::ComponentKind;

    /// 5 in 19.5 lb/ft pipe body (4.276 in ID), S-135.
    fn pipe() -> Component {
        let mut m = steel();
        m.yield_strength_pa = grade_yield_strength_pa("S-135");
        Component {
            kind: ComponentKind::Pipe,
            name: "pipe".into(),
            length_m: 100.0,
            bottom_m: 0.0,
            body_od_m: 5.0 * 0.0254,
            contact_od_m: 5.0 * 0.0254,
            id_m: 4.276 * 0.0254,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: m,
            weight_air_n_per_m: 29.0 * G,
        }
    }

    /// Reference: API RP 7G Table 2 (new pipe, 5 in 19.50 lb/ft S-135): tensile yield
    /// 712,070 lbf = 3167.4 kN, torsional yield 74,100 ft.lbf = 100.5 kN.m. Tolerance 0.5%
    /// (the table's rounding of J and A).
    #[test]
    fn api_rp7g_new_pipe_s135() {
        let y = yield_limits(&pipe()).unwrap();
        let lbf = 4.4482216152605;
        assert!((y.tension_n / (712_070.0 * lbf) - 1.0).abs() < 0.005, "{}", y.tension_n);
        let ftlbf = 0.3048 * lbf;
        assert!(
            (y.torque_nm / (74_100.0 * ftlbf) - 1.0).abs() < 0.005,
            "{}",
            y.torque_nm
        );
        // combined: zero tension gives the pure torsion limit, yield tension gives zero, and
        // the von Mises ratio is 1 on the curve
        let c = pipe();
        assert!((combined_torque_limit(&c, 0.0).unwrap() / y.torque_nm - 1.0).abs() < 1e-12);
        assert!(combined_torque_limit(&c, y.tension_n).unwrap().abs() < 1e-6);
        let p = 0.6 * y.tension_n;
        let t = combined_torque_limit(&c, p).unwrap();
        assert!((stress_ratio(&c, p, t).unwrap() - 1.0).abs() < 1e-12);
        assert!((t / y.torque_nm - 0.8).abs() < 1e-12); // sqrt(1 - 0.36)
    }

    /// Reference: physics.md 6.4 (5 in pipe, 29 kg/m, 1.2 sg, 8.5 in hole): I = 45 deg
    /// F_s = 137.3 kN, F_h (CLC) = 194.1 kN; vertical: 2.55 / 5.55 (EI w_b^2)^(1/3) = 10.58 /
    /// 23.02 kN. Tolerance 0.1 kN (printed digits).
    #[test]
    fn onset_inclined_and_vertical() {
        let c = pipe();
        let hole = 8.5 * 0.0254;
        let o = onset(&c, 1200.0, hole, 45f64.to_radians()).unwrap();
        assert!((o.sinusoidal_n / 1e3 - 137.3).abs() < 0.1, "{}", o.sinusoidal_n);
        assert!((o.helical_n / 1e3 - 194.1).abs() < 0.1, "{}", o.helical_n);
        let v = onset(&c, 1200.0, hole, 0.0).unwrap();
        assert!((v.sinusoidal_n / 1e3 - 10.58).abs() < 0.01, "{}", v.sinusoidal_n);
        assert!((v.helical_n / 1e3 - 23.02).abs() < 0.01, "{}", v.helical_n);
        assert!(onset(&c, 1200.0, c.body_od_m + 1e-4, 0.5).is_none());
    }

    #[test]
    fn positive_length_interpolates() {
        assert_eq!(positive_length(1.0, 1.0, 2.0), 2.0);
        assert_eq!(positive_length(-1.0, -1.0, 2.0), 0.0);
        assert!((positive_length(1.0, -3.0, 2.0) - 0.5).abs() < 1e-15);
        assert!((positive_length(-3.0, 1.0, 2.0) - 0.5).abs() < 1e-15);
    }
}
