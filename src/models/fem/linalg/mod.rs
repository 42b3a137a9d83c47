//! Linear algebra of the global system: band matrices, their LDL^T and LU factorizations, a
//! pool of their storage, and the sparse (faer) reference used in the benchmarks.

pub mod band;
pub mod band_lu;
pub mod buffers;
pub mod sparse_faer;
