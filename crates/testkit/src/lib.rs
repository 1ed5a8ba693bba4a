//! Fixtures shared by rollfit's tests and benches, in the manner of linfa's
//! datasets crate: one definition of each test material, synthetic data
//! generator and helper, so that tests in different crates agree on what
//! "the bundled rubber" or "a broad Prony series" is.
//!
//! A dev-dependency only (`publish = false`): it depends on model and fit,
//! and nothing depends on it but tests and benches.
//!
//! - [`materials`]: the test materials (Havriliak–Negami rubbers, standard
//!   linear solids, Prony series of fixed and random shapes, a seeded LCG).
//! - [`scenes`]: scenes of the model crate built in one call.
//! - [`jacobian`]: the finite-difference check of ∂μ/∂(E1, H_k).
//! - [`rolling`]: rolling set-ups and synthetic μ(v) measurements with
//!   seeded noise, single and temperature sets; accuracy and coverage of a
//!   fitted curve against its truth.
//! - [`broad_polymer`], [`joint_case`]: two synthetic replicas of real
//!   data (a stiff polymer's broad spectrum with kinked shifts; DMA
//!   isotherms and rolling friction of one two-process rubber).
//! - [`series`]: a Prony series written out (E′, E″ by hand) and WLF, the
//!   independent side of the file-reading tests.
//! - [`files`]: temporary folders, folder snapshots, the workspace root.
//! - [`csv`]: the numbers of a CSV file the tool wrote.
//! - [`workbook`]: .xlsx and .ods workbooks written in the tests.
//! - [`run`]: running a binary and checking the promise of a refusal.
//! - [`contract`]: names the contract fixes (the keys of compare.json).

pub mod broad_polymer;
pub mod contract;
pub mod csv;
pub mod eplexor;
pub mod files;
pub mod jacobian;
pub mod joint_case;
pub mod materials;
pub mod rolling;
pub mod run;
pub mod scenes;
pub mod series;
pub mod workbook;
