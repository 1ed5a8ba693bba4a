//! The measured-data reader, [`rollfit_io::data`] (docs/ARCHITECTURE.md,
//! "Contract", "Measured data"), under the path `commands/fit.rs` and
//! `commands/bench.rs` import it by. Its errors name the file; what the
//! fit library then refuses of the data as a whole, the commands name the
//! file of themselves (`data file PATH: …`).

pub use rollfit_io::data::{DataTable, read, read_sheet};
