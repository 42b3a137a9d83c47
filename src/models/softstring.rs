//! Soft-string torque and drag (Johancsik, Friesen & Dawson 1984; physics.md 6.5).
//!
//! The string is a cable lying on the hole axis: no bending stiffness, no clearance. It is
//! integrated element by element from the bit up. For an element with lower (deeper) end
//! `s_lo` and upper end `s_up`, length `dL`, buoyed weight `W = w_b dL`, unit tangents `t_lo`,
//! `t_up` (down the hole, from [`WellPath::point_at`]) and `tbar = (t_lo + t_up)/|t_lo + t_up|`:
//!
//! ```text
//! lateral load  G = F_lo (t_lo - t_up) + W e_D            e_D = (0, 0, 1), gravity
//! normal force  N = |G - (G.tbar) tbar|                  (force on the wall, N)
//! axial         F_up = F_lo + w_b (TVD_lo - TVD_up) - f N v_a / |v|
//! torque        M_up = M_lo + f N R_c (Omega R_c) / |v|
//!               |v| = sqrt(v_a^2 + (Omega R_c)^2)
//! ```
//!
//! The weight term `w_b (TVD_lo - TVD_up)` is the exact integral of the axial weight
//! component `w_b cos I` over the element's arc; it equals `W cos(I_bar) = W (tbar.e_D)` times
//! `sin(beta/2)/(beta/2)` (beta the element's dogleg), i.e. the two agree to `beta^2/24`
//! (1.3e-7 for 1 m elements at 3 deg/30 m). With it the hook load without axial motion is
//! `sum w_b dTVD` to round-off on any path (physics.md 6.5 exact check (a)).
//!
//! Sign conventions: tension positive (effective force, physics.md 2.2); `v_a > 0` is the
//! string moving down the hole (running in, drilling ahead), so wall friction acts up-hole and
//! reduces the tension increase going up; pulling out (`v_a < 0`) increases the hook load.
//! Torque is positive in the sense of rotation (`Omega > 0`, clockwise seen from above).
//! At the bit, `F = -WOB` (compression) and `M = T_b`.
//!
//! The shares `v_a/|v|` and `Omega R_c/|v|` are [`crate::case::Motion::friction_split`], the
//! rule every model shares; a case's speeds come from [`crate::case::Operation::motion`]
//! (sliding and tripping move in the direction the mode implies even when the case gives no
//! speed). When there is no motion at all (`v_a = 0` and `Omega = 0`, only rotating off bottom
//! at 0 rpm) the direction of friction is undetermined; the string is then treated as
//! frictionless and the result says so ([`SoftStringResult::frictionless`]).
//!
//! Not included: mud drag torque (physics.md 2.4, ~10 N.m per 1000 m, negligible), the
//! hole diameter (the cable lies on the axis), bending stiffness. See physics.md 6.6 for how
//! the stiff FEM torque differs in straight sections (factor `1/sqrt(1 + f^2)`).

use crate::case::{Case, Motion};
use crate::geometry::{HoleSize, Vec3, WellPath};
use crate::string::{Component, DrillString};

/// Inputs of a soft-string pass, SI units.
#[derive(Debug, Clone, Copy)]
pub struct SoftStringInput<'a> {
    /// Hole axis (minimum curvature).
    pub path: &'a WellPath,
    /// Hole sizes; only the per-section friction coefficients are used (they override
    /// [`SoftStringInput::friction`] where given).
    pub hole: &'a HoleSize,
    /// The string, components from the bit upward; its top is at `bit_md_m - length`.
    pub string: &'a DrillString,
    /// Mud density inside and outside the string, kg/m3 (buoyed weight per physics.md 2.2).
    pub mud_density_kg_m3: f64,
    /// Measured depth of the bit face, m.
    pub bit_md_m: f64,
    /// Weight on bit, N (>= 0 on bottom; 0 off bottom). The bit boundary is `F = -WOB`.
    pub wob_n: f64,
    /// Bit torque, N.m, in the sense of rotation (0 off bottom). The bit boundary is `M = T_b`.
    pub bit_torque_nm: f64,
    /// Axial speed of the string, m/s, positive down the hole (running in / drilling),
    /// negative pulling out. Only the direction of the velocity matters (with `omega_rad_s`);
    /// from a case, [`crate::case::Operation::motion`].
    pub axial_speed_m_s: f64,
    /// Rotary speed, rad/s (positive clockwise seen from above; 0 = not rotating).
    pub omega_rad_s: f64,
    /// Wall friction coefficient where the hole section gives none.
    pub friction: f64,
    /// Longest element, m (> 0). Nodes are also placed at component boundaries and hole
    /// section boundaries.
    pub max_element_m: f64,
}

/// State of the string at one node.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SoftStringPoint {
    /// Measured depth of the node, m.
    pub md_m: f64,
    /// Effective axial force, N (positive = tension, negative = compression).
    pub tension_n: f64,
    /// Torque carried by the string, N.m (positive in the sense of rotation).
    pub torque_nm: f64,
    /// Wall contact force per length, N/m, of the element just below this node (for the bit
    /// node, of the element just above it).
    pub normal_force_per_m: f64,
    /// Unit vector (global north, east, down) of the direction in which the pipe presses the
    /// wall, for the same element as `normal_force_per_m`; zero where that force is zero.
    pub normal_dir: Vec3,
}

/// Result of a soft-string pass.
#[derive(Debug, Clone, PartialEq)]
pub struct SoftStringResult {
    /// Effective tension at the top of the string (hook load, no block weight), N.
    pub hook_load_n: f64,
    /// Torque at the top of the string, N.m (positive in the sense of rotation).
    pub surface_torque_nm: f64,
    /// Nodes from the bit (index 0) up to the top of the string.
    pub points: Vec<SoftStringPoint>,
    /// True when there was no motion (`v_a = 0` and `Omega = 0`) and friction was therefore
    /// left out (hook load = buoyed weight along the axis minus WOB, torque = bit torque).
    pub frictionless: bool,
}

const E_D: Vec3 = Vec3::new(0.0, 0.0, 1.0);

/// Force balance of one soft-string element (see the module documentation): its mean
/// tangent and the lateral load that the wall carries.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ElementBalance {
    /// Mean unit tangent `tbar = (t_lo + t_up)/|t_lo + t_up|` (`t_lo` when the two tangents
    /// cancel).
    pub tbar: Vec3,
    /// Lateral load `G - (G.tbar) tbar` with `G = F_lo (t_lo - t_up) + W e_D`, N (global
    /// north, east, down): the force the element presses on the wall with, frictionless.
    pub lateral: Vec3,
}

/// Balance of an element with unit tangents `t_lo` (lower end) and `t_up` (upper end) down the
/// hole, axial force `f_lo` at its lower end (N, tension positive) and buoyed weight
/// `weight_n` (N): Johancsik's element balance, shared by [`soft_string`] and the stiff
/// model's start (`models::fem::solve`).
pub fn element_balance(t_lo: Vec3, t_up: Vec3, f_lo: f64, weight_n: f64) -> ElementBalance {
    let sum = t_lo + t_up;
    let sn = sum.norm();
    let tbar = if sn > 1e-12 { sum / sn } else { t_lo };
    let g = (t_lo - t_up) * f_lo + E_D * weight_n;
    ElementBalance {
        tbar,
        lateral: g - tbar * g.dot(&tbar),
    }
}

/// Contact radius of a component for the soft-string torque, m: half the tool-joint OD if
/// the component has tool joints, else half its contact OD (physics.md 1.4 / 2.3).
pub fn contact_radius_m(c: &Component) -> f64 {
    c.tool_joint_od_m.unwrap_or(c.contact_od_m) / 2.0
}

/// Breakpoints (distance from the bit face, m, ascending, from 0 to the string length): the
/// component boundaries and the hole section boundaries inside the string.
fn breakpoints(input: &SoftStringInput) -> Vec<f64> {
    let len = input.string.length_m();
    let mut x: Vec<f64> = Vec::with_capacity(input.string.components.len() + input.hole.sections().len() + 1);
    x.push(0.0);
    for c in &input.string.components {
        x.push(c.top_m());
    }
    for s in input.hole.sections() {
        let d = input.bit_md_m - s.to_md_m;
        if d.is_finite() && d > 0.0 && d < len {
            x.push(d);
        }
    }
    x.retain(|v| *v >= 0.0 && *v <= len);
    x.sort_by(|a, b| a.total_cmp(b));
    x.dedup_by(|a, b| (*a - *b).abs() < 1e-9);
    x
}

/// Number of elements in a segment of length `l`.
fn n_elements(l: f64, max_el: f64) -> usize {
    ((l / max_el) - 1e-9).ceil().max(1.0) as usize
}

/// Soft-string torque and drag, integrated from the bit up (see the module documentation for
/// the equations and sign conventions).
///
/// An empty string gives a result with the bit boundary values and the bit node only.
///
/// # Panics
/// If `max_element_m` is not positive.
pub fn soft_string(input: &SoftStringInput) -> SoftStringResult {
    integrate(input, false, &no_extra_contact)
}

/// [`soft_string`] with an added wall contact force per length, `extra(md_m, s_m,
/// compression_n)` (N/m; at an element's middle MD and distance from the bit face, m, under
/// the effective compression at its lower end, N), pressing the wall in addition to the lateral
/// load and dragging with the same friction: the helix's contact force of a buckled soft string
/// ([`crate::models::helical_drag`]).
pub fn soft_string_with_extra_contact(
    input: &SoftStringInput,
    extra: &dyn Fn(f64, f64, f64) -> f64,
) -> SoftStringResult {
    integrate(input, false, extra)
}

/// Soft string whose wall contact balances the lateral load together with the lateral
/// (circumferential) part of the wall friction, as in the stiff model (physics.md 6.6): the
/// normal force is `|G_lat| / sqrt(1 + (f v_t/|v|)^2)` instead of Johancsik's `|G_lat|`, so a
/// rotating string carries `1/sqrt(1 + f^2)` of the Johancsik torque and drag in a straight
/// section. Used above the stiff part of the `hybrid` level, so that its surface torque is
/// consistent with the stiff model below.
pub fn soft_string_stiff_contact(input: &SoftStringInput) -> SoftStringResult {
    integrate(input, true, &no_extra_contact)
}

/// No added wall contact force (N/m): the plain soft string's `extra`.
fn no_extra_contact(_md_m: f64, _s_m: f64, _compression_n: f64) -> f64 {
    0.0
}

fn integrate(input: &SoftStringInput, stiff_contact: bool, extra: &dyn Fn(f64, f64, f64) -> f64) -> SoftStringResult {
    assert!(input.max_element_m > 0.0, "max_element_m must be positive");
    let motion = Motion {
        axial_speed_m_s: input.axial_speed_m_s,
        omega_rad_s: input.omega_rad_s,
    };
    let frictionless = !motion.is_moving();
    let bit = input.path.point_at(input.bit_md_m);
    let mut f = -input.wob_n;
    let mut m = input.bit_torque_nm;

    let xs = breakpoints(input);
    let n_total: usize = xs
        .windows(2)
        .map(|w| n_elements(w[1] - w[0], input.max_element_m))
        .sum();
    let mut points = Vec::with_capacity(n_total + 1);
    points.push(SoftStringPoint {
        md_m: input.bit_md_m,
        tension_n: f,
        torque_nm: m,
        normal_force_per_m: 0.0,
        normal_dir: Vec3::zeros(),
    });

    let mut p_lo = bit;
    for seg in xs.windows(2) {
        let (xa, xb) = (seg[0], seg[1]);
        let comp = input.string.component_at(0.5 * (xa + xb));
        let w_b = comp.buoyed_weight_n_per_m(input.mud_density_kg_m3);
        let r_c = contact_radius_m(comp);
        // friction split for this component (the contact radius sets the sliding speed)
        let split = motion.friction_split(r_c);
        let (ax_share, rot_share) = (split.axial, split.tangential);
        let n = n_elements(xb - xa, input.max_element_m);
        let h = (xb - xa) / n as f64;
        for j in 0..n {
            let x_up = if j + 1 == n { xb } else { xa + (j + 1) as f64 * h };
            let md_up = input.bit_md_m - x_up;
            let p_up = input.path.point_at(md_up);
            let dl = p_lo.md_m - md_up;
            let lat = element_balance(p_lo.tangent, p_up.tangent, f, w_b * dl).lateral;
            let mu = input
                .hole
                .friction_at(0.5 * (p_lo.md_m + md_up))
                .unwrap_or(input.friction);
            let lateral_friction = if stiff_contact { mu * rot_share } else { 0.0 };
            let lat_norm = lat.norm();
            let lateral_normal = lat_norm / lateral_friction.hypot(1.0);
            // the element's axial balance: the axial force at its upper end, N, under the wall
            // force `normal` (N)
            let f_lo = f;
            let axial_up = |normal: f64| f_lo + (w_b * (p_lo.position.z - p_up.position.z) - mu * normal * ax_share);
            let added = added_contact(
                extra,
                (0.5 * (p_lo.md_m + md_up), xa + (j as f64 + 0.5) * h),
                f,
                dl,
                |q| axial_up(lateral_normal + q),
            );
            let normal = lateral_normal + added;
            let dir = if lat_norm > 0.0 { lat / lat_norm } else { Vec3::zeros() };
            let fric = mu * normal;
            f = axial_up(normal);
            m += fric * r_c * rot_share;
            let q = if dl > 0.0 { normal / dl } else { 0.0 };
            if points.len() == 1 {
                points[0].normal_force_per_m = q;
                points[0].normal_dir = dir;
            }
            points.push(SoftStringPoint {
                md_m: md_up,
                tension_n: f,
                torque_nm: m,
                normal_force_per_m: q,
                normal_dir: dir,
            });
            p_lo = p_up;
        }
    }
    SoftStringResult {
        hook_load_n: f,
        surface_torque_nm: m,
        points,
        frictionless,
    }
}

/// The added wall force (N) of an element of length `dl_m` at `(md_m, s_m)` (its middle) under
/// `extra` ([`soft_string_with_extra_contact`]), trapezoidal in the compression: the mean of
/// `extra` at the lower end's axial force `f_lo_n` and at the upper end's as `f_up(added)`
/// predicts it (Heun's predictor-corrector, second order in the element length). Zero (without
/// evaluating `f_up`) where `extra` adds nothing at the lower end and the string is in tension.
fn added_contact(
    extra: &dyn Fn(f64, f64, f64) -> f64,
    (md_m, s_m): (f64, f64),
    f_lo_n: f64,
    dl_m: f64,
    f_up: impl Fn(f64) -> f64,
) -> f64 {
    let q_lo = extra(md_m, s_m, -f_lo_n) * dl_m;
    if q_lo == 0.0 && f_lo_n >= 0.0 {
        return 0.0;
    }
    let q_up = extra(md_m, s_m, -f_up(q_lo)) * dl_m;
    0.5 * (q_lo + q_up)
}

/// Longest soft-string segment, m: the soft string costs microseconds per 1,000 m, and its
/// torque converges more slowly with the segment length than the stiff pipe mesh does (forge-16a
/// surface torque: 0.9% between 1 m and 3 m segments; docs/performance.md "Pipe mesh").
pub const MAX_SEGMENT_M: f64 = 1.0;

/// The soft-string segment length for `settings`: its pipe element length, at most
/// [`MAX_SEGMENT_M`], m.
pub fn segment_length_m(settings: &crate::case::SolverSettings) -> f64 {
    settings.element_length_m.min(MAX_SEGMENT_M)
}

/// Soft-string pass for a case's operation, with elements of at most `max_element_m`.
///
/// - Speeds from [`crate::case::Operation::motion`] (sliding and tripping move at a nominal
///   speed when the case gives none); friction from the operation where the hole
///   section gives none; mud density from the case.
/// - WOB: the operation's (0 off bottom). When the case gives the hook load instead of the
///   WOB (on bottom), the WOB is solved for (secant on the soft-string hook load, clamped at 0:
///   a hook load above the off-bottom value gives WOB 0).
/// - Bit torque: [`crate::models::bit::bit_torque_nm`] at the WOB.
pub fn from_case(case: &Case, max_element_m: f64) -> SoftStringResult {
    from_case_with_extra_contact(case, max_element_m, &no_extra_contact)
}

/// [`from_case`] with the added wall contact force per length `extra` of
/// [`soft_string_with_extra_contact`].
pub fn from_case_with_extra_contact(
    case: &Case,
    max_element_m: f64,
    extra: &dyn Fn(f64, f64, f64) -> f64,
) -> SoftStringResult {
    let op = &case.operation;
    let bit_torque = |wob: f64| crate::models::bit::bit_torque_nm(case, wob);
    let motion = op.motion();
    let run = |wob: f64| {
        let input = SoftStringInput {
            path: &case.well.path,
            hole: &case.well.hole,
            string: &case.string,
            mud_density_kg_m3: case.mud.density_kg_m3,
            bit_md_m: op.bit_md_m,
            wob_n: wob,
            bit_torque_nm: bit_torque(wob),
            axial_speed_m_s: motion.axial_speed_m_s,
            omega_rad_s: motion.omega_rad_s,
            friction: op.friction,
            max_element_m,
        };
        integrate(&input, false, extra)
    };
    let target = match op.hook_load_n {
        Some(h) if op.mode.on_bottom() => h,
        _ => return run(if op.mode.on_bottom() { op.wob_n } else { 0.0 }),
    };
    // Hook load decreases with WOB (slope about -1): secant iteration.
    let mut w0 = op.wob_n.max(0.0);
    let mut r0 = run(w0);
    if w0 == 0.0 && r0.hook_load_n <= target {
        return r0;
    }
    let mut w1 = (w0 + (r0.hook_load_n - target)).max(0.0);
    let tol = 1e-9 * target.abs().max(1.0);
    for _ in 0..60 {
        let r1 = run(w1);
        let e1 = r1.hook_load_n - target;
        if e1.abs() <= tol || (w1 == 0.0 && e1 < 0.0) {
            return r1;
        }
        let e0 = r0.hook_load_n - target;
        let slope = if w1 != w0 { (e1 - e0) / (w1 - w0) } else { -1.0 };
        let slope = if slope < -1e-6 { slope } else { -1.0 };
        let next = (w1 - e1 / slope).max(0.0);
        w0 = w1;
        r0 = r1;
        w1 = next;
    }
    run(w1)
}

/// The soft string of `case` with the hook load held at zero ([`from_case`] with a hook-load
/// input of 0): on bottom, its WOB (minus the tension at the bit) is the largest the string can
/// deliver; a larger one needs the surface to push (lock-up).
pub fn at_zero_hook_load(case: &Case, max_element_m: f64) -> SoftStringResult {
    let mut c = case.clone();
    c.operation.hook_load_n = Some(0.0);
    from_case(&c, max_element_m)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::geometry::{Station, Survey};
    use crate::string::material::steel;
    use crate::string::ComponentKind;

    fn pipe(len: f64, w_air: f64, tj: Option<f64>) -> Component {
        Component {
            kind: ComponentKind::Pipe,
            name: "pipe".into(),
            length_m: len,
            bottom_m: 0.0,
            body_od_m: 0.127,
            contact_od_m: 0.127,
            contact_length_m: 0.0,
            id_m: 0.1086,
            tool_joint_od_m: tj,
            joint_length_m: 9.144,
            material: steel(),
            weight_air_n_per_m: w_air,
            sensor_to_bit_m: None,
            bend: None,
            rss: None,
        }
    }

    #[test]
    fn softstring_vertical_hanging_weight() {
        // Vertical well, no friction effects: hook load = w_b L exactly in every mode.
        let s = Survey::new(vec![
            Station::from_deg(0.0, 0.0, 0.0),
            Station::from_deg(1000.0, 0.0, 0.0),
        ])
        .unwrap();
        let path = WellPath::new(&s, Vec3::zeros()).unwrap();
        let hole = HoleSize::uniform(0.2159);
        let string = DrillString {
            components: vec![pipe(1000.0, 300.0, Some(0.168))],
        };
        for v in [-0.3, 0.0, 0.3] {
            let r = soft_string(&SoftStringInput {
                path: &path,
                hole: &hole,
                string: &string,
                mud_density_kg_m3: 0.0,
                bit_md_m: 1000.0,
                wob_n: 0.0,
                bit_torque_nm: 0.0,
                axial_speed_m_s: v,
                omega_rad_s: 0.0,
                friction: 0.3,
                max_element_m: 7.0,
            });
            assert!((r.hook_load_n - 300_000.0).abs() < 1e-6);
            assert_eq!(r.points.len(), 144); // ceil(1000/7) = 143 elements
            assert_eq!(r.frictionless, v == 0.0);
        }
    }

    #[test]
    fn softstring_breakpoints_include_components_and_sections() {
        let s = Survey::new(vec![
            Station::from_deg(0.0, 0.0, 0.0),
            Station::from_deg(1000.0, 30.0, 0.0),
        ])
        .unwrap();
        let path = WellPath::new(&s, Vec3::zeros()).unwrap();
        let hole = HoleSize::new(
            vec![
                crate::geometry::HoleSection {
                    to_md_m: 333.3,
                    diameter_m: 0.311,
                    friction: Some(0.2),
                },
                crate::geometry::HoleSection {
                    to_md_m: 1000.0,
                    diameter_m: 0.216,
                    friction: None,
                },
            ],
            vec![],
        );
        let mut a = pipe(100.5, 1000.0, None);
        let mut b = pipe(899.5, 300.0, Some(0.168));
        a.kind = ComponentKind::Collar;
        b.bottom_m = 100.5;
        let string = DrillString { components: vec![a, b] };
        let input = SoftStringInput {
            path: &path,
            hole: &hole,
            string: &string,
            mud_density_kg_m3: 1200.0,
            bit_md_m: 1000.0,
            wob_n: 0.0,
            bit_torque_nm: 0.0,
            axial_speed_m_s: -0.3,
            omega_rad_s: 0.0,
            friction: 0.3,
            max_element_m: 10.0,
        };
        let xs = breakpoints(&input);
        assert_eq!(xs.len(), 4);
        assert!((xs[1] - 100.5).abs() < 1e-12 && (xs[2] - 666.7).abs() < 1e-9);
        let r = soft_string(&input);
        assert!(r.points.iter().any(|p| (p.md_m - 899.5).abs() < 1e-9));
        assert!(r.points.iter().any(|p| (p.md_m - 333.3).abs() < 1e-9));
        assert!((r.points.last().unwrap().md_m).abs() < 1e-9);
        for w in r.points.windows(2) {
            assert!(w[0].md_m - w[1].md_m <= 10.0 + 1e-9);
        }
    }
}
