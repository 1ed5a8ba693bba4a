//! The file formats of rollfit (docs/ARCHITECTURE.md, "Crates" and
//! "Contract"): what the tool reads and writes, and how it writes it.
//!
//! - [`fit_dir`]: the fit folder, fit.json, mu.csv and modulus.csv, written
//!   and read back by one module with its names defined once
//!   ([`fit_dir::columns`]);
//! - [`dma`]: DMA files, the CSV form and the TRIOS LIMS export, as Young's
//!   moduli grouped into isotherms;
//! - [`csv_text`], [`csv_columns`], [`text_file`]: CSV text as rollfit
//!   writes it, what the CSV readers share, UTF-8 text with the place of a
//!   bad byte;
//! - [`output`]: atomic files, result folders swapped in as a whole, and
//!   the lock of a folder.
//!
//! Every function returns [`IoError`], whose messages name the file and,
//! where there is one, the line, column or key at fault. Nothing here
//! prints; the command line decides what a user sees.

pub mod csv_columns;
pub mod csv_text;
pub mod dma;
pub mod error;
pub mod fit_dir;
pub mod output;
pub mod text_file;

pub use error::{Fault, IoError};
pub use fit_dir::FitDir;
