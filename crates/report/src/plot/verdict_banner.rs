//! A picture's verdict, when it is not "good": a banner across the top of
//! the master-curve pictures in the title's size and a warning colour,
//! "Verdict: poor", with the head of each reason (the words before its
//! first colon or semicolon: the cause, without the advice master.json
//! carries in full). A good verdict draws nothing and takes no room, so
//! that a picture shown apart from master.json still says whether to
//! trust it.

use plotters::coord::Shift;
use plotters::prelude::*;
use plotters::style::text_anchor::{HPos, VPos};

use super::isotherm_key::text_style;
use super::{DrawResult, style};

/// The verdict on what a picture shows, as master.json's `quality`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Verdict<'a> {
    /// "good", or another verdict ("poor").
    pub verdict: &'a str,
    /// Why, each a sentence; empty when good.
    pub reasons: &'a [String],
}

/// Reasons named in the banner; more are counted.
const MAX_REASONS: usize = 3;
/// Characters of a reason's head the banner keeps (about 1050 px).
const MAX_HEAD: usize = 130;
/// Height of the title line and of a reason line, px.
const TITLE_HEIGHT: u32 = 34;
const REASON_HEIGHT: u32 = 20;

impl Verdict<'_> {
    /// Whether the verdict is shown: anything but "good".
    fn shown(&self) -> bool {
        self.verdict != "good"
    }

    /// The banner's lines: the title, then a line per reason named.
    fn lines(&self) -> Vec<String> {
        if !self.shown() {
            return Vec::new();
        }
        let mut lines = vec![format!(
            "Verdict: {} — see master.json's \"quality\"",
            self.verdict
        )];
        lines.extend(self.reasons.iter().take(MAX_REASONS).map(|r| head(r)));
        if self.reasons.len() > MAX_REASONS {
            lines.push(format!(
                "… and {} more reasons",
                self.reasons.len() - MAX_REASONS
            ));
        }
        lines
    }

    /// The banner's height, px: 0 when good.
    pub(crate) fn height(verdict: Option<&Verdict>) -> u32 {
        match verdict.map(Verdict::lines) {
            Some(lines) if !lines.is_empty() => {
                TITLE_HEIGHT + REASON_HEIGHT * (lines.len() as u32 - 1) + 8
            }
            _ => 0,
        }
    }

    /// Draws the banner on `area` (of [`Verdict::height`]).
    pub(crate) fn draw<DB>(&self, area: &DrawingArea<DB, Shift>) -> DrawResult
    where
        DB: DrawingBackend,
        DB::ErrorType: 'static,
    {
        let lines = self.lines();
        let Some((title, reasons)) = lines.split_first() else {
            return Ok(());
        };
        let (w, _) = area.dim_in_pixel();
        let x = w as i32 / 2;
        let colour = |size: u32| text_style(size, HPos::Center, VPos::Top).color(&style::VERDICT);
        area.draw(&Text::new(title.clone(), (x, 8), colour(style::CAPTION)))?;
        for (i, line) in reasons.iter().enumerate() {
            area.draw(&Text::new(
                line.clone(),
                (
                    x,
                    TITLE_HEIGHT as i32 + 4 + (REASON_HEIGHT * i as u32) as i32,
                ),
                colour(style::LEGEND),
            ))?;
        }
        Ok(())
    }
}

/// The cause a reason names: its words before the first colon or
/// semicolon, cut to [`MAX_HEAD`] characters.
fn head(reason: &str) -> String {
    let end = reason.find([':', ';']).unwrap_or(reason.len());
    let head = reason[..end].trim();
    if head.chars().count() <= MAX_HEAD {
        return head.to_string();
    }
    let cut: String = head.chars().take(MAX_HEAD - 1).collect();
    format!("{cut}…")
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_reason_is_shown_by_its_cause() {
        assert_eq!(
            head("the shifts are not determined by the overlap: only 2 of 9 isotherms"),
            "the shifts are not determined by the overlap"
        );
        assert_eq!(head("a; b: c"), "a");
        assert_eq!(head(&"x".repeat(200)).chars().count(), MAX_HEAD);
        let reasons: Vec<String> = (0..5).map(|i| format!("reason {i}: fix")).collect();
        let poor = Verdict {
            verdict: "poor",
            reasons: &reasons,
        };
        let lines = poor.lines();
        assert_eq!(lines.len(), 1 + MAX_REASONS + 1, "{lines:?}");
        assert_eq!(lines[1], "reason 0");
        assert!(lines[4].contains("2 more"));
        let good = Verdict {
            verdict: "good",
            reasons: &[],
        };
        assert_eq!(Verdict::height(Some(&good)), 0);
        assert_eq!(Verdict::height(None), 0);
        assert!(Verdict::height(Some(&poor)) > TITLE_HEIGHT);
    }
}
