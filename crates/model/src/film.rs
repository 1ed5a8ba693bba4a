//! Thin film on a rigid base. PLACEHOLDER: being written (helper task); API fixed.

/// The film factor S(x, ν) with x = q d (wavenumber × film thickness).
pub fn film_factor(x: f64, poisson: f64) -> f64 {
    let nu = poisson;
    let c = 3.0 - 4.0 * nu;
    (c * (2.0 * x).cosh() + 2.0 * x * x + 5.0 - 4.0 * nu * (3.0 - 2.0 * nu))
        / (c * (2.0 * x).sinh() - 2.0 * x)
}
