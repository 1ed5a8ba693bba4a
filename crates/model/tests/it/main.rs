//! The model crate's integration tests, as one binary: a module per concern,
//! each saying in its docs what it checks against what. One binary links the
//! dependencies once; a file under tests/it that no `mod` line here declares
//! is reported by .ci/structure.py, so none can silently go unrun.

mod eq11_error_map;
mod exact_cylinder;
mod exact_plane_strain;
mod exact_sphere;
mod exact_sphere_dissipation;
mod exact_sphere_oracle;
mod exact_warm_start;
mod extremes;
mod film_cylinder_oracle;
mod film_sphere;
mod film_sphere_oracle;
mod gradient;
mod ladder;
mod limits;
mod reference_values;
mod table_friction;
mod tolerance;
mod vertical_factor;
