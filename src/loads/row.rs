//! One row of the torque-and-drag chart: a bit depth and a load case, with the soft string's
//! loads, buckling and yield, and the stiff model's outcome when asked for.

use super::limits::Buckling;
use crate::case::fidelity::Level;
use crate::case::Mode;

/// How a converged stiff solve started.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Start {
    /// The solver's own cold start.
    Cold,
    /// The previous load case's state at the same bit depth.
    PreviousCase,
    /// The same load case's state at the previous bit depth, carried onto the new mesh.
    PreviousDepth,
    /// The buckled shape, after the cold start found no equilibrium: the re-solve from the
    /// buckled start ([`crate::models::buckled_start`]), at the row's WOB or, for a row locked
    /// up by the helix's drag, below its lock-up (`lock_up_wob_n`).
    BuckledShape,
}

/// Result of the stiff model for one row.
#[derive(Debug, Clone, PartialEq)]
pub enum StiffOutcome {
    /// Converged solve.
    Converged {
        /// Surface loads and largest nodal contact force.
        loads: RowLoads,
        /// Newton iterations (all attempts, a failed warm start included).
        iterations: usize,
        /// Wall-clock time, s.
        seconds: f64,
        /// How the converged solve started.
        start: Start,
        /// Lock-up: the row's WOB gave the stiff string no equilibrium and its hook load turns
        /// negative below that WOB, so these loads are at the largest WOB it delivers (its
        /// hook load zero, found along the WOB path), N; None when they are at the row's WOB.
        lock_up_wob_n: Option<f64>,
        /// Length of the stiff pipe compressed beyond the helical onset that the solve found
        /// lying unbuckled on one side of the hole (the straight branch past its stability
        /// limit, [`crate::models::buckling::unbuckled_helical_runs`]), m: there its wall force
        /// and drag miss the helix's; 0 when there is none.
        unbuckled_helical_m: f64,
        /// Length of the MD intervals where the rotating string whirls (its wall friction
        /// without its lateral push, [`crate::models::whirl`]), m; 0 when there are none.
        whirl_m: f64,
        /// Length of the helically buckled pipe meshed with elements longer than an eighth of
        /// the helix's pitch there ([`crate::models::levels::coarse_for_helix_pitch`]), m: its
        /// wall force and drag are those of a mesh too coarse for the helix (`solve` refines
        /// it, `loads` does not); 0 when the mesh resolves the pitch.
        coarse_for_pitch_m: f64,
    },
    /// The solver stopped without meeting its criteria: no valid numbers.
    NotConverged {
        /// Newton iterations (all attempts).
        iterations: usize,
        /// Last relative residual.
        residual: f64,
    },
    /// The solver stopped without an equilibrium on a row whose string cannot be put on bottom
    /// at any WOB (the soft string of its lock-up locked up at zero WOB,
    /// [`crate::models::checks::locked_at_zero_wob`]): no whole-string equilibrium on bottom
    /// exists, the lock-up is the row's answer and its soft-string numbers stand.
    LockedAtZeroWob {
        /// Newton iterations of the solve that found no equilibrium.
        iterations: usize,
    },
    /// The solver failed (e.g. singular stiffness); the message says why.
    Failed(String),
}

impl StiffOutcome {
    /// The loads when converged.
    pub fn loads(&self) -> Option<&RowLoads> {
        match self {
            StiffOutcome::Converged { loads, .. } => Some(loads),
            _ => None,
        }
    }
    /// The WOB the loads are at when the row locked up ([`StiffOutcome::Converged`]'s
    /// `lock_up_wob_n`), N.
    pub fn lock_up_wob_n(&self) -> Option<f64> {
        match self {
            StiffOutcome::Converged { lock_up_wob_n, .. } => *lock_up_wob_n,
            _ => None,
        }
    }
    /// The length of stiff pipe lying unbuckled beyond the helical onset when converged
    /// ([`StiffOutcome::Converged`]'s `unbuckled_helical_m`), m.
    pub fn unbuckled_helical_m(&self) -> Option<f64> {
        match self {
            StiffOutcome::Converged {
                unbuckled_helical_m, ..
            } => Some(*unbuckled_helical_m),
            _ => None,
        }
    }
    /// The length of helically buckled pipe meshed too coarsely for the helix's pitch when
    /// converged ([`StiffOutcome::Converged`]'s `coarse_for_pitch_m`), m.
    pub fn coarse_for_pitch_m(&self) -> Option<f64> {
        match self {
            StiffOutcome::Converged { coarse_for_pitch_m, .. } => Some(*coarse_for_pitch_m),
            _ => None,
        }
    }
    /// The length where the rotating string whirls when converged ([`StiffOutcome::Converged`]'s
    /// `whirl_m`), m.
    pub fn whirl_m(&self) -> Option<f64> {
        match self {
            StiffOutcome::Converged { whirl_m, .. } => Some(*whirl_m),
            _ => None,
        }
    }
    /// How the converged solve started ([`StiffOutcome::Converged`]'s `start`).
    pub fn start(&self) -> Option<Start> {
        match self {
            StiffOutcome::Converged { start, .. } => Some(*start),
            _ => None,
        }
    }
    /// Status word for `loads.csv`: `converged`, `not_converged`, `locked_up` or `failed`.
    pub fn status(&self) -> &'static str {
        match self {
            StiffOutcome::Converged { .. } => "converged",
            StiffOutcome::NotConverged { .. } => "not_converged",
            StiffOutcome::LockedAtZeroWob { .. } => "locked_up",
            StiffOutcome::Failed(_) => "failed",
        }
    }
    /// Newton iterations (0 for a failed solve).
    pub fn iterations(&self) -> usize {
        match self {
            StiffOutcome::Converged { iterations, .. }
            | StiffOutcome::NotConverged { iterations, .. }
            | StiffOutcome::LockedAtZeroWob { iterations } => *iterations,
            StiffOutcome::Failed(_) => 0,
        }
    }
}

/// Surface loads and largest wall contact of one solution (soft or stiff), SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RowLoads {
    /// Hook load (effective tension at the top, no block weight), N.
    pub hook_load_n: f64,
    /// Surface torque, N.m.
    pub surface_torque_nm: f64,
    /// Largest wall contact force, N (soft: per joint, see the module documentation; stiff:
    /// largest nodal contact force).
    pub max_contact_force_n: f64,
    /// Largest wall contact force per length, N/m (soft only; 0 for stiff).
    pub max_side_force_n_per_m: f64,
}

/// Yield limits at the surface and the worst stress along the string (all `None` when the
/// string gives no yield strength; see [`super::limits`]).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct RowYield {
    /// Tension at yield of the top component, N.
    pub tension_limit_n: Option<f64>,
    /// Torque at yield of the top component without tension, N.m.
    pub torque_limit_nm: Option<f64>,
    /// Torque at yield of the top component under this row's hook load, N.m.
    pub combined_torque_limit_nm: Option<f64>,
    /// Largest von Mises ratio (axial + torsion) along the string.
    pub max_stress_ratio: Option<f64>,
}

/// One row of the chart: one bit depth, one load case.
#[derive(Debug, Clone, PartialEq)]
pub struct LoadRow {
    /// Bit measured depth, m.
    pub bit_md_m: f64,
    /// Load case.
    pub mode: Mode,
    /// Weight on bit of the row, N (0 off bottom; on bottom the chart's WOB, or less where the
    /// string cannot give it, see [`super::chart::soft_row`]).
    pub wob_n: f64,
    /// Soft-string loads.
    pub soft: RowLoads,
    /// Hook load of the soft string with the helix's drag at the row's WOB, N
    /// ([`crate::models::helical_drag`]; below zero: helically locked up); the soft hook load
    /// where the soft string is nowhere helically buckled.
    pub helical_drag_hook_load_n: f64,
    /// Buckling along the soft string.
    pub buckling: Buckling,
    /// Yield limits and stress ratio.
    pub yield_: RowYield,
    /// Stiff result (whole-string FEM, or hybrid), when asked for.
    pub stiff: Option<StiffOutcome>,
    /// The level of `stiff` (whole or hybrid).
    pub stiff_level: Option<Level>,
}
