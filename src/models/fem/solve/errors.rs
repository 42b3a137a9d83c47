//! Why a solve failed.

use crate::models::fem::linalg::band::FactorError;
use crate::models::fem::model::Model;

/// Why a solve failed.
#[derive(Debug, thiserror::Error)]
pub enum SolveError {
    /// The factorization met a zero pivot.
    #[error("singular stiffness at DOF {dof} (node {node} from the bit): {detail}")]
    Singular {
        /// DOF index.
        dof: usize,
        /// Node index from the bit.
        node: usize,
        /// Details.
        detail: String,
    },
}

/// A failed factorization of `model`'s system as a [`SolveError::Singular`] naming the node.
pub(crate) fn singular(model: &Model, e: FactorError) -> SolveError {
    match e {
        FactorError::ZeroPivot {
            column: dof,
            pivot,
            diagonal,
        } => SolveError::Singular {
            dof,
            node: model.nodes() - 1 - dof / 6,
            detail: format!(
                "pivot {pivot:.3e} against the diagonal entry {diagonal:.3e} it was reduced from (zero below 1e-14 of it, or not finite): nothing holds the string there in that direction"
            ),
        },
    }
}
