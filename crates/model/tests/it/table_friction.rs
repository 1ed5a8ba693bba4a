//! μ(v) of a tabulated modulus: the table's own interpolation error and the
//! quadrature error of μ for the interpolant, measured apart.
//!
//! (a) Interpolation: the table's interpolant against the analytic modulus it
//! was sampled from, between the samples.
//! (b) Quadrature: the library's μ at the requested tolerance against μ of the
//! same interpolant from a slow, obvious quadrature (the oracle below) that
//! splits at the table's knots.
//!
//! The oracle integrates Persson's Eqs. (11) and (17) in s = ln ω as written,
//!
//!   μ = C ∫ ds L(ω)/r(ω)^m k(ln(ω r(ω)/v)),
//!
//! L = −(1 − ν²) Im 1/E, r the dynamic (|E(ω)|) or static (E(0)) Hertz size,
//! C = 18 F_N/π² or 8 f_N/π, m = 2 or 1 and k(ln x) = x² G(x) (sphere) or
//! J₁(x)²/x (cylinder), by composite 20-point Gauss–Legendre rules on panels
//! that end at every knot of the table and are at most min(0.1, 1/x) wide in
//! s (a third of the kernel's period 2π/(2x) in ln x, with dσ/ds ≤ 1). The
//! kernel's oscillation is followed out to x ≈ X_c e^{1.5} and faded out
//! around X_c by the smooth window ½ erfc((ln X_c − ln x)/0.25): for Φ with
//! kinks at the knots what it drops is O(jump/X_c⁴) (integration by parts).
//! It shares nothing with the library's product integration on the σ grid;
//! its own accuracy is checked by refinement (panels halved, X_c ×3).

use rollfit_testkit::materials;
use rollfit_testkit::scenes::scene;

use std::num::NonZeroUsize;

use gauss_quad::legendre::GaussLegendre;
use num_complex::Complex64;
use rayon::prelude::*;
use rollfit_model::kernel::{cylinder, sphere};
use rollfit_model::{
    ContactSize, Prony, Scene, Shape, StandardLinearSolid, TabulatedModulus, ViscoelasticModulus,
};

/// Discretisation of the oracle.
#[derive(Clone, Copy)]
struct Resolution {
    points: usize,
    /// Largest panel width in s.
    width: f64,
    /// Centre X_c of the window that fades the oscillation out.
    x_cut: f64,
}

const BASE: Resolution = Resolution {
    points: 20,
    width: 0.1,
    x_cut: 300.0,
};

struct Oracle<'m, M> {
    material: &'m M,
    shape: Shape,
    radius: f64,
    load: f64,
    nu: f64,
    dynamic: bool,
    /// ln ω of the table's rows (panel ends), empty for an analytic modulus.
    knots: Vec<f64>,
    rule: Vec<(f64, f64)>,
    res: Resolution,
}

impl<'m, M: ViscoelasticModulus> Oracle<'m, M> {
    fn new<S: ViscoelasticModulus>(
        scene: &Scene<S>,
        material: &'m M,
        knots: Vec<f64>,
        res: Resolution,
    ) -> Self {
        let rule = GaussLegendre::new(NonZeroUsize::new(res.points).unwrap())
            .iter()
            .map(|&(x, w)| (0.5 * (x + 1.0), 0.5 * w))
            .collect();
        let g = scene.geometry();
        Oracle {
            material,
            shape: g.shape,
            radius: g.radius,
            load: g.load,
            nu: scene.substrate().poisson,
            dynamic: scene.contact() == ContactSize::Dynamic,
            knots,
            rule,
            res,
        }
    }

    /// (n, K with r^n = K/|E_eff|, prefactor C).
    fn constants(&self) -> (f64, f64, f64) {
        let pi = std::f64::consts::PI;
        match self.shape {
            Shape::Sphere => (
                3.0,
                0.75 * self.load * self.radius,
                18.0 * self.load / (pi * pi),
            ),
            Shape::Cylinder => (
                2.0,
                4.0 * self.load * self.radius / pi,
                8.0 * self.load / pi,
            ),
        }
    }

    /// Contact size r(ω), m.
    fn size(&self, e: Complex64) -> f64 {
        let (n, k, _) = self.constants();
        let e_eff = if self.dynamic {
            e.norm()
        } else {
            self.material.static_modulus()
        } / (1.0 - self.nu * self.nu);
        (k / e_eff).powf(1.0 / n)
    }

    /// The kernel k(ln x) with the oscillation faded out around X_c.
    fn kernel(&self, x: f64) -> f64 {
        let keep = 0.5 * libm::erfc((x.ln() - self.res.x_cut.ln()) / 0.25);
        match self.shape {
            Shape::Sphere => {
                if keep == 1.0 {
                    x * x * sphere::g(x)
                } else {
                    x * x * (sphere::smooth_part(x) + keep * sphere::oscillatory_part(x))
                }
            }
            Shape::Cylinder => {
                if keep == 1.0 {
                    cylinder::kernel(x)
                } else {
                    cylinder::smooth_part(x) + keep * cylinder::oscillatory_part(x)
                }
            }
        }
    }

    /// (σ = ln(ω r), integrand L/r^m k) at s = ln ω.
    fn integrand(&self, s: f64, ln_v: f64) -> (f64, f64) {
        let (n, _, _) = self.constants();
        let omega = s.exp();
        let e = self.material.modulus(omega);
        let r = self.size(e);
        let loss = -(1.0 - self.nu * self.nu) * (1.0 / e).im;
        let sigma = s + r.ln();
        (
            sigma,
            loss / r.powf(n - 1.0) * self.kernel((sigma - ln_v).exp()),
        )
    }

    fn mu(&self, v: f64) -> f64 {
        let (_, _, c) = self.constants();
        let ln_v = v.ln();
        // σ − s = ln r lies between ln r(∞) and ln r(0).
        let ln_r0 = self
            .size(Complex64::new(self.material.static_modulus(), 0.0))
            .ln();
        let ln_r_min = self.size(self.material.modulus(1e300)).ln().min(ln_r0);
        let lo = ln_v - 40.0 - ln_r0;
        let x_end = self.res.x_cut * 1.5f64.exp() * 4.0;
        let hi = ln_v + x_end.ln().max(40.0) - ln_r_min;
        let mut breaks = vec![lo];
        breaks.extend(self.knots.iter().copied().filter(|&k| k > lo && k < hi));
        breaks.push(hi);
        let mut sum = 0.0;
        for w in breaks.windows(2) {
            let (mut a, b) = (w[0], w[1]);
            while a < b {
                // Panel width from x at its start (x grows along the panel
                // by at most e^{width} ≤ e^{0.05}).
                let x = (a + ln_r0.max(ln_r_min) - ln_v).exp();
                // Past x_end the window has removed the oscillation.
                let period_limit = if x < x_end { 1.0 / x } else { f64::INFINITY };
                let width = self.res.width.min(period_limit).min(b - a);
                let end = if b - (a + width) < 1e-3 * width {
                    b
                } else {
                    a + width
                };
                let h = end - a;
                for &(t, wt) in &self.rule {
                    sum += wt * h * self.integrand(a + t * h, ln_v).1;
                }
                a = end;
            }
        }
        c * sum
    }
}

/// Log-spaced frequencies from 10^`lo` to 10^`hi`, `per_decade` per decade,
/// shifted by `offset` of a step.
fn log_grid(lo: f64, hi: f64, per_decade: f64, offset: f64) -> Vec<f64> {
    let count = ((hi - lo) * per_decade).round() as usize;
    (0..=count)
        .map(|i| 10f64.powf(lo + (i as f64 + offset) / per_decade))
        .collect()
}

fn sampled<M: ViscoelasticModulus>(m: &M, omega: &[f64]) -> TabulatedModulus {
    TabulatedModulus::sampled(m, omega).unwrap()
}

/// The largest relative error of E′ and of E″ of the table against `m`,
/// 16 points inside each interval.
fn interpolation_error<M: ViscoelasticModulus>(t: &TabulatedModulus, m: &M) -> (f64, f64) {
    let mut worst = (0.0f64, 0.0f64);
    for w in t.omega().windows(2) {
        let (a, b) = (w[0].ln(), w[1].ln());
        for j in 1..16 {
            let omega = (a + (b - a) * j as f64 / 16.0).exp();
            let (e, exact) = (t.modulus(omega), m.modulus(omega));
            worst.0 = worst.0.max((e.re / exact.re - 1.0).abs());
            worst.1 = worst.1.max((e.im / exact.im - 1.0).abs());
        }
    }
    worst
}

/// The measured cases: name, analytic modulus, frequency range of the table
/// (decades), speeds (m/s).
fn materials() -> Vec<(&'static str, Prony, (f64, f64))> {
    let sls = StandardLinearSolid::new(1e6, 1e7, 1e-2).unwrap().to_prony();
    let sls3 = StandardLinearSolid::new(1e6, 1e9, 1e-2).unwrap().to_prony();
    let prony3 = Prony::new(
        1e6 + 2e6 + 2e7 + 5e7,
        vec![2e6, 2e7, 5e7],
        vec![1e-1, 1e-3, 1e-5],
    )
    .unwrap();
    let mut rng = materials::Lcg(7);
    let prony15 = materials::random_prony(&mut rng, 15, -10.0, 0.5);
    vec![
        ("sls E1/E0=10", sls, (-3.0, 7.0)),
        ("sls E1/E0=1e3", sls3, (-3.0, 10.0)),
        ("prony 3", prony3, (-3.0, 11.0)),
        ("prony 15", prony15, (-8.0, 16.0)),
    ]
}

const SPEEDS: [f64; 5] = [1e-5, 1e-4, 1e-3, 1e-2, 1e-1];

fn scene_of<M: ViscoelasticModulus>(
    shape: Shape,
    contact: ContactSize,
    material: M,
    tolerance: f64,
) -> Scene<M> {
    let load = if shape == Shape::Sphere { 1.0 } else { 200.0 };
    scene(shape, 0.005, load, 0.5, None, contact, material)
        .with_tolerance(tolerance)
        .unwrap()
}

/// The study behind the module doc of `modulus/table.rs`: (a) and (b) for
/// every material, table density, shape, contact rule and tolerance.
/// `cargo test --release -p rollfit-model --test it -- --ignored --nocapture table_friction::study`
#[test]
#[ignore = "study, about a minute in release"]
fn study() {
    let shapes = [Shape::Sphere, Shape::Cylinder];
    let contacts = [ContactSize::Dynamic, ContactSize::Static];
    for (name, prony, (lo, hi)) in materials() {
        for per_decade in [5.0, 10.0, 20.0, 100.0] {
            let table = sampled(&prony, &log_grid(lo, hi, per_decade, 0.37));
            let (ea, eb) = interpolation_error(&table, &prony);
            println!("{name}, {per_decade}/decade: interpolation E' {ea:.1e} E'' {eb:.1e}");
            let knots: Vec<f64> = table.omega().iter().map(|w| w.ln()).collect();
            for shape in shapes {
                for contact in contacts {
                    let base = scene_of(shape, contact, table.clone(), 1e-6);
                    let oracle = Oracle::new(&base, &table, knots.clone(), BASE);
                    let exact: Vec<f64> = SPEEDS.iter().map(|&v| oracle.mu(v)).collect();
                    let analytic = scene_of(shape, contact, prony.clone(), 1e-11)
                        .friction_sweep(&SPEEDS)
                        .unwrap();
                    let mut line = format!("  {shape:?} {contact:?}:");
                    let table_vs_analytic = exact
                        .iter()
                        .zip(&analytic)
                        .map(|(t, a)| (t / a - 1.0).abs())
                        .fold(0.0, f64::max);
                    line += &format!(" μ(interp)/μ(analytic) {table_vs_analytic:.1e};");
                    for tol in [1e-3, 1e-4, 1e-5, 1e-6] {
                        let mu = scene_of(shape, contact, table.clone(), tol)
                            .friction_sweep(&SPEEDS)
                            .unwrap();
                        let quad = mu
                            .iter()
                            .zip(&exact)
                            .map(|(m, e)| (m / e - 1.0).abs())
                            .fold(0.0, f64::max);
                        let total = mu
                            .iter()
                            .zip(&analytic)
                            .map(|(m, e)| (m / e - 1.0).abs())
                            .fold(0.0, f64::max);
                        line += &format!(" tol {tol:.0e}: quad {quad:.1e} total {total:.1e};");
                    }
                    println!("{line}");
                }
            }
        }
    }
}

/// The oracle against itself refined, and against the library's μ of the
/// analytic modulus at tolerance 1e-11.
#[test]
#[ignore = "oracle check, slow"]
fn oracle_converges() {
    let (_, prony, (lo, hi)) = materials().remove(0);
    let table = sampled(&prony, &log_grid(lo, hi, 10.0, 0.37));
    let knots: Vec<f64> = table.omega().iter().map(|w| w.ln()).collect();
    for shape in [Shape::Sphere, Shape::Cylinder] {
        for contact in [ContactSize::Dynamic, ContactSize::Static] {
            let s = scene_of(shape, contact, prony.clone(), 1e-11);
            let lib = s.friction_sweep(&SPEEDS).unwrap();
            let o = Oracle::new(&s, &prony, Vec::new(), BASE);
            let fine = Resolution {
                points: 20,
                width: 0.05,
                x_cut: 900.0,
            };
            let t_scene = scene_of(shape, contact, table.clone(), 1e-6);
            let ot = Oracle::new(&t_scene, &table, knots.clone(), BASE);
            let ot_fine = Oracle::new(&t_scene, &table, knots.clone(), fine);
            for (i, &v) in SPEEDS.iter().enumerate() {
                let a = o.mu(v);
                let t = ot.mu(v);
                let tf = ot_fine.mu(v);
                println!(
                    "{shape:?} {contact:?} v {v:e}: oracle/lib − 1 = {:.1e}; table oracle refined {:.1e}",
                    a / lib[i] - 1.0,
                    tf / t - 1.0
                );
            }
        }
    }
}

/// Speeds around the friction maximum of the SLS of [`materials`] (E1/E0 =
/// 10, τ = 10 ms) under both bodies: below, at and above it.
const CI_SPEEDS: [f64; 3] = [1e-4, 1e-3, 1e-2];

/// The target: μ of a table within 10 × tolerance of μ of the
/// modulus it was sampled from, at tolerances 1e-3 … 1e-6, for tables dense
/// enough that their own interpolation error is below that — 20 rows a
/// decade (μ then differs by 6e-7 at most, see the study).
#[test]
fn table_matches_its_analytic_modulus_at_every_tolerance() {
    for (name, prony, (lo, hi)) in materials().into_iter().take(3) {
        let table = sampled(&prony, &log_grid(lo, hi, 20.0, 0.37));
        for shape in [Shape::Sphere, Shape::Cylinder] {
            for contact in [ContactSize::Dynamic, ContactSize::Static] {
                let analytic = scene_of(shape, contact, prony.clone(), 1e-11)
                    .friction_sweep(&SPEEDS)
                    .unwrap();
                for tol in [1e-3, 1e-4, 1e-5, 1e-6] {
                    let mu = scene_of(shape, contact, table.clone(), tol)
                        .friction_sweep(&SPEEDS)
                        .unwrap();
                    for (i, (m, a)) in mu.iter().zip(&analytic).enumerate() {
                        let error = (m / a - 1.0).abs();
                        assert!(
                            error <= 10.0 * tol,
                            "{name} {shape:?} {contact:?} tol {tol:e} v {:e}: {error:e}",
                            SPEEDS[i]
                        );
                    }
                }
            }
        }
    }
}

/// A realistic sparse table (10 rows a decade): μ at tolerance 1e-6 against
/// the oracle's μ of the same interpolant — the quadrature alone. With the
/// product integration of an analytic modulus this was up to 1.3e-3 off.
#[test]
fn sparse_table_meets_the_tolerance_against_the_oracle() {
    let mut cases = Vec::new();
    for (name, prony, (lo, hi)) in materials().into_iter().take(3).skip(1) {
        for shape in [Shape::Sphere, Shape::Cylinder] {
            for contact in [ContactSize::Dynamic, ContactSize::Static] {
                cases.push((name, prony.clone(), (lo, hi), shape, contact));
            }
        }
    }
    // The eight scenes are independent: checked on every core (a failed
    // assertion in a worker fails the test with its message).
    cases
        .into_par_iter()
        .for_each(|(name, prony, (lo, hi), shape, contact)| {
            let table = sampled(&prony, &log_grid(lo, hi, 10.0, 0.37));
            let knots: Vec<f64> = table.omega().iter().map(|w| w.ln()).collect();
            let s = scene_of(shape, contact, table.clone(), 1e-6);
            let mu = s.friction_sweep(&CI_SPEEDS).unwrap();
            let oracle = Oracle::new(&s, &table, knots, BASE);
            for (&v, m) in CI_SPEEDS.iter().zip(&mu) {
                let error = (m / oracle.mu(v) - 1.0).abs();
                assert!(
                    error <= 1e-6,
                    "{name} {shape:?} {contact:?} v {v:e}: {error:e}"
                );
            }
        });
}

/// The table's error estimates, from its rows alone, against the true
/// errors on the analytic examples at 5, 10 and 20 rows a decade: the
/// modulus's largest relative error between rows, and μ's
/// (`Scene::table_interpolation_error` against μ of the analytic modulus).
#[test]
fn interpolation_error_estimates_track_the_true_errors() {
    for (name, prony, (lo, hi)) in materials().into_iter().take(3) {
        for per_decade in [5.0, 10.0, 20.0] {
            let table = sampled(&prony, &log_grid(lo, hi, per_decade, 0.37));
            let (true_storage, true_loss) = interpolation_error(&table, &prony);
            let (est_storage, est_loss) = table.interpolation_error_estimate();
            for (what, t, e) in [
                ("E'", true_storage, est_storage),
                ("E''", true_loss, est_loss),
            ] {
                assert!(
                    e > t / 2.0 && e < 2.0 * t,
                    "{name} {per_decade}/decade {what}: estimate {e:e}, true {t:e}"
                );
            }
            for shape in [Shape::Sphere, Shape::Cylinder] {
                let contact = ContactSize::Dynamic;
                let analytic = scene_of(shape, contact, prony.clone(), 1e-10)
                    .friction_sweep(&SPEEDS)
                    .unwrap();
                let s = scene_of(shape, contact, table.clone(), 1e-9);
                let mu = s.friction_sweep(&SPEEDS).unwrap();
                let estimate = s
                    .table_interpolation_error(&SPEEDS, &mu)
                    .unwrap()
                    .unwrap()
                    .into_iter()
                    .fold(0.0, f64::max);
                let truth = mu
                    .iter()
                    .zip(&analytic)
                    .map(|(m, a)| (m / a - 1.0).abs())
                    .fold(0.0, f64::max);
                println!(
                    "{name} {per_decade}/decade {shape:?}: μ estimate {estimate:.1e} true {truth:.1e}; E' {est_storage:.1e}/{true_storage:.1e} E'' {est_loss:.1e}/{true_loss:.1e}"
                );
                assert!(
                    estimate > truth / 2.0 && estimate < 2.0 * truth,
                    "{name} {per_decade}/decade {shape:?}: μ estimate {estimate:e}, true {truth:e}"
                );
            }
        }
    }
}
