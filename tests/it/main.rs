//! End-to-end tests of the `rollfit` binary, as one test binary of the cli
//! crate (its one `[[test]]` entry): a module per command or concern, each
//! saying in its docs what it checks. They stay in the workspace's top-level
//! tests/ folder because they test the whole tool, not the cli crate alone
//! (docs/ARCHITECTURE.md, "Crates"). One binary links the dependencies once;
//! a file under tests/it that no `mod` line here declares is reported by
//! .ci/structure.py, so none can silently go unrun.

mod batch_cli;
mod bench_cli;
mod common;
mod compare_cli;
mod crashes_cli;
mod dma_files_cli;
mod dma_input_cli;
mod docs_cli;
mod faults_cli;
mod fit_cli;
mod folders_cli;
mod forward_cli;
mod fuzz_cli;
mod joint_cli;
mod limits_cli;
mod master_cli;
mod master_pictures_cli;
mod messages;
mod negative_numbers_cli;
mod pressure_map_cli;
mod relaxation_files_cli;
mod reliability_cli;
mod report_cli;
mod talk_cli;
mod vertical_shift_cli;
