//! Cancelling a fit from another thread: a flag the caller sets and the
//! driver reads before every solver run (a Python session's Ctrl-C,
//! crates/python). A fit that is never cancelled reads the flag and
//! nothing else, so its result is the same bit for bit; a cancelled one
//! ends at its next solver run with [`FitError::Cancelled`].

use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

use crate::error::FitError;

/// A shared cancellation flag: clones see the same flag.
#[derive(Debug, Clone, Default)]
pub struct Cancel(Arc<AtomicBool>);

impl Cancel {
    /// A flag not yet set.
    pub fn new() -> Cancel {
        Cancel::default()
    }

    /// Asks every fit holding this flag to stop.
    pub fn cancel(&self) {
        self.0.store(true, Ordering::Relaxed);
    }

    /// Whether the fit was asked to stop.
    pub fn is_cancelled(&self) -> bool {
        self.0.load(Ordering::Relaxed)
    }

    /// `Err(FitError::Cancelled)` once the flag is set.
    pub(crate) fn check(&self) -> Result<(), FitError> {
        if self.is_cancelled() {
            Err(FitError::Cancelled)
        } else {
            Ok(())
        }
    }
}

/// Settings are compared by what they ask of the fit; the flag is how it
/// may be stopped, not what it computes.
impl PartialEq for Cancel {
    fn eq(&self, _: &Cancel) -> bool {
        true
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn clones_share_the_flag() {
        let flag = Cancel::new();
        let held = flag.clone();
        assert!(held.check().is_ok());
        flag.cancel();
        assert!(held.is_cancelled());
        assert!(matches!(held.check(), Err(FitError::Cancelled)));
    }
}
