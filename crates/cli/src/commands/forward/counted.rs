//! Progress of the exact solves of a forward sweep. `exact`
//! solves every speed, so its bar counts speeds; `auto` decides inside the
//! model which speeds need the exact contact, so its exact body is wrapped
//! in [`Counted`], which counts the solves it is asked for and passes every
//! call through unchanged: the same numbers with and without a bar.

use indicatif::ProgressBar;
use rollfit_model::exact::{ExactFriction, ExactRolling, PressureMap};
use rollfit_model::{ModelError, Shape};

/// An exact rolling body whose solves advance `bar`.
pub struct Counted<'a> {
    inner: Body<'a>,
    bar: ProgressBar,
}

/// The body counted: the caller's, or one the model rediscretised
/// ([`ExactRolling::with_accuracy`], which `auto` calls).
enum Body<'a> {
    Borrowed(&'a dyn ExactRolling),
    Owned(Box<dyn ExactRolling>),
}

impl<'a> Counted<'a> {
    /// `body`, its solves counted on `bar` (the solves planned are added
    /// to its length as they start: `auto` does not say in advance).
    pub fn new(body: &'a dyn ExactRolling, bar: ProgressBar) -> Counted<'a> {
        Counted {
            inner: Body::Borrowed(body),
            bar,
        }
    }

    fn body(&self) -> &dyn ExactRolling {
        match &self.inner {
            Body::Borrowed(b) => *b,
            Body::Owned(b) => b.as_ref(),
        }
    }
}

impl ExactRolling for Counted<'_> {
    fn shape(&self) -> Shape {
        self.body().shape()
    }

    fn static_contact_size(&self) -> f64 {
        self.body().static_contact_size()
    }

    fn exact_friction(&self, v: f64) -> Result<ExactFriction, ModelError> {
        self.bar.inc_length(1);
        let solved = self.body().exact_friction(v);
        self.bar.inc(1);
        solved
    }

    fn pressure_map(&self, v: f64) -> Result<PressureMap, ModelError> {
        self.body().pressure_map(v)
    }

    fn with_accuracy(&self, accuracy: f64) -> Box<dyn ExactRolling> {
        Box::new(Counted {
            inner: Body::Owned(self.body().with_accuracy(accuracy)),
            bar: self.bar.clone(),
        })
    }
}
