//! The bent housing of a motor in the stiff model: a kink of the unloaded string axis at the
//! bend node, oriented by the toolface (docs/theory.md, "Bent motors").

use super::mesh::Mesh;
use nalgebra::Matrix3;

/// A kink of the unloaded string axis (a bent motor housing, docs/theory.md "Bent motors"):
/// the element below the bend node has its upper end's section turned by the bend, so that
/// the string is stress-free when the part below the bend points `angle` off the part above,
/// toward the toolface.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kink {
    /// The element whose upper end (end A, at the bend node) carries the offset.
    pub element: usize,
    /// Rotation of that end's section relative to the bend node's material triad, in the
    /// triad's own (material) components: `Lambda_section = Lambda_node offset`.
    pub offset: Matrix3<f64>,
    /// The toolface the kink is turned to about the unloaded triads, rad (the model's
    /// toolface plus the correction for the twist of the string, [`super::solve::toolface::solve_holding_toolface`]).
    pub orientation_rad: f64,
    /// The bend node.
    pub node: usize,
}

impl Kink {
    /// The kink of `mesh`'s bend at toolface `toolface_rad` (rad) with the DOF bases `basis`
    /// (the unloaded triads) of the nodes: the part below the bend turned by the bend angle
    /// about `t x d`, `d` the toolface direction ([`crate::geometry::frame::toolface_direction`])
    /// at the bend node, so that the bit points toward `d`. None for a straight mesh or a zero
    /// angle (a neutral point-the-bit tool).
    pub fn of_mesh(mesh: &Mesh, basis: &[Matrix3<f64>], toolface_rad: f64) -> Option<Kink> {
        let bend = mesh.bend.filter(|b| b.angle_rad != 0.0)?;
        let q = &basis[bend.node];
        let t = q.column(0).into_owned();
        let d = crate::geometry::frame::toolface_direction(&t, toolface_rad);
        let axis = t.cross(&d).normalize() * bend.angle_rad;
        Some(Kink {
            orientation_rad: toolface_rad,
            node: bend.node,
            element: bend.node - 1,
            offset: super::element::rotation::exp_so3(&(q.transpose() * axis).into_owned()),
        })
    }
}
