//! One module per `rollfit` subcommand.

pub mod forward;
