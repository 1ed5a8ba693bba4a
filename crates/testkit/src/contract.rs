//! Names docs/ARCHITECTURE.md's contract fixes, written once for the
//! tests that check them (report's compare and the compare command).

/// The keys of compare.json (docs/ARCHITECTURE.md, "Contract").
pub const COMPARE_KEYS: [&str; 11] = [
    "n_points",
    "omega_min",
    "omega_max",
    "tan_delta_rms_rel",
    "tan_delta_max_rel",
    "abs_E_rms_rel",
    "abs_E_max_rel",
    "log10_E_storage_rms",
    "log10_E_loss_rms",
    "dma_kk_misfit_storage",
    "dma_kk_misfit_loss",
];
