//! Solver settings: element lengths, contact tolerance, fidelity, contact scheme, iteration
//! limit, stabilizer contact model.

use super::accuracy::Accuracy;
use super::fidelity::Fidelity;

/// Default number of contact runs above the highest point of interest (the bit, or the
/// highest survey sensor) whose ends the contact-aware refinement refines (`[solver]
/// refine_runs`; `models::fem::refine::reach_m`). What a coarse run end does to the bit's
/// forces and a sensor's sag falls by about the carry-over factor of a continuous beam, -0.27,
/// per span between them; full-gauge pins are not counted. Measured (docs/performance.md, "The
/// near-bit scope"): two runs leave the packed BHA's third run (its bit force 0.27% off at a
/// 1 m mesh); three agree with refining every run within 0.0012% on the test BHAs and the
/// example wells.
pub const DEFAULT_REFINE_RUNS: usize = 3;

/// Contact solution scheme.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Method {
    /// Newton with penalty/augmented-Lagrangian contact (robust default).
    Newton,
    /// The seed paper's modified Newton with gap additional forces (eq. 15).
    Paper,
}

/// How stabilizers and bits touch the wall (`[solver] stabilizer_contact`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StabilizerContact {
    /// Along the blades and the bit's gauge: contact points along each blade and gauge
    /// (docs/theory.md 3.4).
    Blade,
    /// The classic model (the default): one contact point at each stabilizer's middle, the bit
    /// touching only at its face, whatever the blade and gauge lengths (docs/theory.md 3.4 says
    /// why it is the default).
    Point,
}

impl StabilizerContact {
    /// Accepted names, for messages.
    pub const NAMES: &'static str = "blade, point";
    /// Parse the case-file name.
    pub fn parse(s: &str) -> Option<StabilizerContact> {
        match s {
            "blade" => Some(StabilizerContact::Blade),
            "point" => Some(StabilizerContact::Point),
            _ => None,
        }
    }
    /// Name as written in case files.
    pub fn name(self) -> &'static str {
        match self {
            StabilizerContact::Blade => "blade",
            StabilizerContact::Point => "point",
        }
    }
}

/// Default wall-clock limit of one solve, s (`[solver] time_limit`).
pub const DEFAULT_TIME_LIMIT_S: f64 = 60.0;

/// Most elements a string model may have (`element_length` and `bha_element_length` over the
/// string's length); a finer mesh is refused by the case reader with the remedy.
pub const MAX_ELEMENTS: f64 = 50_000.0;

/// Solver settings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverSettings {
    /// Longest element in the pipe, m.
    pub element_length_m: f64,
    /// Longest element in the bottom-hole assembly, m.
    pub bha_element_length_m: f64,
    /// Contact gap tolerance relative to the local clearance.
    pub tolerance: f64,
    /// Fidelity.
    pub fidelity: Fidelity,
    /// Contact scheme.
    pub method: Method,
    /// Iteration limit.
    pub max_iterations: usize,
    /// How stabilizers and bits touch the wall.
    pub stabilizer_contact: StabilizerContact,
    /// Whether a stiff solve refines the assembly's mesh where a collar comes onto the wall and
    /// solves again (`refine_contacts`; [`crate::models::fem::refine`]).
    pub refine_contacts: bool,
    /// How many contact runs above the bit (or above the highest survey sensor) the refinement
    /// refines (`refine_runs`, at least 1; `models::fem::refine::Scope`).
    pub refine_runs: usize,
    /// Paper scheme's gradient-update factor alpha in (0, 1).
    pub alpha: f64,
    /// Wall-clock limit of one solve, s (`time_limit`).
    pub time_limit_s: f64,
    /// The accuracy preset that set the defaults above (`[solver] accuracy` or `--accuracy`),
    /// None when the documented defaults and explicit keys apply.
    pub accuracy: Option<Accuracy>,
}

impl Default for SolverSettings {
    fn default() -> Self {
        SolverSettings {
            element_length_m: 3.0,
            bha_element_length_m: 0.5,
            tolerance: 1e-4,
            fidelity: Fidelity::Auto,
            method: Method::Newton,
            max_iterations: 300,
            stabilizer_contact: StabilizerContact::Point,
            refine_contacts: true,
            refine_runs: DEFAULT_REFINE_RUNS,
            alpha: 0.7,
            time_limit_s: DEFAULT_TIME_LIMIT_S,
            accuracy: None,
        }
    }
}

impl SolverSettings {
    /// Set the element lengths and tolerance of `preset` (and record the preset).
    pub fn apply_preset(&mut self, preset: Accuracy) {
        let k = preset.knobs();
        self.accuracy = Some(preset);
        self.element_length_m = k.element_length_m;
        self.bha_element_length_m = k.bha_element_length_m;
        self.tolerance = k.tolerance;
    }
}
