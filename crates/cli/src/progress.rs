//! Progress on stderr for what can take more than a couple of seconds
//!: exact-physics fits, batches, exact and `auto` forward sweeps,
//! `master`. Bars are for a person at a terminal and are kept out of logs
//! and pipes: they are drawn only when stderr is a terminal, and
//! `ROLLFIT_PROGRESS=never` hides them there too (a terminal recorder, a
//! screen reader). Everything a bar shows is also in the messages a command
//! prints when it ends, so hiding it loses nothing; and a bar only watches,
//! so stdout and every file are the same with and without one.
//!
//! The switch is [`shown`], a function of the two facts it depends on, so
//! that a test can check it without a terminal; the end-to-end test runs
//! the binary under a pseudo-terminal (`script`) and through a pipe.

use std::io::IsTerminal;
use std::sync::Arc;
use std::time::Duration;

use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
use rollfit_fit::{Observer, Progress};

/// The environment variable that hides progress bars on a terminal.
pub const PROGRESS_VARIABLE: &str = "ROLLFIT_PROGRESS";

/// Whether bars are drawn: only on a terminal (`stderr_is_terminal`), and
/// not when [`PROGRESS_VARIABLE`] says `never` (or `0`, `off`, `no`).
pub fn shown(stderr_is_terminal: bool, setting: Option<&str>) -> bool {
    let refused = setting.is_some_and(|s| {
        matches!(
            s.trim().to_ascii_lowercase().as_str(),
            "never" | "0" | "off" | "no" | "false"
        )
    });
    stderr_is_terminal && !refused
}

/// [`shown`] for this process.
pub fn shown_here() -> bool {
    let setting = std::env::var(PROGRESS_VARIABLE).ok();
    shown(std::io::stderr().is_terminal(), setting.as_deref())
}

/// Where bars go: stderr when [`shown_here`], else nowhere (a hidden bar
/// costs a counter).
fn target() -> ProgressDrawTarget {
    if shown_here() {
        ProgressDrawTarget::stderr()
    } else {
        ProgressDrawTarget::hidden()
    }
}

/// A bar of `total` steps named `what` ("exact solves", "fits"; None: not
/// known yet): count, elapsed time, time left and a message.
pub fn bar(total: Option<u64>, what: &str) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(total, target());
    // Short enough to leave the message room on an 80-column terminal.
    let template =
        format!("{{bar:20}} {{pos}}/{{len}} {what}, {{elapsed}}, ~{{eta}} left  {{wide_msg}}");
    if let Ok(style) = ProgressStyle::with_template(&template) {
        bar.set_style(style);
    }
    // Redrawn while a long step runs, so the elapsed time moves.
    bar.enable_steady_tick(Duration::from_millis(250));
    bar
}

/// A spinner for work without a count known in advance, with a message.
pub fn spinner(message: String) -> ProgressBar {
    let bar = ProgressBar::with_draw_target(None, target());
    if let Ok(style) = ProgressStyle::with_template("{spinner} {elapsed} {wide_msg}") {
        bar.set_style(style);
    }
    bar.set_message(message);
    bar.enable_steady_tick(Duration::from_millis(250));
    bar
}

/// The bar of an exact-physics fit: exact solves done out of those planned
/// so far (the total grows as the defect correction plans its sweeps),
/// the stage as its message.
struct FitBar(ProgressBar);

impl Progress for FitBar {
    fn stage(&self, what: &str) {
        self.0.set_message(what.to_string());
    }
    fn planned(&self, count: usize) {
        // Unknown until the first sweep is planned (the approximate fit
        // runs first), so that the bar is not drawn full of nothing.
        let before = self.0.length().unwrap_or(0);
        self.0.set_length(before + count as u64);
    }
    fn solved(&self) {
        self.0.inc(1);
    }
}

/// An observer for a fit and its bar (finish it with
/// [`ProgressBar::finish_and_clear`] before printing the summary).
pub fn fit_observer() -> (Observer, ProgressBar) {
    let bar = bar(None, "exact solves");
    (Observer::new(Arc::new(FitBar(bar.clone()))), bar)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn bars_only_on_a_terminal_unless_refused() {
        assert!(shown(true, None));
        assert!(shown(true, Some("auto")));
        assert!(!shown(false, None), "a pipe or a log gets no bar");
        assert!(
            !shown(false, Some("always")),
            "no setting draws into a pipe"
        );
        for refused in ["never", "NEVER", "0", "off", " no "] {
            assert!(!shown(true, Some(refused)), "{refused}");
        }
    }

    /// A hidden bar counts as a shown one does: the observer changes no
    /// state the fit reads.
    #[test]
    fn the_fit_observer_counts_planned_and_solved() {
        let bar = ProgressBar::hidden();
        bar.unset_length();
        let observer = FitBar(bar.clone());
        observer.planned(3);
        observer.planned(2);
        observer.solved();
        observer.stage("refit 1");
        assert_eq!((bar.position(), bar.length()), (1, Some(5)));
        assert_eq!(bar.message(), "refit 1");
    }
}
