//! One module per `rollfit` subcommand.

pub mod batch;
pub mod fit;
pub mod forward;
