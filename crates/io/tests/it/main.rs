//! The io crate's integration tests, as one binary: a module per concern,
//! each saying in its docs what it checks against what. One binary links the
//! dependencies once; a file under tests/it that no `mod` line here declares
//! is reported by .ci/structure.py, so none can silently go unrun.

mod dma;
mod messages;
