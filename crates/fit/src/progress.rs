//! Progress of a long fit, told to an observer the caller gives:
//! the fit is the problem, the observer how a front end shows it (a bar on
//! a terminal, nothing in a log). The library draws nothing itself, so it
//! needs no terminal crate, and an observer can only watch: it is given
//! counts, never asked for anything, so a fit with one gives the same
//! numbers bit for bit as a fit without.
//!
//! Today the exact-physics fit (`physics = "exact"`, `exact_physics.rs`)
//! reports its exact solves, the part that takes seconds to minutes; the
//! approximate fit around them takes a fraction of a second and reports
//! only that it runs.

use std::fmt;
use std::sync::Arc;

/// What a long fit tells its caller. Every method has an empty default, so
/// an observer implements what it shows. Called from the solver threads,
/// hence `Send + Sync`.
pub trait Progress: Send + Sync {
    /// A stage begins: `"approximate fit"`, `"exact sweep 1"`, `"refit 1"`
    /// (short: a bar on an 80-column terminal leaves its message about 25
    /// characters).
    fn stage(&self, _what: &str) {}
    /// `count` more exact solves are planned (a sweep's batch; the total
    /// grows as adaptive sweeps decide where else to solve).
    fn planned(&self, _count: usize) {}
    /// One exact solve finished.
    fn solved(&self) {}
}

/// The observer a fit's settings hold: none by default.
#[derive(Clone, Default)]
pub struct Observer(Option<Arc<dyn Progress>>);

impl Observer {
    /// Tells `progress` what the fit does.
    pub fn new(progress: Arc<dyn Progress>) -> Observer {
        Observer(Some(progress))
    }

    pub(crate) fn stage(&self, what: &str) {
        if let Some(p) = &self.0 {
            p.stage(what);
        }
    }

    pub(crate) fn planned(&self, count: usize) {
        if let Some(p) = &self.0 {
            p.planned(count);
        }
    }

    pub(crate) fn solved(&self) {
        if let Some(p) = &self.0 {
            p.solved();
        }
    }
}

impl fmt::Debug for Observer {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(if self.0.is_some() {
            "Observer(watched)"
        } else {
            "Observer(none)"
        })
    }
}

/// Settings are compared by what they ask of the fit; who watches it is
/// not part of that (as with [`crate::Cancel`]).
impl PartialEq for Observer {
    fn eq(&self, _: &Observer) -> bool {
        true
    }
}
