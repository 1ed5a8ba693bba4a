//! An independent oracle for μ(v) of a sphere rolling on a film bonded to a
//! rigid base: Persson's Eq. (17) with the film factor,
//! integrated as written over the wavevector plane.
//!
//! # Formula
//!
//!   μ = 9F/(2π²) ∫₀^∞ dq q ∫₀^{2π} dφ cos φ L(q v cos φ) f(q r(q v cos φ))/S(q d)
//!     = 18F/π² ∫₀^{π/2} dφ cos φ ∫₀^∞ dq q L(q v cos φ) f(q r)/S(q d),
//!
//! F the load (N), v the speed (m/s), d the film thickness (m), L(ω) =
//! −(1 − ν²) Im[1/E(ω)] the loss compliance (1/Pa), f(y) = [(sin y −
//! y cos y)/y³]² the Hertz form factor and S the film factor
//! ([`rollfit_model::film::film_factor`], checked against a 100-digit
//! evaluation in its own tests). The dynamic contact radius is taken at the
//! frequency ω = q v cos φ the wave excites, r(ω) = [3F R(1 − ν²)/(4|E(ω)|)]^{1/3}
//! — the library's rule (its kernel argument x = ω r(ω)/v is, with
//! ω = q v cos φ, q r cos φ at that same r). The second line uses that the
//! integrand is even under φ → π − φ and φ → −φ (L odd, |E| even in ω).
//!
//! # Method
//!
//! Nothing of the library's reduction to one frequency integral, its kernel
//! G, its product integration or its Gauss–Kronrod code is used: a tensor
//! product of composite 16-point Gauss–Legendre rules (gauss-quad) in
//! - the outer angle, in ℓ = ln ψ, ψ = π/2 − φ (cos φ = sin ψ), from ψ = 10⁻¹⁰
//!   (the integrand falls like ψ³ in ℓ there) to π/2, panels 0.5/k wide;
//! - the inner wavenumber, in four pieces (r0 the static contact radius, the
//!   largest r):
//!   1. q < 2/r0 in s = ln q from 10⁻⁶ min(1/r0, ω_lo/(v cos φ)) (the
//!      integrand falls like q³ there), panels 0.25/k wide;
//!   2. 2/r0 < q < Q = Y/r0 with the full f, linear panels of width
//!      1/(k r0) (a third of f's period π/r) and, where qd < 30, at most
//!      1/(k d) (S's scale);
//!   3. beyond Q, f is split into its mean f_n(y) = (1 + y²)/(2y⁶) and the
//!      oscillating rest f − f_n (which falls like cos 2y/(2y⁴)): f_n to
//!      q = 10⁷ max(Q, ω_hi/(v cos φ)) in s = ln q (panels 0.25/k; the
//!      integrand falls at least like 1/q beyond), and the rest times a
//!      smooth cut-off w(q) = 1 − B((q − Q)/Q), B(t) = e^{−1/t}/(e^{−1/t} +
//!      e^{−1/(1−t)}), on Q < q < 2Q in the linear panels. A sharp cut at Q
//!      would leave an error ~ (Q r)^{−3} of μ_half, which for thin films is
//!      not small against μ_film (μ_film/μ_half = 2.5e-7 … 3e-4 at
//!      d/r0 = 1e-3 in the cases below); the smooth cut-off's error
//!      falls faster than any power of Q r, because w − 1 vanishes with all
//!      its derivatives at Q.
//!
//! The thin-film scale q ~ 1/d lies in piece 3 (in ln q) for d ≪ r0, so the
//! cost does not grow with r0/d. Resolution k = 1, Y = 200 is the standard
//! setting; convergence is measured against k = 2, Y = 400 (every panel
//! halved, the cut-off twice as far out) in `oracle_converges`.
//!
//! # Measured
//!
//! - Convergence (`oracle_converges`, all 40 target cases: d/r0 = 1e-3 …
//!   10, ν = 0.49 and ½, SLS and 3-term Prony, vτ/r0 = 0.01 and 1): standard
//!   against fine within 2.3e-11 relative (2.3e-11 at d/r0 = 1e-3, ≤ 8.6e-12
//!   at 1e-2, ≤ 2.1e-13 from 0.1 on). With the cut-off at Y = 100 the worst
//!   difference was 4.2e-8 (Y = 50: 2.5e-6), the panels alone (k = 1 → 3 at
//!   fixed Y) change nothing above 1e-15: the cut-off is what converges.
//! - Half-space (no film): the library's sphere μ within 1.9–7.2e-9 (it is
//!   the low one; `oracle_matches_half_space`).
//! - Today's film code (μ_half − Δ): within 5.7e-9 of the oracle at
//!   d/r0 = 1 and 10, 8e-10 … 6.1e-8 at 0.1, 9.8e-8 … 1.6e-7 at 0.05 (low
//!   speed only; refused at vτ/r0 = 1); refused at 0.02 and below. Its error
//!   is the half-space's ~5e-9 times μ_half/μ_film.
//! - Cost: ~1 s per μ (standard) in a release build, whatever d.
//!
//! # References
//! - B.N.J. Persson, "Rolling friction for hard cylinder and sphere on
//!   viscoelastic solid", Eur. Phys. J. E 33 (2010) 327–333, Eq. (17) and the
//!   film factor.
//! - P.J. Davis, P. Rabinowitz, *Methods of Numerical Integration*, 2nd ed.,
//!   Academic Press 1984 (composite Gauss rules, smooth truncation of
//!   oscillatory tails).

use rollfit_testkit::scenes;

use std::f64::consts::PI;
use std::num::NonZeroUsize;

use gauss_quad::legendre::GaussLegendre;
use rayon::prelude::*;
use rollfit_model::ViscoelasticModulus;
use rollfit_model::film::film_factor;
use rollfit_model::{ContactSize, Scene, Shape};
use rollfit_testkit::materials::{prony3, sls};

/// The accuracy the library's half-space sphere μ is documented to (its
/// `HALF_SPACE_ACCURACY`, measured floor ~4e-9 at low speed).
const HALF_SPACE_ACCURACY: f64 = 1e-8;

/// 16-point Gauss–Legendre on [−1, 1].
fn rule() -> Vec<(f64, f64)> {
    GaussLegendre::new(NonZeroUsize::new(16).unwrap())
        .iter()
        .map(|&(x, w)| (x, w))
        .collect()
}

/// f(y) = [(sin y − y cos y)/y³]², by its Taylor series for small y.
fn form_factor(y: f64) -> f64 {
    let a = if y < 0.5 {
        // (sin y − y cos y)/y³ = Σ (−1)ⁿ (2n + 2) y^{2n}/(2n + 3)!
        let y2 = y * y;
        let (mut sum, mut power, mut factorial) = (0.0, 1.0, 6.0);
        for n in 0..12 {
            let k = 2.0 * n as f64;
            sum += power * (k + 2.0) / factorial;
            power *= -y2;
            factorial *= (k + 4.0) * (k + 5.0);
        }
        sum
    } else {
        (y.sin() - y * y.cos()) / (y * y * y)
    };
    a * a
}

/// Mean f_n(y) = (1 + y²)/(2y⁶) of f for large y.
fn form_factor_mean(y: f64) -> f64 {
    (1.0 + y * y) / (2.0 * y.powi(6))
}

/// The smooth cut-off w on [Q, 2Q]: 1 at t = 0, 0 at t = 1, t = q/Q − 1.
fn cut_off(t: f64) -> f64 {
    if t <= 0.0 {
        return 1.0;
    }
    if t >= 1.0 {
        return 0.0;
    }
    let a = (-1.0 / t).exp();
    let b = (-1.0 / (1.0 - t)).exp();
    b / (a + b)
}

/// Oracle resolution: panels k times finer, cut-off at q = Y/r0.
#[derive(Clone, Copy)]
struct Resolution {
    k: f64,
    y_cut: f64,
}

const STANDARD: Resolution = Resolution {
    k: 1.0,
    y_cut: 200.0,
};
const FINE: Resolution = Resolution {
    k: 2.0,
    y_cut: 400.0,
};

/// Composite rule on [a, b] with panels at most `width` wide.
fn composite<F: FnMut(f64) -> f64>(
    rule: &[(f64, f64)],
    a: f64,
    b: f64,
    width: f64,
    mut g: F,
) -> f64 {
    if b <= a {
        return 0.0;
    }
    let n = ((b - a) / width).ceil().max(1.0) as usize;
    let h = (b - a) / n as f64;
    let mut sum = 0.0;
    for i in 0..n {
        let c = a + (i as f64 + 0.5) * h;
        for &(x, w) in rule {
            sum += w * g(c + 0.5 * h * x);
        }
    }
    0.5 * h * sum
}

/// What replaces f(qr)/S(qd) in Eq. (17).
#[derive(Clone, Copy, PartialEq)]
enum Law {
    /// The film as it is, f/S.
    Film,
    /// The thin-layer law of docs/film-sphere-thin-limit.md: P(qd)·(f − f_∞)
    /// + f_∞/S with P the Taylor polynomial of 1/S to third order.
    ThinLayer,
    /// Its leading term for ν < ½, the Winkler foundation β qd·f.
    Winkler,
}

/// β, γ of 1/S(ζ) = β ζ + γ ζ³ + O(ζ⁵) (see the doc of [`Law`]).
fn thin_coefficients(nu: f64) -> (f64, f64) {
    let m = (1.0 - nu) * (1.0 - nu);
    let a = 2.0 * (1.0 - 2.0 * nu);
    let c = 3.0 - 4.0 * nu;
    (
        (1.0 - 2.0 * nu) / (2.0 * m),
        c / (6.0 * m) - a * (c + 1.0) / (16.0 * m * m),
    )
}

/// f_∞(y) = 1/(2(1 + y²)²): f's mean 1/(2y⁴) at large y, regular at 0.
fn form_factor_far(y: f64) -> f64 {
    let t = 1.0 + y * y;
    0.5 / (t * t)
}

/// μ by the 2-D quadrature of the module docs.
fn oracle_mu<M: ViscoelasticModulus>(scene: &Scene<M>, v: f64, res: Resolution) -> f64 {
    oracle_mu_with(scene, v, res, Law::Film)
}

/// μ by the 2-D quadrature with f/S replaced by `law`.
fn oracle_mu_with<M: ViscoelasticModulus>(
    scene: &Scene<M>,
    v: f64,
    res: Resolution,
    law: Law,
) -> f64 {
    let rule = rule();
    let geometry = scene.geometry();
    let (load, radius) = (geometry.load, geometry.radius);
    let nu = scene.substrate().poisson;
    let d = scene.substrate().film_thickness.unwrap_or(f64::INFINITY);
    let plane_strain = 1.0 - nu * nu;
    let material = scene.material();
    let r0 = scene.static_contact_size();
    let (omega_lo, omega_hi) = material.structure_range();
    let contact = scene.contact();
    let size = |omega: f64| match contact {
        ContactSize::Static => r0,
        ContactSize::Dynamic => {
            (0.75 * load * radius * plane_strain / material.modulus(omega).norm()).cbrt()
        }
    };
    let inv_film = |q: f64| {
        if d.is_finite() {
            1.0 / film_factor(q * d, nu)
        } else {
            1.0
        }
    };
    // q L(q v c)/S(q d) and the contact radius at that frequency.
    let weight = |q: f64, c: f64| {
        let omega = q * v * c;
        let loss = -plane_strain * (1.0 / material.modulus(omega)).im;
        (q * loss, size(omega))
    };
    let (beta, gamma) = thin_coefficients(nu);
    // The law with f or its mean f_n: `mean` selects which.
    let kernel = |q: f64, y: f64, mean: bool| {
        let f = if mean {
            form_factor_mean(y)
        } else {
            form_factor(y)
        };
        let zeta = q * d;
        match law {
            Law::Film => f * inv_film(q),
            Law::Winkler => beta * zeta * f,
            Law::ThinLayer => {
                let far = form_factor_far(y);
                (beta * zeta + gamma * zeta * zeta * zeta) * (f - far) + far * inv_film(q)
            }
        }
    };
    let q_cut = res.y_cut / r0;
    let inner = |c: f64| {
        let q_lo = 1e-6 * (1.0 / r0).min(omega_lo / (v * c));
        let q1 = 2.0 / r0;
        // 1. Low wavenumbers, in ln q.
        let low = composite(&rule, q_lo.ln(), q1.ln(), 0.25 / res.k, |s| {
            let q = s.exp();
            let (g, r) = weight(q, c);
            q * g * kernel(q, q * r, false)
        });
        // 2. and the oscillating rest of 3., linear in q.
        let mut linear = 0.0;
        let mut q = q1;
        let q_end = 2.0 * q_cut;
        while q < q_end {
            let mut step = 1.0 / (res.k * r0);
            if q * d < 30.0 {
                step = step.min(1.0 / (res.k * d));
            }
            // Panels end exactly at Q, where the integrand changes form.
            let b = if q < q_cut {
                (q + step).min(q_cut)
            } else {
                (q + step).min(q_end)
            };
            linear += composite(&rule, q, b, b - q, |q| {
                let (g, r) = weight(q, c);
                let y = q * r;
                if q <= q_cut {
                    g * kernel(q, y, false)
                } else {
                    g * (kernel(q, y, false) - kernel(q, y, true)) * cut_off(q / q_cut - 1.0)
                }
            });
            q = b;
        }
        // 3. The mean part beyond Q, in ln q.
        let q_hi = 1e7 * q_cut.max(omega_hi / (v * c));
        let tail = composite(&rule, q_cut.ln(), q_hi.ln(), 0.25 / res.k, |s| {
            let q = s.exp();
            let (g, r) = weight(q, c);
            q * g * kernel(q, q * r, true)
        });
        low + linear + tail
    };
    let outer = composite(&rule, (1e-10f64).ln(), (PI / 2.0).ln(), 0.5 / res.k, |l| {
        let psi = l.exp();
        let c = psi.sin();
        psi * c * inner(c)
    });
    18.0 * load / (PI * PI) * outer
}

/// Film thicknesses of the targets (thin to thick against the contact), in
/// static contact radii.
const THICKNESS_RATIOS: [f64; 5] = [1e-3, 1e-2, 0.1, 1.0, 10.0];

/// A case: material name, scene, speed (m/s).
type Case = (&'static str, Scene<Box<dyn ViscoelasticModulus>>, f64);

/// SLS (τ = 1 s) on a 10 mm ball under 0.15 N and the 3-term Prony series
/// on a 5 mm ball under 0.5 N, dynamic contact, ν = 0.49 and 0.5, at
/// vτ/r0 = 0.01 and 1 (τ = 1 s for both) and film `ratio` r0 thick
/// (`None`: half-space).
fn cases(ratio: Option<f64>) -> Vec<Case> {
    let mut out = Vec::new();
    for nu in [0.49, 0.5] {
        for name in ["sls", "prony3"] {
            let (material, radius, load): (Box<dyn ViscoelasticModulus>, f64, f64) = match name {
                "sls" => (Box::new(sls(10.0)), 0.01, 0.15),
                _ => (Box::new(prony3()), 0.005, 0.5),
            };
            let half = scenes::scene(
                Shape::Sphere,
                radius,
                load,
                nu,
                None,
                ContactSize::Dynamic,
                material,
            );
            let r0 = half.static_contact_size();
            for vt in [1e-2, 1.0] {
                let material: Box<dyn ViscoelasticModulus> = match name {
                    "sls" => Box::new(sls(10.0)),
                    _ => Box::new(prony3()),
                };
                let scene = scenes::scene(
                    Shape::Sphere,
                    radius,
                    load,
                    nu,
                    ratio.map(|x| x * r0),
                    ContactSize::Dynamic,
                    material,
                );
                out.push((name, scene, vt * r0));
            }
        }
    }
    out
}

/// Without a film the oracle is the half-space μ, which the library
/// computes to ~1e-9 ([`HALF_SPACE_ACCURACY`]): this checks the oracle's
/// formula, prefactor, contact radius and cut-off.
#[test]
fn oracle_matches_half_space() {
    // The cases are independent quadratures: computed on every core (each
    // case's scene is built in its worker), printed and checked in order.
    let results: Vec<_> = (0..cases(None).len())
        .into_par_iter()
        .map(|k| {
            let (name, scene, v) = cases(None).swap_remove(k);
            let fast = scene.friction(v).unwrap();
            let slow = oracle_mu(&scene, v, STANDARD);
            (name, scene.substrate().poisson, v, fast, slow)
        })
        .collect();
    for (name, nu, v, fast, slow) in results {
        let err = (fast / slow - 1.0).abs();
        eprintln!(
            "half-space {name} ν={nu} v={v:.3e}: library {fast:.12e} oracle {slow:.12e} rel {err:.2e}"
        );
        assert!(err < 10.0 * HALF_SPACE_ACCURACY, "{name} ν={nu} v={v}");
    }
}

/// The film code against the oracle at every target case: d/r0 = 1e-3 …
/// 10, ν = 0.49 and ½, SLS and Prony, two speeds, at the default tolerance
/// 1e-6.
#[test]
fn film_code_matches_oracle() {
    // The 56 oracle quadratures are independent: computed on every core
    // (each case's scene is built in its worker, a boxed modulus is not
    // Send), then printed and checked in order.
    let ratios = [1e-3, 1e-2, 0.02, 0.05, 0.1, 1.0, 10.0];
    let per_ratio = cases(None).len();
    let results: Vec<_> = (0..ratios.len() * per_ratio)
        .into_par_iter()
        .map(|k| {
            let ratio = ratios[k / per_ratio];
            let (name, scene, v) = cases(Some(ratio)).swap_remove(k % per_ratio);
            let nu = scene.substrate().poisson;
            let fast = scene.friction(v).unwrap();
            let slow = oracle_mu(&scene, v, STANDARD);
            (ratio, name, nu, v, fast, slow)
        })
        .collect();
    let mut worst = 0.0f64;
    for (ratio, name, nu, v, fast, slow) in results {
        let err = (fast / slow - 1.0).abs();
        eprintln!(
            "d/r0={ratio} {name} ν={nu} v={v:.3e}: library {fast:.12e} oracle {slow:.12e} rel {err:.2e}"
        );
        worst = worst.max(err);
        assert!(err < 1e-6, "d/r0={ratio} {name} ν={nu} v={v}");
    }
    eprintln!("worst {worst:.2e}");
}

/// The oracle's own convergence: standard against fine resolution at every
/// target case (slow; run with --ignored --nocapture).
#[test]
#[ignore]
fn oracle_converges() {
    let mut worst = 0.0f64;
    for ratio in THICKNESS_RATIOS {
        for (name, scene, v) in cases(Some(ratio)) {
            let a = oracle_mu(&scene, v, STANDARD);
            let b = oracle_mu(&scene, v, FINE);
            let err = (a / b - 1.0).abs();
            worst = worst.max(err);
            let nu = scene.substrate().poisson;
            eprintln!(
                "d/r0={ratio} {name} ν={nu} v={v:.3e}: standard {a:.14e} fine {b:.14e} rel {err:.2e}"
            );
        }
    }
    eprintln!("worst {worst:.2e}");
    assert!(worst < 1e-8);
}

/// The oracle approaches the thin-layer law of
/// docs/film-sphere-thin-limit.md as d → 0, at the predicted rate: the
/// law's relative error is O((d/r)²) up to logarithms, so from d/r0 = 1e-3
/// to 1e-4 it must fall by at least 30 (100 less a logarithmic factor), and
/// at d/r0 = 1e-3 it must already be small (below 1e-4: d²/r² = 1e-6 times
/// a constant γ/β ≤ 16 and the logarithm ln(r/d) ≈ 7).
#[test]
fn oracle_approaches_thin_layer_law() {
    // The cases are independent quadratures: computed on every core (each
    // case's scene is built in its worker, a boxed modulus is not Send).
    let errors = |ratio: f64| -> Vec<f64> {
        (0..cases(None).len())
            .into_par_iter()
            .map(|k| {
                let (name, scene, v) = cases(Some(ratio)).swap_remove(k);
                let nu = scene.substrate().poisson;
                let film = oracle_mu(&scene, v, STANDARD);
                let thin = oracle_mu_with(&scene, v, STANDARD, Law::ThinLayer);
                let err = (film / thin - 1.0).abs();
                eprintln!("d/r0={ratio} {name} ν={nu} v={v:.3e}: film {film:.12e} thin-layer law {thin:.12e} rel {err:.2e}");
                err
            })
            .collect()
    };
    let (thick, thin) = rayon::join(|| errors(1e-3), || errors(1e-4));
    for (a, b) in thick.iter().zip(&thin) {
        assert!(*a < 1e-4, "thin-layer law off by {a:e} at d/r0 = 1e-3");
        assert!(
            *b < a / 30.0,
            "thin-layer law error {a:e} → {b:e} from d/r0 = 1e-3 to 1e-4"
        );
    }
}

/// The Winkler foundation, the law's leading term for ν < ½, is approached
/// only slowly for ν near ½ (its relative error falls like d/r up to
/// logarithms, with a large constant γ/β); printed, not asserted (slow; run
/// with --ignored --nocapture).
#[test]
#[ignore]
fn winkler_leading_term() {
    for ratio in [1e-3, 1e-4, 1e-5] {
        for (name, scene, v) in cases(Some(ratio)) {
            let nu = scene.substrate().poisson;
            if nu == 0.5 {
                continue;
            }
            let film = oracle_mu(&scene, v, STANDARD);
            let winkler = oracle_mu_with(&scene, v, STANDARD, Law::Winkler);
            let err = (film / winkler - 1.0).abs();
            eprintln!(
                "d/r0={ratio} {name} ν={nu} v={v:.3e}: film {film:.12e} Winkler {winkler:.12e} rel {err:.2e}"
            );
        }
    }
}
