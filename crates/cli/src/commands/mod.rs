//! One module per `rollfit` subcommand.

pub mod batch;
pub mod bench;
pub mod compare;
pub mod fit;
pub mod forward;
pub mod master;
pub mod report;
