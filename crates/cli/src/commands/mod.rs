//! One module per `rollfit` subcommand.

pub mod fit;
pub mod forward;
