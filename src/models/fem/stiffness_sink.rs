//! Where the assembly writes stiffness blocks: the symmetric band (lower triangle read) or the
//! general band (all entries read), behind one trait.

use super::element::corotational::Mat12;
use super::linalg::band::BandMatrix;
use super::linalg::band_lu::GeneralBand;

/// Where assembled stiffness blocks go: the symmetric band (lower triangle read) or the
/// general band (all entries read).
pub trait StiffnessSink {
    /// Zero all entries.
    fn clear(&mut self);
    /// `A[dofs[r], dofs[c]] += k[r * ld + c]`.
    fn add_block(&mut self, dofs: &[usize], k: &[f64], ld: usize);
    /// Zero the stored entries of the storage lines of `dofs` (rows of the general band,
    /// columns of the symmetric band's lower triangle). On the node chain these lines hold
    /// exactly the entries that the blocks touching those DOFs' node write, so an assembly
    /// that calls this for each node just before the first block touching it needs no
    /// [`StiffnessSink::clear`] (and no separate pass over the whole matrix).
    fn clear_dofs(&mut self, dofs: std::ops::Range<usize>);
    /// `A[first + r, first + c] += k[(r, c)]` for an element's 12 consecutive DOFs.
    fn add_element(&mut self, first: usize, k: &Mat12) {
        let dofs: [usize; 12] = std::array::from_fn(|j| first + j);
        self.add_block(&dofs, k.transpose().as_slice(), 12);
    }
}

impl StiffnessSink for BandMatrix {
    fn clear(&mut self) {
        self.fill_zero();
    }
    fn add_block(&mut self, dofs: &[usize], k: &[f64], ld: usize) {
        BandMatrix::add_block(self, dofs, k, ld);
    }
    fn clear_dofs(&mut self, dofs: std::ops::Range<usize>) {
        BandMatrix::clear_columns(self, dofs);
    }
}

impl StiffnessSink for GeneralBand {
    fn clear(&mut self) {
        self.fill_zero();
    }
    fn add_block(&mut self, dofs: &[usize], k: &[f64], ld: usize) {
        GeneralBand::add_block(self, dofs, k, ld);
    }
    fn clear_dofs(&mut self, dofs: std::ops::Range<usize>) {
        GeneralBand::clear_rows(self, dofs);
    }
    fn add_element(&mut self, first: usize, k: &Mat12) {
        GeneralBand::add_block_12(self, first, k.as_slice());
    }
}
