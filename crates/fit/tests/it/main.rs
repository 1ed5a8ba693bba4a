//! The fit crate's integration tests, as one binary: a module per concern,
//! each saying in its docs what it checks against what. One binary links the
//! dependencies once; a file under tests/it that no `mod` line here declares
//! is reported by .ci/structure.py, so none can silently go unrun.

mod broad_spectrum;
mod cancel;
mod coverage;
mod exact_physics;
mod exact_profile;
mod fit_cost;
mod grid_rule;
mod joint;
mod joint_broad;
mod recovery;
mod relaxation;
mod shift_law;
mod sparse;
mod stability;
mod temperature_set;
mod tset_cost;
mod unanchored;
mod verdict;
