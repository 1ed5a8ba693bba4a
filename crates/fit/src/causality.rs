//! Causality (Kramers–Kronig) check of DMA data: can any linear
//! viscoelastic solid have both the measured E′(ω) and E″(ω)?
//!
//! For a causal, passive linear solid E′ and E″ are not independent: they
//! are Kramers–Kronig transforms of each other, and near a loss peak
//! tan δ ≈ (π/2) d ln E′/d ln ω (Booij–Thoone). Real master curves often
//! break this (a poor shift, a vertical shift left out, instrument
//! compliance at the glassy end); then no master curve recovered from
//! μ(v) — always a causal Prony series — can match both E′ and E″, and the
//! comparison must say so instead of blaming the fit.
//!
//! Method: every causal passive solid with a discrete spectrum is a Prony
//! series, and a dense one approximates any continuous spectrum. Fit the
//! (reference-shifted) DMA points with
//!
//! E*(ω) = E0 + Σ_k ΔE_k iωτ_k/(1 + iωτ_k),  E0 ≥ 0, ΔE_k ≥ 0,
//!
//! i.e. E′ = E0 + Σ ΔE_k ω²τ_k²/(1 + ω²τ_k²), E″ = Σ ΔE_k ωτ_k/(1 + ω²τ_k²),
//! on a fixed grid of [`TAU_PER_DECADE`] log-spaced τ_k per decade covering
//! 1/ω over the data's range widened by one decade on each side (so that
//! the ends of the data are not starved of relaxation times). With τ fixed
//! the model is linear in (E0, ΔE), so minimising the relative residuals of
//! E′ and E″ jointly,
//!
//! min Σ_i [(E′(ω_i) − E′_i)/E′_i]² + [(E″(ω_i) − E″_i)/E″_i]²,
//!
//! is a non-negative least-squares problem, solved exactly (no start, no
//! local minima) by the active-set method of Lawson and Hanson ([`nnls`]).
//! The non-negativity is what makes the model causal *and* passive; without
//! it any smooth data could be matched.
//!
//! The misfit is reported per component as the RMS log10 error (decades)
//! of the causal fit against the data,
//!
//! m′ = √(mean_i [log10 E′_fit(ω_i) − log10 E′_i]²), m″ likewise,
//!
//! so that 0.01 means about 2.3 % RMS, and the largest |log10 error| of each
//! (with the point where it is, to name the isotherm).
//!
//! Measured (3 τ per decade): data from a quasi-continuous causal spectrum
//! (4 terms per decade, off the grid) give m′, m″ ≈ 1e-6; an isolated pair
//! of Maxwell elements between grid nodes, the hardest causal case (a sum
//! of non-negative neighbours cannot be as narrow as one element), about
//! 3e-3/5e-3; Gaussian scatter of 1, 2 and 5 % on a broad rubber (340
//! points) about 0.004, 0.0085 and 0.021, i.e. the noise itself. A broad
//! rubber with E″ raised by 50 % within a decade of its loss peak gives
//! m′ = 0.025, m″ = 0.040 and a largest E″ miss of 0.13 decades.
//!
//! Thresholds: RMS [`KK_MISFIT_THRESHOLD`] = 0.03 decades (7 %), largest
//! [`KK_MAX_MISFIT_THRESHOLD`] = 0.1 decades (26 %) at one point. A good
//! DMA master curve (up to ~5 % scatter) passes both; a global violation
//! (the raised peak) fails the RMS, a local one (one bad isotherm) the
//! largest miss, which hundreds of good points dilute in the RMS.
//!
//! The 3M 468MP adhesive (shear, ν = 0.5, 20 isotherms −40 to 150 °C, 339
//! points after dropping one E″ < 0, shifted to 20 °C with WLF C1 = 9.06,
//! C2 = 129.3 K estimated from its isotherms, 14.5 decades) gives
//! m′ = 0.0105, m″ = 0.0163: causal to a few tenths of a per cent from
//! 1e-5 to 1e7 rad/s, including the loss peak (tan δ ≈ 1.15), but not at
//! the glassy end, where the −30 and −40 °C isotherms overlap: there the
//! largest misses are 0.047 (E′) and 0.131 decades (E″), so the check
//! warns. Near the peak the data's tan δ is ~40 % above the small-slope
//! rule (π/2) d ln E′/d ln ω; that is the rule's error, not the data's
//! (for E* ∝ (iω)^n, tan δ = tan(nπ/2), 1.33 × (π/2)n at n = 0.53), and
//! the exact fit above matches both E′ and E″ there.
//!
//! Why our own NNLS: no well-kept NNLS crate works on nalgebra matrices
//! (the Rust ones we know of are built on ndarray and would bring a second
//! linear-algebra stack into the workspace); Lawson–Hanson is a few dozen
//! lines on nalgebra's SVD, and the problem here is small (2 × a few
//! hundred rows, ~60 columns).
//!
//! # References
//! - N.W. Tschoegl, *The Phenomenological Theory of Linear Viscoelastic
//!   Behavior*, Springer 1989, Ch. 3–4 (Prony series, discrete spectra).
//! - C.L. Lawson, R.J. Hanson, *Solving Least Squares Problems*,
//!   Prentice-Hall 1974, Ch. 23 (algorithm NNLS).
//! - F.R. Schwarzl, L.C.E. Struik, "Analysis of relaxation measurements",
//!   Adv. Mol. Relax. Processes 1 (1967) 201–255 (interconversion and the
//!   Kramers–Kronig relations of viscoelastic functions).
//! - H.C. Booij, G.P.J.M. Thoone, "Generalization of Kramers–Kronig
//!   transforms and some approximations of relations between viscoelastic
//!   quantities", Rheol. Acta 21 (1982) 15–24.

use crate::error::FitError;
use crate::master::condense::condense;
use nalgebra::{DMatrix, DVector};
use num_complex::Complex64;

/// One point of E*(ω) under check: at a reduced frequency, Young's moduli.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModulusSample {
    /// Reduced angular frequency ω a_T, rad/s.
    pub omega: f64,
    /// Young's storage modulus E′, Pa.
    pub storage: f64,
    /// Young's loss modulus E″, Pa.
    pub loss: f64,
    /// The temperature it was measured at, °C, when known (to name the
    /// isotherm of a local violation).
    pub temperature: Option<f64>,
}

/// Relaxation times per decade of the causal model: a smooth spectrum off
/// the grid is matched to ~1e-6 decades (denser grids do not help isolated
/// elements, whose error depends on their distance to the nearest node).
/// The grid is the one `rollfit master` fits its smooth Prony series on,
/// so that this check's misfit is the floor that fit tends to as its
/// smoothness weight goes to zero.
pub use crate::master::TAU_PER_DECADE;

/// Above this RMS log10 misfit (decades) of E′ or E″ the DMA data are
/// reported as not causal: a violation spread over the curve (see the
/// module doc for the measured values).
pub const KK_MISFIT_THRESHOLD: f64 = 0.03;

/// Above this largest |log10 misfit| (decades) of E′ or E″ at one point
/// the DMA data are reported as not causal there: a local violation (one
/// bad isotherm) that the RMS over hundreds of points dilutes.
pub const KK_MAX_MISFIT_THRESHOLD: f64 = 0.1;

/// The best causal fit of DMA data.
#[derive(Debug, Clone)]
pub struct CausalFit {
    /// E0 = E′(0), Pa.
    pub rubbery_modulus: f64,
    /// τ_k, s, ascending.
    pub tau: Vec<f64>,
    /// ΔE_k, Pa.
    pub strengths: Vec<f64>,
    /// RMS log10 error of E′ (decades).
    pub misfit_storage: f64,
    /// RMS log10 error of E″ (decades).
    pub misfit_loss: f64,
    /// Largest |log10 error| of E′ (decades) and the point where it is.
    pub max_misfit_storage: (f64, ModulusSample),
    /// Largest |log10 error| of E″ (decades) and the point where it is.
    pub max_misfit_loss: (f64, ModulusSample),
    /// The data's reduced-frequency range, rad/s.
    pub omega_range: (f64, f64),
    /// A warning when either misfit exceeds [`KK_MISFIT_THRESHOLD`].
    pub warnings: Vec<String>,
}

impl CausalFit {
    /// E*(ω) of the causal model, Pa.
    pub fn modulus(&self, omega: f64) -> Complex64 {
        let i_omega = Complex64::new(0.0, omega);
        self.tau.iter().zip(&self.strengths).fold(
            Complex64::new(self.rubbery_modulus, 0.0),
            |sum, (tau, h)| sum + h * i_omega * tau / (1.0 + i_omega * tau),
        )
    }

    /// The causal curve at `count` log-spaced frequencies over the data's
    /// range, as samples without temperature.
    pub fn curve(&self, count: usize) -> Vec<ModulusSample> {
        let (lo, hi) = (self.omega_range.0.log10(), self.omega_range.1.log10());
        let count = count.max(2);
        (0..count)
            .map(|j| {
                let omega = 10f64.powf(lo + (hi - lo) * j as f64 / (count - 1) as f64);
                let e = self.modulus(omega);
                ModulusSample {
                    omega,
                    storage: e.re,
                    loss: e.im,
                    temperature: None,
                }
            })
            .collect()
    }
}

/// The relaxation-time grid for data over [ω_lo, ω_hi]: τ from
/// 1/(10 ω_hi) to 10/ω_lo, [`TAU_PER_DECADE`] per decade, ends included
/// (defined once, with the master curve's Prony fit).
pub use crate::master::tau_grid;

/// Fits `points` (reduced to one reference state, Young's moduli > 0) with
/// a causal Prony series and measures the misfit (see the module doc).
pub fn check(points: &[ModulusSample]) -> Result<CausalFit, FitError> {
    if points.is_empty() {
        return Err(FitError::NoCausalityPoints);
    }
    let omega_lo = points.iter().map(|p| p.omega).fold(f64::INFINITY, f64::min);
    let omega_hi = points.iter().map(|p| p.omega).fold(0.0, f64::max);
    let tau = tau_grid(omega_lo, omega_hi);
    let (mut a, b) = relative_rows(points, &tau);
    // Unit columns: the moduli span decades, and the active-set test
    // compares gradient components across columns.
    let columns = tau.len() + 1;
    let norms: Vec<f64> = (0..columns).map(|k| a.column(k).norm()).collect();
    for (k, norm) in norms.iter().enumerate() {
        if *norm > 0.0 {
            a.column_mut(k).scale_mut(1.0 / norm);
        }
    }
    // 1/E″ of a subnormal E″ overflows; the SVD would panic on it.
    if a.iter().any(|x| !x.is_finite()) {
        return Err(FitError::CausalityModuliOutOfRange);
    }
    let x = nnls(&a, &b);
    let scaled: Vec<f64> = x
        .iter()
        .zip(&norms)
        .map(|(x, norm)| if *norm > 0.0 { x / norm } else { 0.0 })
        .collect();
    let mut fit = CausalFit {
        rubbery_modulus: scaled[0],
        tau,
        strengths: scaled[1..].to_vec(),
        misfit_storage: 0.0,
        misfit_loss: 0.0,
        max_misfit_storage: (0.0, points[0]),
        max_misfit_loss: (0.0, points[0]),
        omega_range: (omega_lo, omega_hi),
        warnings: Vec::new(),
    };
    let (mut storage, mut loss) = (0.0, 0.0);
    for p in points {
        let e = fit.modulus(p.omega);
        let r_storage = (e.re / p.storage).log10();
        // A causal fit with E″ = 0 at a point (all strengths zero there)
        // misses it by infinitely many decades; keep the number finite.
        let r_loss = (e.im.max(f64::MIN_POSITIVE) / p.loss).log10();
        storage += r_storage * r_storage;
        loss += r_loss * r_loss;
        if r_storage.abs() > fit.max_misfit_storage.0 {
            fit.max_misfit_storage = (r_storage.abs(), *p);
        }
        if r_loss.abs() > fit.max_misfit_loss.0 {
            fit.max_misfit_loss = (r_loss.abs(), *p);
        }
    }
    let count = points.len() as f64;
    fit.misfit_storage = (storage / count).sqrt();
    fit.misfit_loss = (loss / count).sqrt();
    let at = |p: &ModulusSample| match p.temperature {
        Some(t) => format!("ω a_T = {:.3e} rad/s, measured at {t:.1} °C", p.omega),
        None => format!("ω = {:.3e} rad/s", p.omega),
    };
    if fit.misfit_storage > KK_MISFIT_THRESHOLD || fit.misfit_loss > KK_MISFIT_THRESHOLD {
        fit.warnings.push(format!(
            "the DMA data are not causal: the best linear viscoelastic (Prony) fit misses E′ by {:.3} and E″ by {:.3} decades RMS (threshold {KK_MISFIT_THRESHOLD}); no master curve can match both, so differences between the fit and the DMA in E′ or E″ are partly the DMA's (check its shift)",
            fit.misfit_storage, fit.misfit_loss
        ));
    }
    for (name, (worst, p)) in [("E′", fit.max_misfit_storage), ("E″", fit.max_misfit_loss)] {
        if worst > KK_MAX_MISFIT_THRESHOLD {
            fit.warnings.push(format!(
                "the DMA data are not causal near {}: no linear viscoelastic (Prony) fit comes closer than {worst:.3} decades to {name} there (threshold {KK_MAX_MISFIT_THRESHOLD}); suspect that isotherm or its shift",
                at(&p)
            ));
        }
    }
    Ok(fit)
}

/// The NNLS system of the module doc for `points` on the grid `tau`: rows
/// 0..n are E′'s relative residuals, n..2n E″'s, column 0 is E0. Thousands
/// of points give their bins of 1/50 decade, each row weighted by √(its
/// count), as the master curve's series is fitted (module doc of
/// `rollfit_fit::master::condense`).
fn relative_rows(points: &[ModulusSample], tau: &[f64]) -> (DMatrix<f64>, DVector<f64>) {
    let (omega, storage, loss): (Vec<f64>, Vec<f64>, Vec<f64>) = (
        points.iter().map(|p| p.omega).collect(),
        points.iter().map(|p| p.storage).collect(),
        points.iter().map(|p| p.loss).collect(),
    );
    let condensed = condense(&omega, &storage, &loss);
    let (omega, storage, loss, root_count) = match &condensed {
        Some(c) => (
            c.omega.as_slice(),
            c.storage.as_slice(),
            c.loss.as_slice(),
            c.count.iter().map(|n| n.sqrt()).collect(),
        ),
        None => (
            omega.as_slice(),
            storage.as_slice(),
            loss.as_slice(),
            vec![1.0; omega.len()],
        ),
    };
    let n = omega.len();
    let columns = tau.len() + 1;
    // Rows 0..n: E′ relative residuals, n..2n: E″; column 0 is E0.
    let mut a = DMatrix::<f64>::zeros(2 * n, columns);
    for i in 0..n {
        a[(i, 0)] = 1.0 / storage[i];
        for (k, t) in tau.iter().enumerate() {
            let x = omega[i] * t;
            let d = 1.0 + x * x;
            a[(i, k + 1)] = x * x / d / storage[i];
            a[(n + i, k + 1)] = x / d / loss[i];
        }
    }
    if condensed.is_some() {
        for (i, &weight) in root_count.iter().enumerate() {
            a.row_mut(i).scale_mut(weight);
            a.row_mut(n + i).scale_mut(weight);
        }
    }
    let b = if condensed.is_some() {
        DVector::from_iterator(2 * n, root_count.iter().chain(&root_count).copied())
    } else {
        DVector::from_element(2 * n, 1.0)
    };
    (a, b)
}

/// Non-negative least squares, min ‖A x − b‖₂ subject to x ≥ 0, by the
/// active-set algorithm of Lawson & Hanson (1974, Ch. 23). Each inner step
/// solves the unconstrained problem on the passive set by SVD (columns of a
/// dense Prony grid are nearly collinear, so no normal equations).
pub fn nnls(a: &DMatrix<f64>, b: &DVector<f64>) -> DVector<f64> {
    let n = a.ncols();
    let mut x = DVector::<f64>::zeros(n);
    let mut passive = vec![false; n];
    let tolerance = 10.0 * f64::EPSILON * a.abs().row_sum().max() * (a.nrows().max(n) as f64);
    let max_iterations = 3 * n + 10;
    let solve = |passive: &[bool]| -> DVector<f64> {
        let indices: Vec<usize> = (0..n).filter(|&j| passive[j]).collect();
        let sub = a.select_columns(&indices);
        let z = sub
            .svd(true, true)
            .solve(b, f64::EPSILON)
            .expect("SVD with both factors computed");
        let mut s = DVector::<f64>::zeros(n);
        for (k, &j) in indices.iter().enumerate() {
            s[j] = z[k];
        }
        s
    };
    for _ in 0..max_iterations {
        let w = a.transpose() * (b - a * &x);
        let Some((t, w_max)) = (0..n)
            .filter(|&j| !passive[j])
            .map(|j| (j, w[j]))
            .max_by(|p, q| p.1.total_cmp(&q.1))
        else {
            break;
        };
        if w_max <= tolerance {
            break;
        }
        passive[t] = true;
        let mut inner = 0;
        loop {
            let s = solve(&passive);
            if (0..n).filter(|&j| passive[j]).all(|j| s[j] > 0.0) {
                x = s;
                break;
            }
            // Step from x towards s as far as feasibility allows, and
            // release the variables that hit zero.
            let alpha = (0..n)
                .filter(|&j| passive[j] && s[j] <= 0.0)
                .map(|j| x[j] / (x[j] - s[j]))
                .fold(f64::INFINITY, f64::min);
            x += (s - &x) * alpha;
            for j in 0..n {
                if passive[j] && x[j] <= tolerance {
                    passive[j] = false;
                    x[j] = 0.0;
                }
            }
            inner += 1;
            if inner > max_iterations {
                break;
            }
        }
    }
    x
}
