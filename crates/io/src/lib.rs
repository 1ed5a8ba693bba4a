//! The file formats of rollfit (docs/ARCHITECTURE.md, "Crates" and
//! "Contract"): what the tool reads and writes, and how it writes it.
//!
//! - [`scene`]: the scene file of `forward`, `fit` and `bench`, its
//!   sections checked and turned into the model's objects;
//! - [`manifest`]: the batch manifest of `rollfit batch`;
//! - [`material_file`]: the material.toml `rollfit master` writes;
//! - [`data`]: measured rolling friction, text (`,`, `;` or tab, decimal
//!   commas, any common encoding) or a workbook, with header aliases and
//!   units converted to SI;
//! - [`table`]: modulus tables, the material of a scene's
//!   `model = "table"`: a plain `omega`/`f`, `E_storage`, `E_loss` CSV or
//!   any DMA form holding one temperature;
//! - [`fit_dir`]: the fit folder, fit.json, mu.csv and modulus.csv, written
//!   and read back by one module with its names defined once
//!   ([`fit_dir::columns`]);
//! - [`dma`]: DMA files, the CSV form and the TRIOS LIMS export, as Young's
//!   moduli, and relaxation and creep files; their points grouped into
//!   isotherms by the fit library's rule, each refusal naming its line
//!   (building master curves from them is the report crate's
//!   `master_input`, where commands are assembled);
//! - [`columns`]: column names shared by a writer and its readers beyond
//!   the fit folder's;
//! - [`pressure_map`]: the pressure maps of the exact rolling contact that
//!   `rollfit forward` writes beside its CSV, their file and column names;
//! - [`input_file`]: every input file's bytes, refused unopened when it is
//!   no regular file and read no further than the size limit;
//! - [`csv_text`], [`csv_columns`], [`text_file`]: CSV text as rollfit
//!   writes it, what the CSV readers share, UTF-8 text with the place of a
//!   bad byte;
//! - [`output`]: atomic files, result folders swapped in as a whole, and
//!   the lock of a folder.
//!
//! Every function returns [`IoError`], whose messages name the file and,
//! where there is one, the line, column or key at fault (a cause found
//! inside a file is the source of an error naming the file: `{:#}` prints
//! both, as the command line does).
//! Nothing here prints; the command line decides what a user sees (a
//! reader's notes reach it through a callback).

// First: its `err!` serves every module below.
#[macro_use]
pub mod error;
pub mod columns;
pub mod csv_columns;
pub mod csv_text;
pub mod data;
pub mod dma;
pub mod fit_dir;
pub mod input_file;
pub mod manifest;
pub mod material_file;
pub mod output;
pub mod pressure_map;
pub mod scene;
pub mod table;
pub mod text_file;
pub(crate) mod units;

pub use data::DataTable;
pub use error::{ErrorKind, IoError};
pub use fit_dir::FitDir;
pub use table::ModulusTable;

/// An error as the command line prints it (`{:#}` of anyhow): the message,
/// then each source after a colon. Also the text of the Python module's
/// exceptions (crates/python), so that both front doors say the same.
pub fn chain(error: &dyn std::error::Error) -> String {
    let mut text = error.to_string();
    let mut source = error.source();
    while let Some(s) = source {
        text += &format!(": {s}");
        source = s.source();
    }
    text
}
