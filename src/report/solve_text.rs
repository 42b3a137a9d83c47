//! The readable summary of `drillpath solve` on stdout, in the user's units.

use super::display_units::{fixed, signed, DisplayUnit, UnitSystem};
use super::solve_output::CONTACT_THRESHOLD_N;
use crate::case::{Case, Level};
use crate::models::buckling::summarize;
use crate::models::fem::results::BitResult;
use crate::models::soft_comparison::SoftComparison;
use crate::models::string_solve::StringSolve;
use crate::predict::steer::{RssSteering, Steering};
use std::io::Write;
use std::path::Path;

/// What the summary shows besides the solve: where it came from and where it went.
pub struct SolveView<'a> {
    /// The case file as the user named it.
    pub case_file: &'a Path,
    /// Units shown.
    pub units: UnitSystem,
    /// The `--out` directory, when files were written.
    pub out_dir: Option<&'a Path>,
    /// The HTML report written, if any.
    pub report: Option<&'a Path>,
    /// The bent housing's tendencies (None: a straight string).
    pub steering: Option<&'a Steering>,
    /// A rotary steerable system's tendency (None: no RSS).
    pub rss: Option<&'a RssSteering>,
}

/// The lines every level prints about the operation and the bit: mode, bit MD, WOB, rpm; bit
/// side forces, tilt and torque (or only the torque for the soft string).
pub struct BitLines<'a> {
    /// Units shown.
    pub units: UnitSystem,
    /// The case solved.
    pub case: &'a Case,
    /// Weight on bit, N.
    pub wob_n: f64,
    /// Bit forces and tilt (None for the soft string).
    pub bit: Option<&'a BitResult>,
    /// Bit torque, N.m.
    pub bit_torque_nm: f64,
}

impl BitLines<'_> {
    /// Write the two lines to `out`.
    pub fn write(&self, out: &mut impl Write) -> std::io::Result<()> {
        let (depth_unit, force_unit, torque_unit) = (self.units.depth(), self.units.force(), self.units.torque());
        let op = &self.case.operation;
        // the string turns only when the mode rotates it (sliding and tripping: the rpm of the
        // case is not applied, Operation::omega_rad_s)
        let rotation = if op.omega_rad_s() > 0.0 {
            format!("{} rpm", fixed(op.rpm, 0))
        } else {
            "string not rotating".to_string()
        };
        writeln!(
            out,
            "  mode {}, bit at {} MD, WOB {}, {rotation}",
            op.mode.name(),
            depth_unit.fmt(op.bit_md_m, 2),
            force_unit.fmt(self.wob_n, 1),
        )?;
        match self.bit {
            Some(b) => writeln!(
                out,
                "  bit: build force {}, walk force {}, tilt inc {} deg, tilt azi {} deg, torque {}",
                force_unit.fmt_signed(b.build_force_n, 3),
                force_unit.fmt_signed(b.walk_force_n, 3),
                signed(b.tilt_inc_rad.to_degrees(), 4),
                signed(b.tilt_azi_rad.to_degrees(), 4),
                torque_unit.fmt(b.torque_nm, 2)
            ),
            None => writeln!(
                out,
                "  bit: torque {}; side forces and tilt not computed (soft string: no bending)",
                torque_unit.fmt(self.bit_torque_nm, 2)
            ),
        }
    }
}

/// Write the readable summary of the solve `s` of `case` to `out`: the whole string's
/// (contacts near the bit, solver statistics) or another level's (cut, buckling, time).
pub fn write_summary(out: &mut impl Write, case: &Case, s: &StringSolve, view: &SolveView) -> std::io::Result<()> {
    let lr = &s.level;
    writeln!(out, "solve: {} ({})", case.name, view.case_file.display())?;
    writeln!(out, "  fidelity {}: {}", lr.choice.level.name(), lr.choice.reason)?;
    for w in s.warnings(case) {
        writeln!(out, "  WARNING: {w}")?;
    }
    for x in &s.sensors {
        writeln!(
            out,
            "  sensor of `{}` at {} from the bit ({} MD): sag {} deg (it reads the inclination {} deg high; correct by {} deg)",
            x.component,
            view.units.depth().fmt(x.sensor_to_bit_m, 2),
            view.units.depth().fmt(x.md_m, 2),
            signed(x.sag_rad.to_degrees(), 4),
            signed(x.sag_rad.to_degrees(), 4),
            signed(-x.sag_rad.to_degrees(), 4)
        )?;
    }
    if let Some(st) = view.steering {
        writeln!(out, "{}", steering_line(st, view.units))?;
    }
    if let Some(st) = view.rss {
        writeln!(out, "{}", rss_line(st, view.units))?;
    }
    if lr.choice.level == Level::Whole {
        write_whole(out, case, s, view)
    } else {
        write_level(out, case, s, view)
    }
}

/// The stdout line of a bent housing's tendencies, in `units`.
pub fn steering_line(st: &Steering, units: UnitSystem) -> String {
    let dl = units.dogleg();
    let head = format!(
        "  bent motor: {} deg at {} from the bit, toolface {} deg ({})",
        fixed(st.bend.angle_rad.to_degrees(), 2),
        units.depth().fmt(st.bend.to_bit_m, 2),
        fixed(st.toolface_rad.to_degrees(), 1),
        if st.magnetic { "magnetic" } else { "gravity" }
    );
    let head = match st.reactive_turn {
        Some(t) => format!(
            "{head}, turned {} deg left by the motor's reactive torque {} kN.m (drilling at {} deg{})",
            fixed(t.turn_rad.to_degrees(), 1),
            fixed(t.torque_nm / 1e3, 2),
            fixed(
                crate::geometry::survey::degrees_in_turn((st.toolface_rad - t.turn_rad).to_degrees(), 1),
                1
            ),
            match t.held_m {
                Some(h) => format!("; the wall holds it within {} of the bit", units.depth().fmt(h, 0)),
                None => "; the wall does not hold it: the rotary table does".to_string(),
            }
        ),
        None => head,
    };
    match &st.tendencies {
        Ok((y, r)) => format!(
            "{head}; motor yield sliding {} (build {}, right {}); rotating tendency build {}, right {} ({} toolfaces)",
            dl.fmt(y.dogleg_rad_per_m(), 2),
            dl.fmt_signed(y.build_rad_per_m, 2),
            dl.fmt_signed(y.right_rad_per_m, 2),
            dl.fmt_signed(r.build_rad_per_m, 2),
            dl.fmt_signed(r.right_rad_per_m, 2),
            st.rotating_toolfaces
        ),
        Err(why) => format!("{head}; motor yield not computed: {why}"),
    }
}

/// The stdout line of a rotary steerable system's tendency, in `units`.
pub fn rss_line(st: &RssSteering, units: UnitSystem) -> String {
    let dl = units.dogleg();
    let what = match st.tool.steer {
        crate::string::RssSteer::PushTheBit {
            pad_force_n,
            pad_to_bit_m,
        } => format!(
            "pad force {} at {} from the bit",
            units.force().fmt(pad_force_n, 1),
            units.depth().fmt(pad_to_bit_m, 2)
        ),
        crate::string::RssSteer::PointTheBit {
            deflection_rad,
            hinge_to_bit_m,
        } => format!(
            "deflection {} deg at {} from the bit",
            fixed(deflection_rad.to_degrees(), 2),
            units.depth().fmt(hinge_to_bit_m, 2)
        ),
    };
    let head = format!(
        "  rss ({}): {what}, ratio {}, toolface {} deg ({})",
        st.tool.kind_name(),
        fixed(st.tool.ratio, 2),
        fixed(st.toolface_rad.to_degrees(), 1),
        if st.magnetic { "magnetic" } else { "gravity" }
    );
    match &st.tendency {
        Ok(t) => format!(
            "{head}; dogleg rotating {} (build {}, right {})",
            dl.fmt(t.dogleg_rad_per_m(), 2),
            dl.fmt_signed(t.build_rad_per_m, 2),
            dl.fmt_signed(t.right_rad_per_m, 2),
        ),
        Err(why) => format!("{head}; dogleg not computed: {why}"),
    }
}

fn not_converged_line(out: &mut impl Write) -> std::io::Result<()> {
    writeln!(
        out,
        "  WARNING: NOT CONVERGED - results below are flagged and not valid"
    )
}

fn wrote_line(out: &mut impl Write, view: &SolveView) -> std::io::Result<()> {
    if let Some(dir) = view.out_dir {
        writeln!(out, "  wrote {}/summary.json and string.csv", dir.display())?;
    }
    if let Some(file) = view.report {
        writeln!(out, "  wrote {}", file.display())?;
    }
    Ok(())
}

fn write_whole(out: &mut impl Write, case: &Case, s: &StringSolve, view: &SolveView) -> std::io::Result<()> {
    let lr = &s.level;
    let Some(part) = &lr.fem else {
        return Ok(());
    };
    let res = &part.results;
    let (depth_unit, force_unit) = (view.units.depth(), view.units.force());
    let b = &res.bit;
    if !part.converged {
        not_converged_line(out)?;
    }
    BitLines {
        units: view.units,
        case,
        wob_n: b.wob_n,
        bit: Some(b),
        bit_torque_nm: b.torque_nm,
    }
    .write(out)?;
    writeln!(
        out,
        "  surface: hook load {}, torque {}",
        force_unit.fmt(res.hook_load_n, 1),
        view.units.torque().fmt(res.surface_torque_nm, 2)
    )?;
    if let Some(c) = &s.soft_comparison {
        soft_line(out, c, view.units)?;
    }
    let contacts: Vec<_> = res
        .nodes
        .iter()
        .filter(|n| n.contact_force_n > CONTACT_THRESHOLD_N)
        .collect();
    if let (Some(first), Some(last)) = (contacts.first(), contacts.last()) {
        let near: Vec<String> = contacts
            .iter()
            .filter(|n| b.md_m - n.md_m < 60.0)
            .take(6)
            .map(|n| {
                format!(
                    "{}: {} at {} deg",
                    depth_unit.fmt(b.md_m - n.md_m, 1),
                    force_unit.fmt(n.contact_force_n, 2),
                    fixed(crate::geometry::survey::degrees_in_turn(n.contact_angle_deg, 0), 0)
                )
            })
            .collect();
        writeln!(
            out,
            "  contacts: {} nodes between {} and {} MD; max {}",
            contacts.len(),
            depth_unit.fmt(last.md_m, 1),
            depth_unit.fmt(first.md_m, 1),
            force_unit.fmt(contacts.iter().map(|n| n.contact_force_n).fold(0.0, f64::max), 2)
        )?;
        if !near.is_empty() {
            writeln!(out, "  near the bit (distance above bit): {}", near.join("; "))?;
        }
    } else {
        writeln!(out, "  contacts: none")?;
    }
    writeln!(out, "  solver: {} iterations, {} factorizations, {} DOF, {} elements, {:.3} s, equilibrium error {:.1e} of the largest force",
        part.stats.iterations, part.stats.factorizations, part.model.dofs(), part.model.nodes() - 1, part.stats.seconds,
        res.force_imbalance_n.norm() / res.largest_force_n.max(1.0))?;
    wrote_line(out, view)
}

fn write_level(out: &mut impl Write, case: &Case, s: &StringSolve, view: &SolveView) -> std::io::Result<()> {
    let lr = &s.level;
    let (depth_unit, force_unit, torque_unit) = (view.units.depth(), view.units.force(), view.units.torque());
    if let Some(cut) = lr.cut_m {
        writeln!(
            out,
            "  stiff model cut {} above the bit (on the wall, parallel to the hole); results reported up to {} above the bit",
            depth_unit.fmt(cut, 1),
            depth_unit.fmt(s.coupling_m.unwrap_or(cut), 1)
        )?;
    }
    if !lr.converged {
        not_converged_line(out)?;
    }
    BitLines {
        units: view.units,
        case,
        wob_n: lr.wob_n,
        bit: lr.bit.as_ref(),
        bit_torque_nm: lr.bit_torque_nm,
    }
    .write(out)?;
    match (lr.hook_load_n, lr.surface_torque_nm) {
        (Some(h), Some(t)) => writeln!(
            out,
            "  surface: hook load {}, torque {}",
            force_unit.fmt(h, 1),
            torque_unit.fmt(t, 2)
        )?,
        _ => writeln!(
            out,
            "  surface: not computed (bha: the stiff model ends at the cut; use hybrid or whole)"
        )?,
    }
    if let Some(c) = &s.soft_comparison {
        soft_line(out, c, view.units)?;
    }
    let b = summarize(&s.marks);
    writeln!(
        out,
        "  buckling: sinusoidal over {}, helical over {} (max compression {})",
        depth_unit.fmt(b.sinusoidal_length_m, 1),
        depth_unit.fmt(b.helical_length_m, 1),
        force_unit.fmt(b.max_compression_n, 1)
    )?;
    writeln!(out, "  time {:.4} s", lr.seconds)?;
    wrote_line(out, view)
}

/// The hook load of the soft string with the helix's drag beside a stiff solve, in
/// `force_unit`: its value, or that its compression diverged up the helix (the value then a
/// flag, [`SoftComparison::helical_drag_diverged`]).
pub(super) fn helical_drag_hook_load_text(c: &SoftComparison, force_unit: DisplayUnit) -> String {
    if c.helical_drag_diverged() {
        "none (its compression diverges up the helix)".to_string()
    } else {
        force_unit.fmt(c.helical_drag_hook_load_n, 1)
    }
}

/// The soft string beside the stiff solve `c`: its hook load and torque at the same WOB, the
/// stiff-minus-soft differences, and its helically buckled length; where it is helically
/// buckled, the soft string with the helix's drag too.
fn soft_line(out: &mut impl Write, c: &SoftComparison, units: UnitSystem) -> std::io::Result<()> {
    let (depth_unit, force_unit, torque_unit) = (units.depth(), units.force(), units.torque());
    writeln!(
        out,
        "  soft string at this WOB: hook load {} (stiff - soft {}), torque {} (stiff - soft {}), helical over {}",
        force_unit.fmt(c.hook_load_n, 1),
        force_unit.fmt(c.hook_load_difference_n(), 1),
        torque_unit.fmt(c.surface_torque_nm, 2),
        torque_unit.fmt(c.surface_torque_difference_nm(), 2),
        depth_unit.fmt(c.helical_length_m, 1)
    )?;
    if c.helical_length_m > 0.0 {
        writeln!(
            out,
            "  soft string with the helix's drag (Mitchell): hook load {}, torque {}",
            helical_drag_hook_load_text(c, force_unit),
            torque_unit.fmt(c.helical_drag_surface_torque_nm, 2)
        )?;
    }
    Ok(())
}
