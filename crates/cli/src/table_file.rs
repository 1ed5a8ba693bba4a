//! The modulus-table reader of a scene's `model = "table"`,
//! [`rollfit_io::table`] (docs/ARCHITECTURE.md, "Contract", "Scene file"),
//! under the path and name `scene_file.rs` uses. Its errors and notes name
//! the file and speak the scene's words (`[substrate] poisson`,
//! `[material] modulus`).

pub use rollfit_io::table::{ModulusTable, read as read_with};
