//! One module per `rollfit` subcommand.

pub mod batch;
pub mod compare;
pub mod fit;
pub mod forward;
pub mod report;
