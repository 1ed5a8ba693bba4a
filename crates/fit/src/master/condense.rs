//! Shifted DMA points condensed to narrow bins of reduced frequency before
//! a series is fitted to them.
//!
//! A master curve from many long isotherms (60 isotherms of 3000
//! frequencies) holds far more points than its shape has
//! features: the series it is fitted with has [`super::TAU_PER_DECADE`]
//! relaxation times per decade and cannot follow anything narrower than a
//! third of a decade, while a fit's cost and memory grow with every point
//! (a dense Jacobian of 2N rows). Above [`CONDENSE_ABOVE_POINTS`] points,
//! the points are grouped into bins of 1/[`BINS_PER_DECADE`] decade of
//! reduced ω, and each bin becomes one point of weight n_b (its count):
//!
//!   ln ω̄ = mean ln ω_i,  ln Ē′ = mean ln E′_i,  ln Ē″ = mean ln E″_i.
//!
//! A least-squares fit in ln E then sees Σ_b n_b [ln E(ω̄_b) − ln Ē_b]²,
//! which is Σ_i [ln E(ω_i) − ln E_i]² up to a constant (the scatter within
//! the bins) and to the model's curvature across a bin: ln E is linear
//! across 1/50 decade to (1/2) |d²ln E/d(ln ω)²| Var(ln ω) ≤ (1/2) · 1 ·
//! (ln 10/50)²/12 ≈ 9e-5 for any solid's modulus (|d²ln E/d(ln ω)²| ≤ 1,
//! reached only by a single Maxwell element). Each bin mean has variance
//! σ²/n_b, so the weighted rows have the points' noise and a rule that
//! profiles the noise (GML) works on them as on the points.
//!
//! The same bins, a tenth of a decade wide, are the curves a dense
//! isotherm's shift is found from (`super::horizontal::curves`).
//!
//! Below the threshold nothing is condensed, so every fit of a DMA file of
//! ordinary size (tens of isotherms of tens of frequencies) is the fit of
//! its points themselves.
//!
//! References: Bevington & Robinson, *Data Reduction and Error Analysis*,
//! 3rd ed., §4.1 (means of repeated measurements and their weights).

/// Bins per decade of reduced ω.
pub const BINS_PER_DECADE: f64 = 50.0;

/// Point sets larger than this are condensed: 2000 points is more than a
/// DMA of 40 isotherms × 50 frequencies has.
pub const CONDENSE_ABOVE_POINTS: usize = 2000;

/// The bins of a condensed point set, ascending in ω.
#[derive(Debug, Clone, PartialEq)]
pub struct Condensed {
    /// Geometric mean of each bin's reduced ω, rad/s.
    pub omega: Vec<f64>,
    /// Geometric mean of each bin's E′ (or of any positive quantity the
    /// caller bins), Pa.
    pub storage: Vec<f64>,
    /// Geometric mean of each bin's E″, Pa.
    pub loss: Vec<f64>,
    /// Points in each bin, the weight of its squared log residual.
    pub count: Vec<f64>,
}

/// The bins of (ω_i, E′_i, E″_i) (all > 0), or None when there are at most
/// [`CONDENSE_ABOVE_POINTS`] points.
pub fn condense(omega: &[f64], storage: &[f64], loss: &[f64]) -> Option<Condensed> {
    (omega.len() > CONDENSE_ABOVE_POINTS).then(|| bins(omega, storage, loss, BINS_PER_DECADE))
}

/// The bins of 1/`per_decade` decade of (ω_i, E′_i, E″_i), all > 0,
/// whatever their number.
pub(crate) fn bins(omega: &[f64], storage: &[f64], loss: &[f64], per_decade: f64) -> Condensed {
    let mut order: Vec<usize> = (0..omega.len()).collect();
    order.sort_by(|&a, &b| omega[a].total_cmp(&omega[b]));
    let bin_of = |w: f64| (w.log10() * per_decade).floor() as i64;
    let mut out = Condensed {
        omega: Vec::new(),
        storage: Vec::new(),
        loss: Vec::new(),
        count: Vec::new(),
    };
    let mut start = 0;
    while start < order.len() {
        let bin = bin_of(omega[order[start]]);
        let mut end = start;
        while end < order.len() && bin_of(omega[order[end]]) == bin {
            end += 1;
        }
        let members = &order[start..end];
        let n = members.len() as f64;
        let mean_ln = |values: &[f64]| members.iter().map(|&i| values[i].ln()).sum::<f64>() / n;
        out.omega.push(mean_ln(omega).exp());
        out.storage.push(mean_ln(storage).exp());
        out.loss.push(mean_ln(loss).exp());
        out.count.push(n);
        start = end;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Small sets are left alone; a large one gives one bin per occupied
    /// 1/50 decade, whose counts add up to the points and whose means are
    /// the geometric means of their members (checked against a slow
    /// per-bin scan).
    #[test]
    fn bins_hold_their_members_geometric_means() {
        let w: Vec<f64> = (0..100).map(|i| 10f64.powf(i as f64 / 37.0)).collect();
        assert!(condense(&w, &w, &w).is_none());
        let n = 6000;
        let omega: Vec<f64> = (0..n)
            .map(|i| 10f64.powf(-2.0 + 5.0 * ((i * 7919) % n) as f64 / n as f64))
            .collect();
        let storage: Vec<f64> = omega.iter().map(|w| 1e6 * (1.0 + w.sqrt())).collect();
        let loss: Vec<f64> = omega.iter().map(|w| 1e5 * (1.0 + w.cbrt())).collect();
        let c = condense(&omega, &storage, &loss).unwrap();
        assert_eq!(c.count.iter().sum::<f64>(), n as f64);
        assert_eq!(c.omega.len(), 250);
        for b in 0..c.omega.len() {
            let key = (c.omega[b].log10() * BINS_PER_DECADE).floor();
            let members: Vec<usize> = (0..n)
                .filter(|&i| (omega[i].log10() * BINS_PER_DECADE).floor() == key)
                .collect();
            assert_eq!(members.len() as f64, c.count[b]);
            let geo = |v: &[f64]| {
                (members.iter().map(|&i| v[i].ln()).sum::<f64>() / members.len() as f64).exp()
            };
            assert!((c.storage[b] / geo(&storage) - 1.0).abs() < 1e-12);
            assert!((c.loss[b] / geo(&loss) - 1.0).abs() < 1e-12);
        }
        assert!(c.omega.windows(2).all(|p| p[0] < p[1]));
    }
}
