//! The content of one output file: bytes encoded in memory, or an encoder
//! that writes them into the file as it goes. A result folder is staged
//! and swapped as a whole (`folder.rs`), so content written as it goes is
//! still all or nothing; it keeps a file that grows with the input (a
//! logger's mu.csv, several times the data file) out of memory.

use std::io::{self, Write};

/// What can be written into an output file.
pub trait FileContent {
    /// Writes the whole content to `out`.
    fn write_to(&self, out: &mut dyn Write) -> io::Result<()>;
}

impl FileContent for &[u8] {
    fn write_to(&self, out: &mut dyn Write) -> io::Result<()> {
        out.write_all(self)
    }
}

impl FileContent for Vec<u8> {
    fn write_to(&self, out: &mut dyn Write) -> io::Result<()> {
        out.write_all(self)
    }
}
