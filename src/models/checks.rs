//! Checks of a solved string against what a real string can do: the stress against the yield
//! strength, and a hook load below zero (lock-up: the surface would have to push the string
//! down to put the WOB on the bit).

use crate::case::{Case, Mode};
use crate::models::fem::model::Model;
use crate::models::fem::results::NodeResult;
use crate::models::helical_drag::{diverged, HelicalLockUp};
use crate::models::lock_up_depth::{hook_load_at_wob_n, lock_up_depths, metres, Drag, LockUpDepths};
use crate::models::softstring;
use crate::string::material::grade_yield_strength_pa;

/// Yield strength assumed for a steel component without a grade or yield strength: the
/// lowest API drill-pipe grade, E-75 (75 ksi), Pa.
pub fn assumed_steel_yield_pa() -> f64 {
    grade_yield_strength_pa("E-75").unwrap_or(517.1e6)
}

/// The highest von Mises stress of a stiff solve against the component's yield strength.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct YieldCheck {
    /// MD of the node with the highest stress over yield, m.
    pub md_m: f64,
    /// Von Mises stress there, Pa.
    pub von_mises_pa: f64,
    /// Yield strength of the component there, Pa.
    pub yield_strength_pa: f64,
    /// The yield strength is assumed ([`assumed_steel_yield_pa`]), not given by the case.
    pub assumed: bool,
}

impl YieldCheck {
    /// Stress over yield strength.
    pub fn ratio(&self) -> f64 {
        self.von_mises_pa / self.yield_strength_pa
    }
    /// Whether the stress exceeds the yield strength.
    pub fn exceeded(&self) -> bool {
        self.ratio() > 1.0
    }
    /// The warning to print when the stress exceeds the yield strength.
    pub fn warning(&self) -> Option<String> {
        self.exceeded().then(|| {
            format!(
                "von Mises stress {:.0} MPa at {:.1} m MD is {:.1} times the yield strength {:.0} MPa{}: the string would yield there (a dogleg sharper than it can pass, or loads beyond its strength); the elastic results are not valid there",
                self.von_mises_pa / 1e6,
                self.md_m,
                self.ratio(),
                self.yield_strength_pa / 1e6,
                if self.assumed {
                    " (assumed: the lowest API grade E-75, as the case gives no grade or yield_strength)"
                } else {
                    ""
                }
            )
        })
    }
}

/// The yield check of the stiff `nodes` (from the bit up, as meshed in `model`): the node with
/// the highest stress over its component's yield strength; None when no node has a yield
/// strength (non-steel components without one given).
pub fn yield_check(case: &Case, model: &Model, nodes: &[NodeResult]) -> Option<YieldCheck> {
    let components = &case.string.components;
    nodes
        .iter()
        .zip(&model.mesh.nodes)
        .filter_map(|(n, m)| {
            let material = &components.get(m.component)?.material;
            let (yield_pa, assumed) = match material.yield_strength_pa {
                Some(y) => (y, false),
                None if material.name == "steel" => (assumed_steel_yield_pa(), true),
                None => return None,
            };
            Some(YieldCheck {
                md_m: n.md_m,
                von_mises_pa: n.von_mises_pa,
                yield_strength_pa: yield_pa,
                assumed,
            })
        })
        .max_by(|a, b| a.ratio().total_cmp(&b.ratio()))
}

/// A hook load below zero on bottom: the WOB asked for cannot be put on the bit by the
/// string's weight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LockUp {
    /// The hook load computed, N (negative).
    pub hook_load_n: f64,
    /// The WOB asked for, N.
    pub wob_n: f64,
    /// The largest WOB the string can deliver (soft string, hook load zero), N.
    pub max_wob_n: f64,
    /// The WOB the results are at when the whole string found no equilibrium at the WOB asked
    /// for and was solved at the largest WOB it delivers (its hook load zero), N; None when
    /// the results are at the WOB asked for.
    pub results_at_wob_n: Option<f64>,
    /// Whether the lock-up is the helix's: the plain soft string delivers the WOB, the soft
    /// string with the helix's drag (`models::helical_drag`) does not; `hook_load_n` and
    /// `max_wob_n` are then that soft string's.
    pub by_helix: bool,
    /// For a lock-up by the helix's drag: where the soft string with the helix's drag is
    /// helically buckled at its largest WOB, MD of the highest and lowest helical point, m.
    pub helical_md_m: Option<(f64, f64)>,
    /// For a lock-up by the helix's drag with results below it: whether their WOB is the
    /// largest the whole string delivers along its slack-off path (its hook load within the
    /// climb's tolerance of zero); false where that path met a limit first (then the WOB is a
    /// lower bound of the largest).
    pub results_at_largest_wob: bool,
    /// For a lock-up by the helix's drag: the results are those of a level whose soft string
    /// has no helix's drag (`soft`, `hybrid`) at the WOB asked for, their hook load not below
    /// zero.
    pub results_without_helical_drag: bool,
    /// The results are a cut model's (`bha`), which has no hook load, at the WOB asked for: the
    /// lock-up is the soft string's at that WOB.
    pub results_without_hook_load: bool,
    /// Running in (`trip_in`): the string cannot be run in to the bit depth (no WOB; `wob_n` and
    /// `max_wob_n` are 0).
    pub running_in: bool,
    /// The whole string found no equilibrium on bottom and the string cannot be put on bottom
    /// at any WOB at this bit depth (`max_wob_n` zero): the results are the soft string's at the
    /// WOB asked for (`solve --fidelity whole` answers with the `soft` level).
    pub results_from_soft_string: bool,
    /// The bit depths from which the string locks up at the WOB asked for and at zero WOB
    /// ([`crate::models::lock_up_depth`]); None where not computed (`loads` rows).
    pub depths: Option<LockUpDepths>,
}

impl LockUp {
    /// A lock-up by the helix's drag whose soft string's compression diverged up the helix: its
    /// hook load a flag, not a load ([`crate::models::helical_drag::DIVERGED_HOOK_LOAD_N`]).
    pub fn helical_drag_diverged(&self) -> bool {
        self.by_helix && diverged(self.hook_load_n)
    }

    /// The lock-up by the helix's drag `h` ([`LockUp::by_helix`]), its results at the WOB asked
    /// for.
    pub fn by_helix(h: &HelicalLockUp) -> LockUp {
        LockUp {
            by_helix: true,
            helical_md_m: h.helical_md_m,
            ..LockUp::at(h.hook_load_n, h.wob_n, h.max_wob_n)
        }
    }

    /// A lock-up with the hook load `hook_load_n`, the WOB asked for `wob_n` and the largest WOB
    /// `max_wob_n` (N): its results at the WOB asked for, no flag set, no depths computed.
    fn at(hook_load_n: f64, wob_n: f64, max_wob_n: f64) -> LockUp {
        LockUp {
            hook_load_n,
            wob_n,
            max_wob_n,
            results_at_wob_n: None,
            by_helix: false,
            helical_md_m: None,
            results_at_largest_wob: false,
            results_without_helical_drag: false,
            results_without_hook_load: false,
            running_in: false,
            results_from_soft_string: false,
            depths: None,
        }
    }

    /// The lock-up with its lock-up depths computed for `case` at the WOB asked for
    /// ([`lock_up_depths`]), by the soft string of its largest WOB (with the helix's drag for a
    /// lock-up by the helix).
    pub fn with_depths(self, case: &Case) -> LockUp {
        let drag = match (self.by_helix, self.running_in) {
            (true, _) => Drag::WithHelix,
            (false, true) => Drag::of(case, 0.0),
            (false, false) => Drag::Plain,
        };
        LockUp {
            depths: Some(lock_up_depths(case, self.wob_n, drag)),
            ..self
        }
    }

    /// The warning of a lock-up running in ([`running_in_lock_up`], or by the helix's drag
    /// [`crate::models::helical_drag::helical_running_in_lock_up`]).
    fn running_in_warning(&self) -> String {
        let depth = self
            .depths
            .filter(|d| !d.locked_everywhere())
            .and_then(|d| {
                Some(format!(
                    "; lock-up depth (by the {}, the string refitted to each bit depth of the surveyed hole): {}",
                    d.drag.name(),
                    d.running_in_clause(metres)?
                ))
            })
            .unwrap_or_default();
        let soft = match self.results_from_soft_string {
            true => "; the whole string finds no equilibrium running in to this depth: no stiff-string results exist there, and the results are the soft string's (`fidelity.used` soft)",
            false => "",
        };
        let without_helix = match self.results_without_helical_drag {
            true => "; the results are from a soft string without the helix's drag: their hook load, not below zero, is one the string cannot give",
            false => "",
        };
        let (what, cause) = match self.by_helix {
            true => (
                format!(
                    "helical lock-up running in: the pipe buckles into a helix whose wall force and drag grow faster than its weight; by the soft string with the helix's drag (Mitchell's r F^2/(4 EI)) its hook load is {:.0} kN{}",
                    self.hook_load_n / 1e3,
                    self.helical_md_m
                        .map(|(top, bottom)| format!(" (helically buckled at {top:.0}-{bottom:.0} m MD)"))
                        .unwrap_or_default()
                ),
                "the helix",
            ),
            false => (
                format!("lock-up running in: hook load {:.0} kN below zero", self.hook_load_n / 1e3),
                "the compressed part",
            ),
        };
        format!(
            "{what}, the surface would have to push the string down to run it in to this depth: less friction, rotation while running in, or heavier pipe above {cause}{depth}{soft}{without_helix}"
        )
    }

    /// The warning's clause on the lock-up depths (empty where not computed).
    fn depth_clause(&self) -> String {
        match self.depths.and_then(|d| d.sentence(self.wob_n)) {
            Some(d) => format!("; {d}"),
            None => String::new(),
        }
    }

    /// The warning to print.
    pub fn warning(&self, mode: &str) -> String {
        if self.running_in {
            return self.running_in_warning();
        }
        if self.by_helix {
            return self.helical_warning(mode);
        }
        let at = match self.results_at_wob_n {
            Some(w) => format!(
                "; the whole string finds no equilibrium at {:.0} kN: the results are at the largest WOB it delivers, {:.1} kN (its hook load zero)",
                self.wob_n / 1e3,
                w / 1e3
            ),
            None if self.results_without_hook_load => BHA_RESULTS_CLAUSE.to_string(),
            None if self.results_from_soft_string => SOFT_RESULTS_CLAUSE.to_string(),
            None => String::new(),
        };
        format!(
            "lock-up: hook load {:.0} kN below zero, the surface would have to push the string down to put {:.0} kN on the bit while {mode}; the string can deliver at most about {:.0} kN WOB (soft string, hook load zero): less WOB or friction, rotation, or heavier pipe above the compressed part{}{at}",
            self.hook_load_n / 1e3,
            self.wob_n / 1e3,
            self.max_wob_n / 1e3,
            self.depth_clause()
        )
    }
}

/// The clause of a lock-up warning whose results are a cut model's (`bha`), which has no hook
/// load ([`LockUp::results_without_hook_load`]).
const BHA_RESULTS_CLAUSE: &str = "; the results are the bottom-hole assembly's at the WOB asked for (the `bha` model has no hook load), a WOB the string cannot deliver";

/// The clause of a lock-up warning whose results are the soft string's because the whole string
/// has no equilibrium on bottom at any WOB ([`LockUp::results_from_soft_string`]).
const SOFT_RESULTS_CLAUSE: &str = "; the whole string finds no equilibrium on bottom, and at this bit depth the string cannot be put on bottom at any WOB (lock-up at zero WOB): no stiff-string results exist there, and the results are the soft string's at the WOB asked for (`fidelity.used` soft)";

impl LockUp {
    /// The warning of a lock-up by the helix's drag ([`LockUp::by_helix`]).
    fn helical_warning(&self, mode: &str) -> String {
        let asked = self.wob_n / 1e3;
        let at = match self.results_at_wob_n {
            Some(w) if self.results_at_largest_wob => format!(
                "; the whole string finds no equilibrium at {asked:.0} kN, and its results are at the largest WOB it delivers along its slack-off path, {:.1} kN (its hook load near zero; solved from the buckled shape, docs/guide.md)",
                w / 1e3
            ),
            Some(w) => format!(
                "; the whole string finds no equilibrium at {asked:.0} kN, and its results are at {:.1} kN, where its slack-off path met a limit: the largest WOB it delivers lies between {:.1} kN and about {:.0} kN (solved from the buckled shape, docs/guide.md)",
                w / 1e3,
                w / 1e3,
                self.max_wob_n / 1e3
            ),
            None if self.results_without_hook_load => BHA_RESULTS_CLAUSE.to_string(),
            None if self.results_from_soft_string => format!(
                "{SOFT_RESULTS_CLAUSE}: a soft string without the helix's drag, whose hook load, not below zero, is one the string cannot give"
            ),
            None if self.results_without_helical_drag => format!(
                "; the results are at the WOB asked for, from a soft string without the helix's drag: their hook load, not below zero, is one the string cannot give ({})",
                if self.max_wob_n > 0.0 {
                    "`--fidelity whole` solves the stiff string, which forms the helix, below the lock-up"
                } else {
                    "at this bit depth the string cannot be put on bottom at any WOB"
                }
            ),
            None => "; the results are at the WOB asked for, where the solved string's hook load is below zero too (the surface pushing)".to_string(),
        };
        let helix = match self.helical_md_m {
            Some((top, bottom)) => format!(" (helically buckled at {top:.0}-{bottom:.0} m MD there)"),
            None => String::new(),
        };
        let hook = if self.helical_drag_diverged() {
            "its compression diverges up the helix".to_string()
        } else {
            format!("its hook load is {:.0} kN", self.hook_load_n / 1e3)
        };
        format!(
            "helical lock-up: the pipe buckles into a helix whose wall force and drag grow faster than its weight; by the soft string with the helix's drag (Mitchell's r F^2/(4 EI)) {hook}, the surface would have to push to put {:.0} kN on the bit while {mode}, and it delivers at most about {:.0} kN WOB{helix}: less WOB or friction, rotation, or heavier pipe above the helix{}{at}",
            self.wob_n / 1e3,
            self.max_wob_n / 1e3,
            self.depth_clause()
        )
    }
}

/// The lock-up of `case` on bottom when `hook_load_n` is below zero (a WOB input; with a hook
/// load input the WOB follows from it): the largest WOB from the soft string at hook load zero.
pub fn lock_up(case: &Case, hook_load_n: Option<f64>, wob_n: f64) -> Option<LockUp> {
    let h = hook_load_n?;
    if h >= 0.0 || !case.operation.mode.on_bottom() || case.operation.hook_load_n.is_some() {
        return None;
    }
    let soft = softstring::at_zero_hook_load(case, softstring::segment_length_m(&case.solver));
    let max_wob_n = (-soft.points.first()?.tension_n).max(0.0);
    Some(LockUp::at(h, wob_n, max_wob_n))
}

/// The lock-up of `case` at the WOB `wob_n` (N) by the soft string's hook load there.
pub fn soft_lock_up_at(case: &Case, wob_n: f64) -> Option<LockUp> {
    let mut c = case.clone();
    c.operation.wob_n = wob_n;
    let hook = softstring::from_case(&c, softstring::segment_length_m(&c.solver)).hook_load_n;
    lock_up(&c, Some(hook), wob_n)
}

/// The soft string's lock-up of `case` at its WOB: the plain soft string's, else the one with
/// the helix's drag ([`crate::models::helical_drag::helical_lock_up`], which is None where the
/// plain one is locked up); None where neither is locked up.
pub fn soft_lock_up(case: &Case) -> Option<LockUp> {
    soft_lock_up_at(case, case.operation.wob_n)
        .or_else(|| crate::models::helical_drag::helical_lock_up(case).map(|h| LockUp::by_helix(&h)))
}

/// Whether the soft string of `case`'s lock-up delivers no WOB at all at its bit depth (the
/// largest WOB of [`soft_lock_up`] zero: that soft string, [`Drag::of`] the case's WOB, has a
/// hook load below zero at zero WOB): the string cannot be put on bottom there, so no
/// whole-string equilibrium on bottom exists and no WOB path can reach one. Running in
/// (`trip_in`, no WOB): whether the soft string of its lock-up, the plain one
/// ([`running_in_lock_up`]) or else the one with the helix's drag
/// ([`crate::models::helical_drag::helical_running_in_lock_up`]), cannot be run in to the bit
/// depth: the whole string then finds no equilibrium with the surface holding it.
pub fn locked_at_zero_wob(case: &Case) -> bool {
    let op = &case.operation;
    if op.hook_load_n.is_some() || !(op.mode.on_bottom() || op.mode == Mode::TripIn) {
        return false;
    }
    let drag = match op.mode {
        Mode::TripIn => Drag::of(case, 0.0),
        _ => Drag::of(case, op.wob_n),
    };
    hook_load_at_wob_n(case, 0.0, drag) < 0.0
}

/// The lock-up of `case` running in (`trip_in`) when `hook_load_n` is below zero: the surface
/// would have to push the string down to run it in to the bit depth.
pub fn running_in_lock_up(case: &Case, hook_load_n: Option<f64>) -> Option<LockUp> {
    let h = hook_load_n?;
    if h >= 0.0 || case.operation.mode != Mode::TripIn || case.operation.hook_load_n.is_some() {
        return None;
    }
    Some(LockUp {
        running_in: true,
        ..LockUp::at(h, 0.0, 0.0)
    })
}

/// The sharpest curvature a component can be bent to without its outer fibre yielding,
/// `yield / (E OD/2)`, rad/m (None without a yield strength: non-steel, none given).
pub fn yield_curvature_rad_m(c: &crate::string::component::Component) -> Option<f64> {
    let m = &c.material;
    let yield_pa = match m.yield_strength_pa {
        Some(y) => y,
        None if m.name == "steel" => assumed_steel_yield_pa(),
        None => return None,
    };
    Some(yield_pa / (m.youngs_modulus_pa * c.body_od_m / 2.0))
}

/// A warning when a survey interval the string lies in (MD up to the bit) is sharper than
/// some component above the bit (which is too short to bend) can be bent to without yielding ([`yield_curvature_rad_m`]): the string
/// cannot pass that dogleg elastically, whatever the solve says.
pub fn dogleg_warning(case: &Case) -> Option<String> {
    let path = &case.well.path;
    let (limit, name) = case
        .string
        .components
        .iter()
        .filter(|c| c.kind != crate::string::ComponentKind::Bit)
        .filter_map(|c| Some((yield_curvature_rad_m(c)?, c.name.as_str())))
        .min_by(|a, b| a.0.total_cmp(&b.0))?;
    let bit = case.operation.bit_md_m;
    let (dls, md) = (1..path.stations().len())
        .filter(|&k| path.stations()[k - 1].md_m < bit)
        .map(|k| (path.dls_before(k), path.stations()[k].md_m))
        .max_by(|a, b| a.0.total_cmp(&b.0))?;
    let per30 = |x: f64| x.to_degrees() * 30.0;
    (dls > limit).then(|| {
        format!(
            "the survey's dogleg of {:.1} deg/30 m in the interval ending at {md:.1} m MD is sharper than the string can pass: bent to it, `{name}` reaches its yield strength at {:.1} deg/30 m",
            per30(dls),
            per30(limit)
        )
    })
}
