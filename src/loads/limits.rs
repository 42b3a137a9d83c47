//! Limit curves of the torque-and-drag chart: buckling onset along the string and pipe-body
//! yield limits.
//!
//! **Buckling**: the onsets of [`crate::models::buckling::onset_at`] (the same as `solve`'s
//! buckling marks): Dawson & Paslay (1984) sinusoidal and Chen, Lin & Cheatham (1990) helical
//! with the curved-hole wall load `q(F) = |w_b (e_D - t t_D) - F dt/ds|` (curvature raises the
//! onset in a build and lowers it in a drop), the vertical-hole floors `2.55 / 5.55 (EI
//! w_b^2)^(1/3)` \[uncertain coefficients, docs/theory.md 7.1], and in the bottom-hole assembly the
//! span between stabilizers as a supported column ([`crate::models::buckling::span_sinusoidal_onset`]).
//! The clearance uses the body OD (tool joints make `r` ambiguous, docs/theory.md 7.1); components
//! with less than [`MIN_BUCKLING_CLEARANCE_M`] of clearance (bit, gauge stabilizers) are taken
//! as unable to buckle. The buckled length is the length where the soft-string effective
//! compression exceeds the onset, interpolated linearly inside an element.
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
//! (docs/theory.md 3.3, `p` the hydrostatic pressure at the point); at the surface `F_true = F_eff`.
//! Bending stress, internal/external pressure stresses and wear are not included: these are
//! body limits of new pipe, not a design check.

use crate::geometry::{HoleSize, WellPath};
pub use crate::models::buckling::MIN_BUCKLING_CLEARANCE_M;
use crate::models::buckling::{onset_at, support_span_m};
use crate::models::softstring::SoftStringResult;
use crate::string::{Component, DrillString};
use crate::units::G;

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
    for w in res.points.windows(2) {
        let (lo, up) = (&w[0], &w[1]);
        let dl = lo.md_m - up.md_m;
        let (c_lo, c_up) = (-lo.tension_n, -up.tension_n);
        out.max_compression_n = out.max_compression_n.max(c_lo).max(c_up);
        if dl > 0.0 && (c_lo > 0.0 || c_up > 0.0) {
            let mid = bit_md_m - 0.5 * (lo.md_m + up.md_m);
            let comp = string.component_at(mid.max(0.0));
            // the span of the element's middle (an element does not straddle a stabilizer
            // centre by more than its length)
            let span = support_span_m(string, mid.max(0.0));
            let onset = |md: f64| onset_at(comp, path, md, hole.diameter_at(md), mud_density_kg_m3, span);
            if let (Some((s_lo, h_lo)), Some((s_up, h_up))) = (onset(lo.md_m), onset(up.md_m)) {
                out.sinusoidal_length_m += positive_length(c_lo - s_lo, c_up - s_up, dl);
                out.helical_length_m += positive_length(c_lo - h_lo, c_up - h_up, dl);
                out.max_sinusoidal_ratio = out.max_sinusoidal_ratio.max(c_lo / s_lo).max(c_up / s_up);
            }
        }
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
            contact_length_m: 0.0,
            id_m: 4.276 * 0.0254,
            tool_joint_od_m: None,
            joint_length_m: 9.144,
            material: m,
            weight_air_n_per_m: 29.0 * G,
            sensor_to_bit_m: None,
            bend: None,
            rss: None,
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

    fn path(st: &[(f64, f64, f64)]) -> WellPath {
        use crate::geometry::{Station, Survey, Vec3};
        let s = Survey::new(st.iter().map(|&(m, i, a)| Station::from_deg(m, i, a)).collect()).unwrap();
        WellPath::new(&s, Vec3::zeros()).unwrap()
    }

    /// Reference: docs/theory.md 7.1 (5 in pipe, 29 kg/m, 1.2 sg, 8.5 in hole): I = 45 deg
    /// F_s = 137.3 kN, F_h (CLC) = 194.1 kN; vertical: 2.55 / 5.55 (EI w_b^2)^(1/3) = 10.58 /
    /// 23.02 kN. Tolerance 0.1 kN (printed digits). The chart's onset is `onset_at` of
    /// models::buckling, in a straight hole without supports.
    #[test]
    fn onset_inclined_and_vertical() {
        let c = pipe();
        let hole = 8.5 * 0.0254;
        let inclined = path(&[(0.0, 45.0, 0.0), (1000.0, 45.0, 0.0)]);
        let (s, h) = onset_at(&c, &inclined, 500.0, hole, 1200.0, None).unwrap();
        assert!((s / 1e3 - 137.3).abs() < 0.1, "{s}");
        assert!((h / 1e3 - 194.1).abs() < 0.1, "{h}");
        let vertical = path(&[(0.0, 0.0, 0.0), (1000.0, 0.0, 0.0)]);
        let (s, h) = onset_at(&c, &vertical, 500.0, hole, 1200.0, None).unwrap();
        assert!((s / 1e3 - 10.58).abs() < 0.01, "{s}");
        assert!((h / 1e3 - 23.02).abs() < 0.01, "{h}");
        assert!(onset_at(&c, &inclined, 500.0, c.body_od_m + 1e-4, 1200.0, None).is_none());
    }

    /// Reference, by hand (models::buckling's curved-hole form, its test gives the numbers): 5 in
    /// pipe at I = 45 deg in 8.5 in hole, onset 137.29 kN straight, 264.38 kN in a 10 deg/100 m
    /// build, 71.29 kN in the same drop. A constant compression of 200 kN over the 20 m from
    /// 60 m up to 40 m is buckled over all 20 m in the straight hole and the drop, over none in
    /// the build (the straight-hole onset would have said 20 m).
    #[test]
    fn chart_buckling_includes_hole_curvature() {
        use crate::geometry::Vec3;
        use crate::models::softstring::SoftStringPoint;
        let string = DrillString {
            components: vec![pipe()],
        };
        let hole = HoleSize::uniform(8.5 * 0.0254);
        let res = SoftStringResult {
            hook_load_n: 0.0,
            surface_torque_nm: 0.0,
            points: (0..=20)
                .map(|k| SoftStringPoint {
                    md_m: 60.0 - k as f64,
                    tension_n: -200e3,
                    torque_nm: 0.0,
                    normal_force_per_m: 0.0,
                    normal_dir: Vec3::zeros(),
                })
                .collect(),
            frictionless: false,
        };
        let len = |p: &WellPath| buckling_along(&res, &string, p, &hole, 60.0, 1200.0).sinusoidal_length_m;
        let straight = path(&[(0.0, 45.0, 0.0), (100.0, 45.0, 0.0)]);
        let build = path(&[(0.0, 40.0, 0.0), (100.0, 50.0, 0.0)]);
        let drop = path(&[(0.0, 50.0, 0.0), (100.0, 40.0, 0.0)]);
        assert!((len(&straight) - 20.0).abs() < 1e-9, "{}", len(&straight));
        assert!((len(&drop) - 20.0).abs() < 1e-9, "{}", len(&drop));
        assert_eq!(len(&build), 0.0);
    }

    #[test]
    fn positive_length_interpolates() {
        assert_eq!(positive_length(1.0, 1.0, 2.0), 2.0);
        assert_eq!(positive_length(-1.0, -1.0, 2.0), 0.0);
        assert!((positive_length(1.0, -3.0, 2.0) - 0.5).abs() < 1e-15);
        assert!((positive_length(-3.0, 1.0, 2.0) - 0.5).abs() < 1e-15);
    }
}
