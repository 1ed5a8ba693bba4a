//! The errors of building a master curve from a DMA file
//! ([`DmaMasterError`], reached as [`super::IoError::Master`]; built by
//! [`crate::dma_master`] for `rollfit master` and a scene's
//! `[material] model = "dma"`, docs/ARCHITECTURE.md, "Contract", "DMA
//! files"). What the fit library refuses is wrapped by a variant naming
//! the file ([`DmaMasterError::InFile`], [`DmaMasterError::MasterCurve`]),
//! whose source `{:#}` prints after it.

use std::fmt;

/// A point of an isotherm where its sweep turns, as a message names it:
/// `line 13: ω = 5.2e0 rad/s`, or `point 7: …` where the file has no line
/// for it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct TurnPoint {
    /// The point's file line, if known.
    pub line: Option<usize>,
    /// Its index among the file's points, from 0.
    pub index: usize,
    /// Its frequency, rad/s.
    pub omega: f64,
}

impl fmt::Display for TurnPoint {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self.line {
            Some(l) => write!(f, "line {l}: ω = {:e} rad/s", self.omega),
            None => write!(f, "point {}: ω = {:e} rad/s", self.index + 1, self.omega),
        }
    }
}

/// `line 12: ω = …, line 13: ω = …`.
pub(crate) fn turn_list(turn: &[TurnPoint]) -> String {
    let listed: Vec<String> = turn.iter().map(TurnPoint::to_string).collect();
    listed.join(", ")
}
