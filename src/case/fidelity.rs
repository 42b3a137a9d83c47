//! Fidelity levels: which model a command runs, and why.
//!
//! | level    | model                                                         | gives |
//! |----------|---------------------------------------------------------------|-------|
//! | `soft`   | soft-string torque and drag over the whole string | hook load, surface torque, axial force and torque along the string, buckling check; **no** bit side forces, tilt or bending |
//! | `bha`    | stiff FEM of the bottom part, cut where it lies on the wall | bit forces and tilt, contacts and bending below the cut; **no** surface values |
//! | `hybrid` | stiff FEM of the bottom-hole assembly and the pipe just above it + soft string from the coupling point to the surface | all of `bha`, plus hook load and surface torque |
//! | `whole`  | stiff FEM of the whole string (the seed paper's model)        | everything |
//!
//! `auto` picks per command ([`choose`]): `solve` reports the whole string (contacts, bending
//! and stresses along it, hook load and surface torque) and runs `whole`; prediction needs bit
//! forces only and runs `bha` (a requested `hybrid` also runs `bha` there: the soft upper part
//! does not change the bit forces); the torque-and-drag chart needs surface values at many
//! depths and runs `soft`. The models themselves run in [`crate::models::levels`].

/// A model level: what actually runs.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Level {
    /// Soft string over the whole length.
    Soft,
    /// Stiff bottom-hole assembly only.
    Bha,
    /// Stiff bottom-hole assembly and the pipe just above it, plus soft string above the coupling point.
    Hybrid,
    /// Stiff whole string.
    Whole,
}

impl Level {
    /// Every level, cheapest first.
    pub const ALL: [Level; 4] = [Level::Soft, Level::Bha, Level::Hybrid, Level::Whole];

    /// Name as in `[solver] fidelity`, `--fidelity` and `summary.json`.
    pub fn name(self) -> &'static str {
        match self {
            Level::Soft => "soft",
            Level::Bha => "bha",
            Level::Hybrid => "hybrid",
            Level::Whole => "whole",
        }
    }
}

/// The fidelity a user asks for: `auto` (chosen per command) or one level.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Fidelity {
    /// Choose per command ([`choose`]).
    Auto,
    /// This level.
    Level(Level),
}

/// Accepted names, for messages.
pub const NAMES: &str = "auto, soft, bha, hybrid, whole";

impl Fidelity {
    /// Parse a fidelity name (`auto`, `soft`, `bha`, `hybrid`, `whole`).
    pub fn parse(name: &str) -> Option<Fidelity> {
        if name == "auto" {
            return Some(Fidelity::Auto);
        }
        Level::ALL.into_iter().find(|l| l.name() == name).map(Fidelity::Level)
    }

    /// Name as in case files and `summary.json`'s `fidelity.requested`.
    pub fn name(self) -> &'static str {
        match self {
            Fidelity::Auto => "auto",
            Fidelity::Level(l) => l.name(),
        }
    }
}

/// What a command asks of the model (for `auto`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Purpose {
    /// `drillpath solve`: bit forces, contacts along the string, hook load and surface torque.
    Solve,
    /// `drillpath predict` / `backanalyze`: bit forces and tilt at many bit positions.
    Predict,
    /// `drillpath loads`: hook load and surface torque at many depths.
    Loads,
}

/// The level chosen and why.
#[derive(Debug, Clone, PartialEq)]
pub struct Choice {
    /// What the user asked for (case file or `--fidelity`).
    pub requested: Fidelity,
    /// What runs.
    pub level: Level,
    /// One sentence: why this level.
    pub reason: String,
}

/// The level for `requested` on a command with `purpose` (see the module documentation).
pub fn choose(requested: Fidelity, purpose: Purpose) -> Choice {
    let (level, reason) = match requested {
        Fidelity::Level(Level::Hybrid) if purpose == Purpose::Predict => (
            Level::Bha,
            "requested hybrid: prediction uses the bit forces only, which the soft string above the stiff bottom-hole assembly does not change, so the bha model runs",
        ),
        Fidelity::Level(Level::Soft) => (Level::Soft, "requested: soft string (no bending, no bit side forces)"),
        Fidelity::Level(Level::Bha) => (
            Level::Bha,
            "requested: stiff bottom-hole assembly only (no hook load or surface torque)",
        ),
        Fidelity::Level(Level::Hybrid) => (
            Level::Hybrid,
            "requested: stiff bottom-hole assembly and the pipe just above it, soft string from the coupling point (three tangency lengths above the assembly) to the surface",
        ),
        Fidelity::Level(Level::Whole) => (Level::Whole, "requested: stiff whole string"),
        Fidelity::Auto => match purpose {
            Purpose::Solve => (
                Level::Whole,
                "auto: solve reports the whole string (contacts, bending and stresses along it, hook load and surface torque), which needs the stiff whole-string model",
            ),
            Purpose::Predict => (
                Level::Bha,
                "auto: prediction needs the bit forces and tilt only, which depend on the stiff bottom part",
            ),
            Purpose::Loads => (
                Level::Soft,
                "auto: the torque-and-drag chart needs hook load and surface torque at many depths, which the soft string gives",
            ),
        },
    };
    Choice {
        requested,
        level,
        reason: reason.to_string(),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Reference: the documented names; parse and name are inverse on every level and `auto`.
    #[test]
    fn names_round_trip() {
        for l in Level::ALL {
            assert_eq!(Fidelity::parse(l.name()), Some(Fidelity::Level(l)));
        }
        assert_eq!(Fidelity::parse("auto"), Some(Fidelity::Auto));
        assert_eq!(Fidelity::parse("medium"), None);
        assert_eq!(Fidelity::Auto.name(), "auto");
    }
}
