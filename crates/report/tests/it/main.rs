//! The report crate's integration tests, as one binary: a module per
//! concern, each saying in its docs what it checks against what. One binary
//! links the dependencies once; a file under tests/it that no `mod` line here
//! declares is reported by .ci/structure.py, so none can silently go unrun.

mod common;
mod dma;
mod fitted_friction;
mod forward_master_pictures;
mod joint;
mod master_input;
mod pictures;
mod pressure_map_picture;
mod verdict;
