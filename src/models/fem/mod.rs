//! Finite element model of the stiff string: co-rotational space beams from the bit to the
//! top, contact-friction gap elements at the nodes that can touch the wall, and the contact
//! Newton solution.
//!
//! - [`element`]: the beam element (section, co-rotational kinematics, rotations);
//! - [`contact`]: the gap element (normal force, friction force and torque);
//! - [`mesh`], [`model`]: the mesh along the hole, the model's state and its assembly;
//! - [`kink`]: the bent housing of a motor, a kink of the unloaded axis;
//! - [`linalg`]: band matrices and their factorizations;
//! - [`solve`]: the contact Newton solvers;
//! - [`bha`]: the bottom-hole assembly cut where it lies on the wall;
//! - [`results`]: bit forces, contacts, forces and stresses along the string;
//! - [`warm`]: carrying a solved state onto a moved or lengthened model;
//! - [`refine`]: the assembly's mesh refined where a collar comes onto the wall.

pub mod bha;
pub mod condense;
pub mod condensed_top;
pub mod contact;
pub mod element;
pub mod kink;
pub mod linalg;
pub mod mesh;
pub mod model;
pub mod model_top;
pub mod pin_reaction;
pub mod reactive;
pub mod refine;
pub mod results;
pub mod solve;
pub mod stiffness_sink;
pub mod warm;
