//! The cylinder kernel of Eq. (11).
//!
//! With s = ln ω and y = ω a(ω)/v, Persson's Eq. (11),
//! μ = (8 f_N/π) ∫₀^∞ dq L(qv) J1²(qa)/(qa)², becomes
//! μ = (8 f_N/π) ∫ ds (L/a) · k(ln y) with the universal kernel
//! k(ln y) = J1(y)²/y.
//!
//! Split into a smooth and an oscillatory part through the Hankel function
//! H1 = J1 + iY1: J1² = ½(J1² + Y1²) + ½ Re H1², where J1² + Y1² = |H1|² is
//! free of oscillation and Re H1² ∝ cos(2y − 3π/2) oscillates with full
//! amplitude: k_n = (J1² + Y1²)/(2y), k_o = (J1² − Y1²)/(2y).
//!
//! Asymptotes: k → y/4 for y → 0; k_n → (1/(πy²))(1 + 3/(8y²) + …) for
//! y → ∞ (Hankel's expansion of J1² + Y1²).

/// k(ln y) = J1(y)²/y.
pub fn kernel(y: f64) -> f64 {
    let j = libm::j1(y);
    j * j / y
}

/// Smooth part k_n = (J1² + Y1²)/(2y).
pub fn smooth_part(y: f64) -> f64 {
    if y > 1e3 {
        // Hankel's expansion is exact to rounding here and avoids y1's cost.
        let inv2 = 1.0 / (y * y);
        inv2 / std::f64::consts::PI * (1.0 + 0.375 * inv2 - 45.0 / 128.0 * inv2 * inv2)
    } else {
        let j = libm::j1(y);
        let yy = libm::y1(y);
        (j * j + yy * yy) / (2.0 * y)
    }
}

/// Oscillatory part k_o = (J1² − Y1²)/(2y).
pub fn oscillatory_part(y: f64) -> f64 {
    let j = libm::j1(y);
    let yy = libm::y1(y);
    (j * j - yy * yy) / (2.0 * y)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parts_add_up() {
        for &y in &[0.5f64, 2.0, 7.3, 40.0, 300.0] {
            let sum = smooth_part(y) + oscillatory_part(y);
            assert!((sum - kernel(y)).abs() < 1e-13 * smooth_part(y), "{y}");
        }
    }

    #[test]
    fn smooth_part_is_hankel_asymptote() {
        let y = 999.0;
        let inv2 = 1.0 / (y * y);
        let asym = inv2 / std::f64::consts::PI * (1.0 + 0.375 * inv2 - 45.0 / 128.0 * inv2 * inv2);
        assert!((smooth_part(y) / asym - 1.0).abs() < 1e-12);
    }
}
