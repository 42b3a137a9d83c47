//! The wall reaction of an exact pin (a zero-clearance gap: a full-gauge stabilizer or bit held
//! on the hole axis), with the lateral part of its friction.

use super::model::Model;
use crate::geometry::Vec3;

impl Model {
    /// Wall force vector `p` (N, perpendicular to `t`; the pin's normal force `|p|` along
    /// `p / |p|`) of an exact pin at node `i` whose wall force must balance the lateral force
    /// `a` (N): the force on the string is `-p` plus friction `-f |p| v^`, whose lateral part
    /// for the sliding velocity `v = v_a t + Omega R_c t x n` is `-f' t x p` with
    /// `f' = f Omega R_c / |v|`; so `p + f' t x p = a_perp`, solved as
    /// `p = (a_perp - f' t x a_perp) / (1 + f'^2)`.
    pub fn pin_reaction(&self, i: usize, t: &Vec3, a: &Vec3) -> Vec3 {
        let a = a - t * t.dot(a);
        let split = self
            .loads
            .motion()
            .friction_split(self.mesh.nodes[i].contact_od_m / 2.0);
        let fp = self.friction[i] * split.tangential;
        (a - t.cross(&a) * fp) / (1.0 + fp * fp)
    }
}
