//! The names of a fit folder (docs/ARCHITECTURE.md, "Contract", "Fit
//! folder"): its three files and the columns of its two tables, defined
//! once for the writer ([`super::write`]) and the reader
//! ([`super::FitDir::read`]). Extend them; do not rename or reorder what
//! exists.

/// The fit's report (written last).
pub const FIT_JSON: &str = "fit.json";
/// The master curve over the determined window.
pub const MODULUS_CSV: &str = "modulus.csv";
/// One row per data row.
pub const MU_CSV: &str = "mu.csv";

/// Angular frequency, rad/s (modulus.csv).
pub const OMEGA: &str = "omega";
/// Young's storage modulus E′, Pa (modulus.csv).
pub const E_STORAGE: &str = "E_storage";
/// Young's loss modulus E″, Pa (modulus.csv).
pub const E_LOSS: &str = "E_loss";
/// tan δ = E″/E′ (modulus.csv).
pub const TAN_DELTA: &str = "tan_delta";
/// |E*|, Pa (modulus.csv).
pub const ABS_E: &str = "abs_E";
/// 1σ of E′, Pa (modulus.csv).
pub const E_STORAGE_SIGMA: &str = "E_storage_sigma";
/// 1σ of E″, Pa (modulus.csv).
pub const E_LOSS_SIGMA: &str = "E_loss_sigma";
/// 1σ of tan δ (modulus.csv).
pub const TAN_DELTA_SIGMA: &str = "tan_delta_sigma";
/// 1σ of |E*|, Pa (modulus.csv).
pub const ABS_E_SIGMA: &str = "abs_E_sigma";

/// modulus.csv in order: the contract fixes the first four (readers need
/// them); then |E*| and the 1σ band of each quantity.
pub const MODULUS_COLUMNS: [&str; 9] = [
    OMEGA,
    E_STORAGE,
    E_LOSS,
    TAN_DELTA,
    ABS_E,
    E_STORAGE_SIGMA,
    E_LOSS_SIGMA,
    TAN_DELTA_SIGMA,
    ABS_E_SIGMA,
];

/// Rolling speed, m/s (mu.csv).
pub const V: &str = "v";
/// Measured μ (mu.csv).
pub const MU_MEASURED: &str = "mu_measured";
/// Fitted μ (mu.csv).
pub const MU_FIT: &str = "mu_fit";
/// Standard deviation of the measured μ, only if the data had it (mu.csv).
pub const SIGMA: &str = "sigma";
/// (mu_fit − mu_measured)/mu_measured (mu.csv).
pub const RESIDUAL: &str = "residual";
/// Temperature, °C, temperature sets only (mu.csv).
pub const T: &str = "T";
/// log10 a_T of the nearest fitted temperature, temperature sets only
/// (mu.csv).
pub const LOG_AT: &str = "log_aT";
/// v·a_T, m/s, temperature sets only (mu.csv).
pub const V_REDUCED: &str = "v_reduced";
/// μ_exact/μ_approx at the fitted modulus per row, fits with
/// `physics = "exact"` only (mu.csv; `mu_fit` is then the exact μ,
/// μ_approx times this).
pub const EXACT_CORRECTION: &str = "exact_correction";
