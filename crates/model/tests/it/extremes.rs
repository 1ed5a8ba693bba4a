//! Extremes: films from 1e-3 to 1e3 contact sizes, ν = 0.5,
//! speeds from 1e-12 to 1e6 times the natural speed a0/τ, E1/E0 up to 1e4.
//! Every result is finite and accurate, or clearly refused: never a NaN, a
//! negative μ or a silent wrong number. Printed with --nocapture: the
//! figures docs/validation.md, "Where the methods fail", quotes.

use rollfit_model::{ContactSize, Geometry, Scene, Shape, StandardLinearSolid, Substrate};

fn scene(shape: Shape, ratio: f64, poisson: f64, film: Option<f64>) -> Scene<StandardLinearSolid> {
    let load = if shape == Shape::Sphere { 1.0 } else { 100.0 };
    Scene::new(
        Geometry {
            shape,
            radius: 0.005,
            load,
        },
        Substrate {
            poisson,
            film_thickness: film,
        },
        ContactSize::Dynamic,
        StandardLinearSolid::new(1e6, 1e6 * ratio, 1.0).unwrap(),
    )
    .unwrap()
}

/// Half-space: every μ from 1e-12 to 1e6 natural speeds is finite and
/// positive; at the low end it equals the low-speed asymptote, at the high
/// end it falls as the solid turns glassy.
#[test]
fn speeds_over_eighteen_decades_and_moduli_ratios_to_ten_thousand() {
    for shape in [Shape::Sphere, Shape::Cylinder] {
        for ratio in [2.0, 10.0, 1e3, 1e4] {
            for poisson in [0.0, 0.5] {
                let s = scene(shape, ratio, poisson, None);
                let natural = s.static_contact_size(); // τ = 1 s
                let speeds: Vec<f64> = (0..19).map(|k| natural * 10f64.powi(k - 12)).collect();
                let mu = s.friction_sweep(&speeds).unwrap();
                for (v, m) in speeds.iter().zip(&mu) {
                    assert!(
                        m.is_finite() && *m > 0.0,
                        "{shape:?} E1/E0 {ratio} ν {poisson} v {v}: μ = {m}"
                    );
                }
                let low = s.low_speed_asymptote(speeds[0]);
                let rel = (mu[0] / low - 1.0).abs();
                assert!(
                    rel < 1e-6,
                    "{shape:?} E1/E0 {ratio}: low-speed μ off the asymptote by {rel}"
                );
                assert!(
                    mu[18] < mu[12],
                    "{shape:?} E1/E0 {ratio}: no decay at high speed"
                );
                eprintln!(
                    "{shape:?} E1/E0 = {ratio:e} ν = {poisson}: μ(1e-12 v0) = {:.3e} (asymptote to {rel:.1e}), max sampled {:.3e}, μ(1e6 v0) = {:.3e}",
                    mu[0],
                    mu.iter().copied().fold(0.0, f64::max),
                    mu[18]
                );
            }
        }
    }
}

/// Films from 1e-3 to 1e3 static contact sizes under a cylinder and a
/// sphere: thick films give the half-space; thin ones either compute (a
/// finite μ below the half-space's: the rigid base stiffens the contact)
/// or are refused with a message naming the film and the tolerance.
#[test]
fn films_from_a_thousandth_to_a_thousand_contact_sizes() {
    for shape in [Shape::Cylinder, Shape::Sphere] {
        let half = scene(shape, 10.0, 0.5, None);
        let a0 = half.static_contact_size();
        let v = a0; // vτ/a0 = 1: near the friction maximum
        let mu_half = half.friction(v).unwrap();
        for k in -3..=3 {
            let d = a0 * 10f64.powi(k);
            let film = scene(shape, 10.0, 0.5, Some(d));
            match film.friction(v) {
                Ok(mu) => {
                    assert!(
                        mu.is_finite() && mu > 0.0,
                        "{shape:?} d/a0 = 1e{k}: μ = {mu}"
                    );
                    eprintln!(
                        "{shape:?} d/a0 = 1e{k}: μ/μ_half-space = {:.4}",
                        mu / mu_half
                    );
                    if k >= 2 {
                        assert!(
                            (mu / mu_half - 1.0).abs() < 0.02,
                            "{shape:?} thick film d/a0 = 1e{k}"
                        );
                    }
                }
                Err(e) => {
                    let message = e.to_string();
                    eprintln!("{shape:?} d/a0 = 1e{k}: refused: {message}");
                    assert!(
                        k < 0,
                        "{shape:?}: a film of 1e{k} contact sizes was refused: {message}"
                    );
                    assert!(
                        message.contains("film") || message.contains("thickness"),
                        "{message}"
                    );
                }
            }
        }
    }
}
