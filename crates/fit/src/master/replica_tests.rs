//! Synthetic replicas of real DMA sets that `rollfit master` met (narrow
//! windows, steps of 1.5–3.5 decades between neighbours, 21 isotherms from
//! the glass to the rubber with a β relaxation whose tan δ does not shift
//! with E′; a foam of 19 isotherms over 2-decade windows), fixed seeds.
//! The classes of pairs are decided by an independent oracle in the test:
//! a brute-force scan of the noise-free isotherms for the shift log E′
//! alone and log tan δ alone need.

use super::pairwise::{DETERMINED_SIGMA, PairVerdict};
use super::*;
use num_complex::Complex64;
use rand::SeedableRng;
use rand_chacha::ChaCha8Rng;
use rand_distr::Normal;
use rollfit_model::{HavriliakNegami, ViscoelasticModulus};

/// A material of two processes with their own shifts: E*(ω, T) =
/// E_α(ω a_α(T)) + ΔE_β (iω a_β τ_β)^m/(1 + (iω a_β τ_β)^m).
struct TwoProcess {
    alpha: HavriliakNegami,
    beta_strength: f64,
    beta_tau: f64,
    beta_width: f64,
}

impl TwoProcess {
    fn modulus(&self, omega: f64, log_a_alpha: f64, log_a_beta: f64) -> Complex64 {
        let e = self.alpha.modulus(omega * 10f64.powf(log_a_alpha));
        let x = Complex64::new(0.0, omega * 10f64.powf(log_a_beta) * self.beta_tau)
            .powf(self.beta_width);
        e + self.beta_strength * x / (1.0 + x)
    }
}

/// Isotherms at `temps`, `count` frequencies over `decades` from 0.1 Hz,
/// relative noise `noise` on E′ and E″.
fn replica(
    material: &TwoProcess,
    temps: &[f64],
    shifts: &dyn Fn(usize) -> (f64, f64),
    (count, decades): (usize, f64),
    noise: f64,
    seed: u64,
) -> Vec<Isotherm> {
    let mut rng = ChaCha8Rng::seed_from_u64(seed);
    let normal = Normal::new(0.0, 1.0).unwrap();
    temps
        .iter()
        .enumerate()
        .map(|(k, &t)| {
            let (a, b) = shifts(k);
            let omega: Vec<f64> = (0..count)
                .map(|i| {
                    2.0 * std::f64::consts::PI
                        * 0.1
                        * 10f64.powf(decades * i as f64 / (count - 1) as f64)
                })
                .collect();
            let e: Vec<Complex64> = omega.iter().map(|&w| material.modulus(w, a, b)).collect();
            super::tests::measured(t, omega, &e, noise, (&mut rng, &normal))
        })
        .collect()
}

/// The oracle: the shift s with curve_j(x) = curve_i(x + s) of the
/// noise-free isotherms, by a scan of 0.002 decade over every shift with
/// at least two points of overlap, for log E′ (k = 0) or log tan δ (1).
fn oracle_shift(lower: &Isotherm, upper: &Isotherm, k: usize) -> f64 {
    let curve = |iso: &Isotherm| -> Vec<(f64, f64)> {
        (0..iso.omega.len())
            .map(|i| {
                let y = if k == 0 {
                    iso.storage[i]
                } else {
                    iso.loss[i] / iso.storage[i]
                };
                (iso.omega[i].log10(), y.log10())
            })
            .collect()
    };
    let (l, u) = (curve(lower), curve(upper));
    let at = |c: &[(f64, f64)], x: f64| -> Option<f64> {
        let j = c.iter().position(|p| p.0 >= x)?;
        if j == 0 {
            return (c[0].0 == x).then_some(c[0].1);
        }
        let w = (x - c[j - 1].0) / (c[j].0 - c[j - 1].0);
        Some(c[j - 1].1 * (1.0 - w) + c[j].1 * w)
    };
    let mut best = (f64::INFINITY, 0.0);
    for i in -5000..=5000 {
        let s = i as f64 * 0.002;
        let d: Vec<f64> = u
            .iter()
            .filter_map(|p| at(&l, p.0 + s).map(|y| p.1 - y))
            .collect();
        if d.len() < 2 {
            continue;
        }
        let m = d.iter().map(|d| d * d).sum::<f64>() / d.len() as f64;
        if m < best.0 {
            best = (m, s);
        }
    }
    best.1
}

/// The Eplexor-like set: 21 isotherms 7.5 K apart from −50 to 100 °C, 10
/// frequencies over 3 decades; the α process steps by 3.5 decades at the
/// cold end down to 1.5 at the warm end (not WLF), the β process by 0.07
/// decade per step (a low activation energy).
fn eplexor_like() -> (TwoProcess, Vec<f64>, Vec<f64>, Vec<f64>) {
    let material = TwoProcess {
        alpha: HavriliakNegami::new(3e6, 1.5e9, 1e28, 0.35, 0.45).unwrap(),
        beta_strength: 2e8,
        beta_tau: 0.03,
        beta_width: 0.3,
    };
    let temps: Vec<f64> = (0..21).map(|k| -50.0 + 7.5 * k as f64).collect();
    let mut log_alpha = vec![0.0];
    let mut log_beta = vec![0.0];
    for k in 0..20 {
        log_alpha.push(log_alpha[k] - (3.5 - 2.0 * k as f64 / 19.0));
        log_beta.push(log_beta[k] - 0.07);
    }
    (material, temps, log_alpha, log_beta)
}

/// On the Eplexor-like replica with 1 % noise, over 3 seeds: where the
/// oracle's E′ and tan δ shifts of the measured isotherms agree within 0.2
/// decade and the pair is not on a plateau, the shift is within 0.1 decade
/// of the noise-free oracle's,
/// determined, σ ≤ 0.1; where they differ by more than 0.3, no shift is
/// determined with σ < 0.1 and the warnings say superposition fails; the
/// set gives shift factors (no refusal) with default settings.
#[test]
fn eplexor_like_replica_superposes_where_it_can_and_says_where_not() {
    let (material, temps, log_alpha, log_beta) = eplexor_like();
    let shifts = |k: usize| (log_alpha[k], log_beta[k]);
    let exact = replica(&material, &temps, &shifts, (10, 3.0), 0.0, 0);
    let span = |iso: &Isotherm, k: usize| {
        let y: Vec<f64> = (0..iso.omega.len())
            .map(|i| {
                if k == 0 {
                    iso.storage[i].log10()
                } else {
                    (iso.loss[i] / iso.storage[i]).log10()
                }
            })
            .collect();
        y.iter().copied().fold(f64::NEG_INFINITY, f64::max)
            - y.iter().copied().fold(f64::INFINITY, f64::min)
    };
    // The noise-free oracle's shift (the reference) and which pairs lie
    // off a plateau.
    let mut reference = Vec::new();
    let mut sloped = Vec::new();
    let mut exact_gap = Vec::new();
    for k in 0..20 {
        let (e, t) = (
            oracle_shift(&exact[k], &exact[k + 1], 0),
            oracle_shift(&exact[k], &exact[k + 1], 1),
        );
        reference.push(0.5 * (e + t));
        exact_gap.push((e - t).abs());
        sloped.push(
            [&exact[k], &exact[k + 1]]
                .iter()
                .all(|iso| span(iso, 0) >= 0.04 || span(iso, 1) >= 0.1),
        );
        eprintln!(
            "pair {k} ({} °C): E′ {e:.3}, tan δ {t:.3}, α step {:.3}, spans {:.3} {:.3}",
            temps[k],
            log_alpha[k + 1] - log_alpha[k],
            span(&exact[k], 0),
            span(&exact[k], 1)
        );
    }
    for seed in 0..3 {
        let isotherms = replica(&material, &temps, &shifts, (10, 3.0), 0.01, 40 + seed);
        // The classes as the issue defines them, on the measured (noisy)
        // isotherms and, so that the truth is one shift or clearly two, on
        // the noise-free ones: the best shifts of log E′ alone and log tan δ
        // alone agree within 0.2 decade (and the pair is off a plateau), or
        // differ by more than 0.3. A gap the noise of a nearly flat E′ makes
        // alone is neither.
        let (mut holds, mut fails) = (Vec::new(), Vec::new());
        for k in 0..20 {
            let d = oracle_shift(&isotherms[k], &isotherms[k + 1], 0)
                - oracle_shift(&isotherms[k], &isotherms[k + 1], 1);
            if d.abs() <= 0.2 && exact_gap[k] <= 0.2 && sloped[k] {
                holds.push(k);
            } else if d.abs() > 0.3 && exact_gap[k] > 0.3 {
                fails.push(k);
            }
        }
        eprintln!("seed {seed}: holds {holds:?}, fails {fails:?}");
        assert!(
            holds.len() >= 5 && fails.len() >= 3,
            "replica classes {holds:?} {fails:?}"
        );
        let valid = MasterSettings::default().check(&isotherms).unwrap();
        let factors = shift_factors(&isotherms, &valid).unwrap();
        assert!(factors.shifts.iter().any(|s| s.determined));
        for &k in &holds {
            let p = factors
                .pairs
                .iter()
                .find(|p| p.lower == k && p.upper == k + 1)
                .unwrap();
            let truth = reference[k];
            assert!(
                p.verdict == PairVerdict::Determined
                    && p.sigma <= 0.1
                    && (p.shift - truth).abs() <= 0.1,
                "seed {seed}, pair {k}: {p:?}, truth {truth}"
            );
        }
        for &k in &fails {
            let p = factors
                .pairs
                .iter()
                .find(|p| p.lower == k && p.upper == k + 1)
                .unwrap();
            assert!(
                !(p.verdict == PairVerdict::Determined && p.sigma < 0.1),
                "seed {seed}, pair {k}: {p:?}"
            );
        }
        if factors.pairs.iter().any(|p| p.tts_fails) {
            assert!(
                factors
                    .warnings
                    .iter()
                    .any(|w| w.contains("superposition fails")),
                "{:?}",
                factors.warnings
            );
        }
        report_named(&factors, &isotherms, &fails, seed);
        for s in &factors.shifts {
            assert_eq!(s.determined, s.log_shift_measured_sigma <= DETERMINED_SIGMA);
        }
    }
}

/// The null case of the superposition test: the Eplexor-like set with its
/// β process shifting exactly as the α process does, so that one shift
/// superposes every pair (thermorheologically simple), including the
/// glassy pairs whose E′ is nearly flat and whose tan δ has its best
/// overlap at the overlap's end. Over 40 seeds at 1 % noise no pair is
/// named a superposition failure, no warning says so, and the van
/// Gurp–Palmen test finds no pair apart.
#[test]
fn simple_eplexor_like_replica_is_never_called_complex() {
    let (material, temps, log_alpha, _) = eplexor_like();
    let shifts = |k: usize| (log_alpha[k], log_alpha[k]);
    for seed in 0..40 {
        let isotherms = replica(&material, &temps, &shifts, (10, 3.0), 0.01, 90 + seed);
        let valid = MasterSettings::default().check(&isotherms).unwrap();
        let factors = shift_factors(&isotherms, &valid).unwrap();
        let named: Vec<_> = factors.pairs.iter().filter(|p| p.tts_fails).collect();
        assert!(named.is_empty(), "seed {seed}: {named:?}");
        let vgp = van_gurp_palmen(&isotherms);
        let apart: Vec<_> = vgp
            .pairs
            .iter()
            .filter(|p| p.collapses() == Some(false))
            .collect();
        assert!(apart.is_empty(), "seed {seed}: van Gurp–Palmen {apart:?}");
        assert!(
            !factors
                .warnings
                .iter()
                .any(|w| w.contains("superposition fails")),
            "seed {seed}: {:?}",
            factors.warnings
        );
    }
}

/// Prints how many of the failing pairs `fails` the summary names as
/// superposition failures: by their shifts, by the van Gurp–Palmen test,
/// or by either; asserts that their shifts name every one.
fn report_named(factors: &ShiftFactors, isotherms: &[Isotherm], fails: &[usize], seed: u64) {
    // The van Gurp–Palmen test names a failure without any shift, where a
    // nearly flat E′ leaves its own shift unfixed.
    let vgp = van_gurp_palmen(isotherms);
    let by_shifts = |k: usize| {
        factors
            .pairs
            .iter()
            .any(|p| p.lower == k && p.upper == k + 1 && p.tts_fails)
    };
    let by_vgp = |k: usize| {
        vgp.pairs
            .iter()
            .any(|p| p.t_lower == isotherms[k].temperature && p.collapses() == Some(false))
    };
    let count = |named: &dyn Fn(usize) -> bool| fails.iter().filter(|&&k| named(k)).count();
    eprintln!(
        "seed {seed}: of {} failing pairs {} named by their shifts, {} by van Gurp–Palmen, {} \
         by either",
        fails.len(),
        count(&by_shifts),
        count(&by_vgp),
        count(&|k| by_shifts(k) || by_vgp(k))
    );
    assert_eq!(
        count(&by_shifts),
        fails.len(),
        "seed {seed}: failing pairs {fails:?}"
    );
}

/// The foam-like set: 19 isotherms from −35 to 60 °C, 10 frequencies over
/// 2 decades, WLF shifts; at 10 °C E′ rises steeply across the window.
/// With default settings the pairs from −15 to 10 °C are determined within
/// 0.1 decade of the truth, σ ≤ 0.1, and the set gives a master curve.
#[test]
fn foam_like_replica_is_superposed() {
    let material = TwoProcess {
        alpha: HavriliakNegami::new(1e5, 3e7, 0.03, 0.5, 0.5).unwrap(),
        beta_strength: 0.0,
        beta_tau: 1.0,
        beta_width: 0.5,
    };
    let temps: Vec<f64> = (0..19).map(|k| -35.0 + 95.0 * k as f64 / 18.0).collect();
    let law = |t: f64| -10.0 * (t - 10.0) / (80.0 + t - 10.0);
    let shifts = |k: usize| (law(temps[k]), 0.0);
    let exact = replica(&material, &temps, &shifts, (10, 2.0), 0.0, 0);
    let middle = exact
        .iter()
        .find(|i| (i.temperature - 10.0).abs() < 3.0)
        .unwrap();
    let rise = middle.storage[9] / middle.storage[0];
    eprintln!("E′ rises ×{rise:.2} at {} °C", middle.temperature);
    assert!(rise >= 1.5, "E′ rises ×{rise} only");
    for seed in 0..3 {
        let isotherms = replica(&material, &temps, &shifts, (10, 2.0), 0.01, 70 + seed);
        let valid = MasterSettings::default().check(&isotherms).unwrap();
        let master = build_master_curve(&isotherms, &valid).unwrap();
        let factors = &master.shift;
        for p in factors.pairs.iter().filter(|p| p.upper == p.lower + 1) {
            let (tl, tu) = (temps[p.lower], temps[p.upper]);
            if tl >= -15.5 && tu <= 10.5 {
                let truth = law(tu) - law(tl);
                assert!(
                    p.verdict == PairVerdict::Determined
                        && p.sigma <= 0.1
                        && (p.shift - truth).abs() <= 0.1,
                    "seed {seed}, {tl}–{tu} °C: {p:?}, truth {truth}"
                );
            }
        }
        assert!(master.determined_window.is_some());
    }
}

/// A narrow window and a big step: two isotherms of 10 frequencies over 3
/// decades, 2.2 decades apart on a sloped transition, overlap on about
/// three points each; the shift is measured there (the old rule of a
/// fifth of the points and four refused it at the overlap's edge), within
/// 0.1 decade over 10 seeds, its 2σ covering the truth in ≥ 9.
#[test]
fn big_steps_on_narrow_windows_are_measured() {
    let material = TwoProcess {
        alpha: HavriliakNegami::new(3e6, 1.5e9, 1e-3, 0.3, 0.5).unwrap(),
        beta_strength: 0.0,
        beta_tau: 1.0,
        beta_width: 0.5,
    };
    let temps = [0.0, 7.5, 15.0];
    let steps = [0.0, -2.2, -4.2];
    let mut covered = 0;
    for seed in 0..10 {
        let isotherms = replica(
            &material,
            &temps,
            &|k| (steps[k], 0.0),
            (10, 3.0),
            0.01,
            seed,
        );
        let valid = MasterSettings::default().check(&isotherms).unwrap();
        let factors = shift_factors(&isotherms, &valid).unwrap();
        let p = factors.pairs[0];
        assert!(
            p.verdict == PairVerdict::Determined && (p.shift + 2.2).abs() <= 0.1,
            "seed {seed}: {p:?}"
        );
        if (p.shift + 2.2).abs() <= 2.0 * p.sigma {
            covered += 1;
        }
    }
    assert!(covered >= 9, "2σ covers the truth in {covered} of 10");
}

/// A study of the mismatch targets of the held-out real sets, asked of
/// the β replica: the mean neighbour-pair mismatch of log E′ under the
/// applied shifts against 1.5× that of a tool superposing E′ alone (each
/// pair at its own best E′ shift, the least any such tool reaches), and
/// that of log tan δ against the E′ tool's. Printed, not asserted: the
/// log E′ target is not met (BENCHMARKS.md, "Master curves of real DMA
/// files"), since where superposition fails the pair's shift follows
/// tan δ. `cargo test --release -p rollfit-fit --lib study_beta_replica
/// -- --ignored --nocapture`.
#[test]
#[ignore = "a study: prints the mismatch against an E′-only tool's"]
fn study_beta_replica_mismatch() {
    let (material, temps, log_alpha, log_beta) = eplexor_like();
    let shifts = |k: usize| (log_alpha[k], log_beta[k]);
    for seed in 0..8 {
        let isotherms = replica(&material, &temps, &shifts, (10, 3.0), 0.01, 40 + seed);
        let valid = MasterSettings::default().check(&isotherms).unwrap();
        let factors = shift_factors(&isotherms, &valid).unwrap();
        // The applied increments, in the oracle's convention: isotherm k + 1
        // at log ω + log a_T(k + 1) meets isotherm k at log ω + log a_T(k).
        let increment = |k: usize| factors.shifts[k + 1].log_shift - factors.shifts[k].log_shift;
        let (mut ours, mut theirs) = ([0.0; 2], [0.0; 2]);
        for k in 0..20 {
            let (lower, upper) = (&isotherms[k], &isotherms[k + 1]);
            let best_e = oracle_shift(lower, upper, 0);
            for q in 0..2 {
                ours[q] += mismatch(lower, upper, q, increment(k)) / 20.0;
                theirs[q] += mismatch(lower, upper, q, best_e) / 20.0;
            }
        }
        eprintln!(
            "seed {seed}: mean pair mismatch log E′ {:.4} (E′ tool {:.4}), log tan δ {:.4} \
             (E′ tool {:.4})",
            ours[0], theirs[0], ours[1], theirs[1]
        );
        eprintln!(
            "seed {seed}: ratios log E′ {:.2} (target ≤ 1.5), log tan δ {:.2} (target ≤ 1)",
            ours[0] / theirs[0],
            ours[1] / theirs[1]
        );
    }
}

/// The RMS difference, over the overlap, of log E′ (q = 0) or log tan δ
/// (1) between `upper` and `lower` shifted by `s` decades (the oracle's
/// convention: curve_upper(x) against curve_lower(x + s)), interpolated
/// linearly in log ω.
fn mismatch(lower: &Isotherm, upper: &Isotherm, q: usize, s: f64) -> f64 {
    let y = |iso: &Isotherm, i: usize| {
        if q == 0 {
            iso.storage[i].log10()
        } else {
            (iso.loss[i] / iso.storage[i]).log10()
        }
    };
    let x: Vec<f64> = lower.omega.iter().map(|w| w.log10()).collect();
    let mut sum = 0.0;
    let mut n = 0;
    for i in 0..upper.omega.len() {
        let at = upper.omega[i].log10() + s;
        let Some(j) = (1..x.len()).find(|&j| x[j] >= at && x[j - 1] <= at) else {
            continue;
        };
        let w = (at - x[j - 1]) / (x[j] - x[j - 1]);
        let d = y(upper, i) - (y(lower, j - 1) * (1.0 - w) + y(lower, j) * w);
        sum += d * d;
        n += 1;
    }
    assert!(n > 0, "no overlap at shift {s}");
    (sum / n as f64).sqrt()
}
