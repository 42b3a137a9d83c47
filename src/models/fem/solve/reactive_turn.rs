//! The turn of a sliding bent housing's toolface by the motor's reactive torque in a solved
//! state (docs/theory.md 9.9, "Reactive torque"; the torque and the string above a cut model:
//! [`crate::models::fem::reactive`]).

use super::Solution;
use crate::models::fem::model::{Model, TopCondition};
use crate::models::fem::reactive::ReactiveTurn;

impl Model {
    /// The turn of the bent housing's toolface by the motor's reactive torque in `sol` (None
    /// without [`Model::reactive`] or a kink): the housing below the bend holds the capacity
    /// `μ N r` of its contacts (not the bit's gauge, which turns with the shaft), the torque left enters the string at the bend and falls by each
    /// contact's capacity above it; the turn is the twist `∫ T / (G J) ds` of the model's
    /// elements from the bend to where the torque is taken up, continued above a cut model's
    /// top along [`crate::models::fem::reactive::ReactiveTorque::string`] (a whole string's top, the rotary table, holds the
    /// rest).
    pub fn reactive_turn(&self, sol: &Solution) -> Option<ReactiveTurn> {
        let r = self.reactive.as_ref()?;
        let bend = self.kink?.node;
        // the bit's gauge turns with the motor's shaft: it holds nothing
        let cap = |i: usize| match &sol.eval.gaps[i] {
            Some(g) if g.normal_force > 0.0 && !self.mesh.nodes[i].on_bit_gauge => {
                self.friction[i] * g.normal_force * self.mesh.nodes[i].contact_od_m / 2.0
            }
            _ => 0.0,
        };
        let mut t = r.torque_nm - (0..=bend).map(cap).sum::<f64>();
        let mut turn = 0.0;
        let done = |turn: f64, held: Option<f64>| ReactiveTurn {
            torque_nm: r.torque_nm,
            turn_rad: turn,
            held_m: held,
        };
        if t <= 0.0 {
            return Some(done(0.0, Some(self.mesh.nodes[bend].s_m)));
        }
        for e in bend..self.sections.len() {
            turn += t * self.sections[e].l0 / self.sections[e].gj;
            t -= cap(e + 1);
            if t <= 0.0 {
                return Some(done(turn, Some(self.mesh.nodes[e + 1].s_m)));
            }
        }
        if matches!(self.top, TopCondition::Surface) {
            return Some(done(turn, None));
        }
        let top = self.mesh.nodes.last().map(|n| n.s_m).unwrap_or(0.0);
        for p in r.string.iter().filter(|p| p.top_m > top) {
            let len = p.top_m - p.bottom_m.max(top);
            let c = p.capacity_nm_per_m;
            if c * len >= t {
                // the torque falls linearly to zero within the piece
                let x = t / c;
                return Some(done(turn + t * x / (2.0 * p.gj_nm2), Some(p.top_m - len + x)));
            }
            turn += (t * len - c * len * len / 2.0) / p.gj_nm2;
            t -= c * len;
        }
        Some(done(turn, None))
    }
}
