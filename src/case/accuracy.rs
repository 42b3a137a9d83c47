//! Accuracy presets: element length, contact tolerance and prediction step set
//! together. `[solver] accuracy = "fast" | "default" | "precise"` gives the defaults of
//! `element_length`, `bha_element_length` and `tolerance` (keys given explicitly win);
//! `--accuracy` on `solve`, `predict` and `backanalyze` overrides all three. The preset's
//! prediction step is the default of `[bit_rock] step` when the case names a preset, and
//! `predict`/`backanalyze --accuracy` set it (an explicit `--step` wins).
//!
//! | preset    | element_length | bha_element_length | tolerance | prediction step |
//! |-----------|----------------|--------------------|-----------|-----------------|
//! | `fast`    | 6 m            | 1 m                | 1e-3      | 2 m             |
//! | `default` | 3 m            | 0.5 m              | 1e-4      | 1 m             |
//! | `precise` | 0.5 m          | 0.3 m              | 1e-5      | 0.5 m           |
//!
//! The pipe element length barely matters for the bit forces (the bottom-hole assembly has its
//! own, finer mesh) and little for the surface values: on the six example wells, 3 m pipe
//! elements give the same bit forces as 0.5 m to 5 digits, hook loads within 1e-5 and surface
//! torques within 0.2% (6 m: 0.8%); docs/performance.md "Pipe mesh". The soft string keeps
//! segments of at most 1 m ([`crate::models::softstring::MAX_SEGMENT_M`]).
//!
//! The prediction step dominates the predictor's error; the bottom-hole-assembly mesh and the
//! tolerance move the inclination after 100 m by less than 0.005 deg between the presets' values
//! (j-shape, seed-daqing, horizontal at fixed steps of 0.5 m and more). With the arc march
//! ([`crate::predict::march::StepScheme::Arc`]) the inclination after 100 m lies within 0.02 deg
//! of the limit of equal-step marches at 1 m on four of the six examples and within 0.08 deg at
//! 2 m (the first step's own, slowly converging effect is an open point). The
//! exceptions: a start with a large bit side force (forge-16a from 7,300 ft: 0.16 deg at 1 m,
//! 0.27 at 2 m, set in the first step) and the s-shape pendulum (an oscillation of 0.12-0.17 deg
//! about a trend that moves by 0.07 deg per halving of the step between 1 and 0.25 m).
//! Richardson extrapolation (`--extrapolate`) is therefore not a preset default: it triples the
//! time for a gain below 0.02 deg where the march is converged and removes only a third of a
//! first-order error. Measurements: docs/performance.md, "Step convergence" and "Prediction of
//! 100 m".
//!
//! `precise` uses 0.3 m, not 0.25 m, in the bottom-hole assembly: with 0.25 m the cut
//! (`bha`) model of the j-shape and horizontal examples does not converge (open point).

/// An accuracy preset.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Accuracy {
    /// Coarse mesh, loose contact tolerance.
    Fast,
    /// The documented defaults.
    Default,
    /// Fine mesh, tight contact tolerance (the benchmark's reference).
    Precise,
}

/// The knobs a preset sets, SI.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Knobs {
    /// Longest pipe element, m.
    pub element_length_m: f64,
    /// Longest element in the bottom-hole assembly, m.
    pub bha_element_length_m: f64,
    /// Contact gap tolerance relative to the clearance.
    pub tolerance: f64,
    /// Prediction step, m.
    pub step_m: f64,
}

/// Accepted names, for messages.
pub const NAMES: &str = "fast, default, precise";

impl Accuracy {
    /// All presets, coarse first.
    pub const ALL: [Accuracy; 3] = [Accuracy::Fast, Accuracy::Default, Accuracy::Precise];

    /// Parse a preset name.
    pub fn parse(name: &str) -> Option<Accuracy> {
        Some(match name {
            "fast" => Accuracy::Fast,
            "default" => Accuracy::Default,
            "precise" => Accuracy::Precise,
            _ => return None,
        })
    }

    /// Name as in case files.
    pub fn name(self) -> &'static str {
        match self {
            Accuracy::Fast => "fast",
            Accuracy::Default => "default",
            Accuracy::Precise => "precise",
        }
    }

    /// The preset's knobs (table in the module documentation).
    pub fn knobs(self) -> Knobs {
        match self {
            Accuracy::Fast => Knobs {
                element_length_m: 6.0,
                bha_element_length_m: 1.0,
                tolerance: 1e-3,
                step_m: 2.0,
            },
            Accuracy::Default => Knobs {
                element_length_m: 3.0,
                bha_element_length_m: 0.5,
                tolerance: 1e-4,
                step_m: 1.0,
            },
            Accuracy::Precise => Knobs {
                element_length_m: 0.5,
                bha_element_length_m: 0.3,
                tolerance: 1e-5,
                step_m: 0.5,
            },
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::case::SolverSettings;

    /// Reference: the documented defaults of `[solver]` (SolverSettings::default, docs/guide.md):
    /// the `default` preset must equal them; presets are ordered fast -> precise on every knob.
    #[test]
    fn default_preset_is_the_documented_default() {
        let d = SolverSettings::default();
        let k = Accuracy::Default.knobs();
        assert_eq!(
            (k.element_length_m, k.bha_element_length_m, k.tolerance),
            (d.element_length_m, d.bha_element_length_m, d.tolerance)
        );
        for w in Accuracy::ALL.windows(2) {
            let (a, b) = (w[0].knobs(), w[1].knobs());
            assert!(a.element_length_m > b.element_length_m && a.bha_element_length_m > b.bha_element_length_m);
            assert!(a.tolerance > b.tolerance && a.step_m > b.step_m);
        }
        for p in Accuracy::ALL {
            assert_eq!(Accuracy::parse(p.name()), Some(p));
        }
        assert_eq!(Accuracy::parse("medium"), None);
    }
}
