//! Dense data condensed to bins of 1/20 decade of speed.
//!
//! A logger that samples one μ(v) sweep thousands of times adds rows, not
//! information about the shape of μ(v): a Prony spectrum with at most three
//! terms per decade cannot show a feature narrower than a third of a decade,
//! while the fit's cost grows with every row. Above [`CONDENSE_ABOVE_ROWS`]
//! rows, the rows of each temperature are grouped into bins of width
//! 1/[`BINS_PER_DECADE`] decade in v, and each bin becomes one point:
//!
//! - with measured σ_i: the weighted means, w_i = 1/σ_i²,
//!   ln v̄ = Σ w_i ln v_i / Σ w_i, μ̄ = Σ w_i μ_i / Σ w_i, σ̄ = (Σ w_i)^(−1/2);
//! - without σ: the plain means of ln v and μ, and σ̄ = s μ̄ /√n from the
//!   scatter s of μ within the bins, pooled over all bins: in each bin the
//!   relative deviations r_i = μ_i/μ̄ − 1 are fitted by a line in
//!   x_i = ln v_i − ln v̄ (μ(v) changes by up to a few percent across a
//!   1/20-decade bin, which a plain variance would count as noise), and
//!   s² = Σ_bins Σ_i (r_i − b x_i)² / Σ_bins (n − 2).
//!
//! The bin means are what a fit to the rows would see, with the noise the
//! rows carry; the λ rule then works on a data set of the size the 41-point
//! examples have, and with a noise level measured independently of any fit
//! (the discrepancy rule applies). The scatter assumes that rows scatter
//! independently; rows of one slow drift would make it too small, and the
//! fit's quality test then reports a χ² far above its degrees of freedom.
//!
//! A mean of μ over a bin in which μ(v) curves differs from μ at ln v̄ by
//! (1/2) μ'' Var(x) ≈ μ'' (Δ ln v)²/24 with Δ ln v = ln 10 / 20 ≈ 0.115:
//! below 0.1 % of μ for the curvature of any rubber's μ(v).
//!
//! References: Bevington & Robinson, *Data Reduction and Error Analysis*,
//! 3rd ed., §4.1 (weighted means) and §6.3 (scatter about a fitted line).

use serde::Serialize;

use crate::data::{MIN_RELATIVE_SIGMA, Measurements};
use crate::error::FitError;

/// Bins per decade of speed.
pub const BINS_PER_DECADE: f64 = 20.0;
/// Data with more rows than this are condensed (when that merges rows).
pub const CONDENSE_ABOVE_ROWS: usize = 200;
/// The fewest degrees of freedom of the pooled within-bin scatter for it to
/// stand as the noise; fewer, and the bins keep relative weights and the
/// noise is estimated from the fit's residuals as for sparse data.
const MIN_SCATTER_DOF: usize = 20;

/// How the data were condensed (fit.json `condensed`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CondensedRecord {
    /// Rows of the data file.
    pub rows: usize,
    /// Bins the fit saw.
    pub bins: usize,
    /// Bins per decade of speed.
    pub bins_per_decade: f64,
    /// Scatter of μ within the bins, relative to μ (no sigma column), or
    /// `None` when σ was measured or the bins hold too few repeats.
    pub scatter: Option<f64>,
    /// Degrees of freedom of that scatter.
    pub scatter_dof: usize,
}

/// The condensed data and how they came about.
#[derive(Debug, Clone)]
pub struct Condensed {
    pub data: Measurements,
    pub record: CondensedRecord,
}

impl Condensed {
    /// The sentence the user reads.
    pub fn note(&self) -> String {
        let r = &self.record;
        let noise = match r.scatter {
            Some(s) => format!(
                "; the scatter of μ within the bins, {:.2} % of μ ({} degrees of freedom), gives \
                 each bin mean its σ = s μ/√n (this assumes the rows scatter independently)",
                100.0 * s,
                r.scatter_dof
            ),
            None if self.data.sigma().is_some() => {
                "; each bin is the σ-weighted mean of its rows".into()
            }
            None => "; too few repeats within bins to measure their scatter, so the noise is \
                     estimated from the residuals"
                .into(),
        };
        format!(
            "{} rows condensed to {} bins of 1/{} decade of speed (per temperature): the fit's \
             cost grows with rows, its information about a smooth μ(v) does not{noise}; mu.csv \
             keeps every row",
            r.rows, r.bins, r.bins_per_decade
        )
    }
}

/// Condenses `data` when it has more than [`CONDENSE_ABOVE_ROWS`] rows and
/// binning merges some of them; `None` otherwise.
pub fn condense(data: &Measurements) -> Result<Option<Condensed>, FitError> {
    let n = data.len();
    if n <= CONDENSE_ABOVE_ROWS {
        return Ok(None);
    }
    let speeds = data.speeds();
    let temperature = data.temperature();
    let t_of = |i: usize| temperature.map_or(0.0, |t| t[i]);
    let bin_of = |i: usize| (speeds[i].log10() * BINS_PER_DECADE).floor() as i64;
    let mut order: Vec<usize> = (0..n).collect();
    order.sort_by(|&a, &b| {
        t_of(a)
            .total_cmp(&t_of(b))
            .then(bin_of(a).cmp(&bin_of(b)))
            .then(speeds[a].total_cmp(&speeds[b]))
    });
    let mut bins: Vec<Vec<usize>> = Vec::new();
    for &i in &order {
        match bins.last_mut() {
            Some(bin) if t_of(bin[0]) == t_of(i) && bin_of(bin[0]) == bin_of(i) => bin.push(i),
            _ => bins.push(vec![i]),
        }
    }
    if bins.len() == n {
        return Ok(None);
    }

    let friction = data.friction();
    let mut v = Vec::with_capacity(bins.len());
    let mut mu = Vec::with_capacity(bins.len());
    let mut t = Vec::with_capacity(bins.len());
    let mut sigma = Vec::with_capacity(bins.len());
    let (mut ss, mut dof) = (0.0, 0usize);
    for bin in &bins {
        let weights: Vec<f64> = match data.sigma() {
            Some(s) => bin.iter().map(|&i| 1.0 / (s[i] * s[i])).collect(),
            None => vec![1.0; bin.len()],
        };
        let total: f64 = weights.iter().sum();
        let mean = |f: &dyn Fn(usize) -> f64| {
            bin.iter()
                .zip(&weights)
                .map(|(&i, w)| w * f(i))
                .sum::<f64>()
                / total
        };
        let ln_v = mean(&|i| speeds[i].ln());
        let mu_bar = mean(&|i| friction[i]);
        v.push(ln_v.exp());
        mu.push(mu_bar);
        t.push(t_of(bin[0]));
        sigma.push(total.sqrt().recip());
        if data.sigma().is_none() {
            let (bin_ss, bin_dof) = scatter_about_line(bin, speeds, friction, ln_v, mu_bar);
            ss += bin_ss;
            dof += bin_dof;
        }
    }
    let scatter =
        (data.sigma().is_none() && dof >= MIN_SCATTER_DOF).then(|| (ss / dof as f64).sqrt());
    if let Some(s) = scatter
        && s < MIN_RELATIVE_SIGMA
    {
        // Copies of the same rows (a list tiled, a file pasted twice) have
        // a scatter of rounding errors: σ from it would be a number the
        // user never gave, and one no point can claim.
        return Err(FitError::InsufficientData(format!(
            "the {n} rows repeat {} speeds (bins of 1/{BINS_PER_DECADE} decade) with μ identical \
             to {s:.1e} of μ: the noise cannot be estimated from the scatter of repeated rows \
             when they are copies; give a sigma column (sigma= in Python) or remove the copies",
            bins.len()
        )));
    }
    let sigma = match (data.sigma(), scatter) {
        (Some(_), _) => Some(sigma),
        (None, Some(s)) => Some(
            bins.iter()
                .zip(&mu)
                .map(|(bin, m)| s * m / (bin.len() as f64).sqrt())
                .collect(),
        ),
        (None, None) => None,
    };
    let record = CondensedRecord {
        rows: n,
        bins: bins.len(),
        bins_per_decade: BINS_PER_DECADE,
        scatter,
        scatter_dof: if scatter.is_some() { dof } else { 0 },
    };
    let data = Measurements::new(v, mu, sigma, temperature.map(|_| t))?;
    Ok(Some(Condensed { data, record }))
}

/// Σ (r_i − b x_i)² and its degrees of freedom for one bin: the relative
/// deviations about the bin mean, less their linear trend in ln v (a bin
/// whose rows share one speed has no trend to remove).
fn scatter_about_line(
    bin: &[usize],
    speeds: &[f64],
    friction: &[f64],
    ln_v: f64,
    mu_bar: f64,
) -> (f64, usize) {
    let n = bin.len();
    let x: Vec<f64> = bin.iter().map(|&i| speeds[i].ln() - ln_v).collect();
    let r: Vec<f64> = bin.iter().map(|&i| friction[i] / mu_bar - 1.0).collect();
    let sxx: f64 = x.iter().map(|x| x * x).sum();
    // A spread below 1e-9 in ln v is rounding, not a trend.
    if sxx > 1e-18 * n as f64 && n >= 3 {
        let b = x.iter().zip(&r).map(|(x, r)| x * r).sum::<f64>() / sxx;
        let ss = x.iter().zip(&r).map(|(x, r)| (r - b * x).powi(2)).sum();
        (ss, n - 2)
    } else if sxx <= 1e-18 * n as f64 && n >= 2 {
        (r.iter().map(|r| r * r).sum(), n - 1)
    } else {
        (0.0, 0)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use rand::SeedableRng;
    use rand_chacha::ChaCha8Rng;
    use rand_distr::{Distribution, Normal};

    /// A straight power law μ = 0.1 (v/1 mm/s)^0.3 sampled 5000 times over
    /// 4 decades with 3 % noise: 80 bins, the scatter within 5 % of 3 %
    /// (the trend across each bin removed), each bin mean within 4 σ̄ of the
    /// power law at its speed.
    #[test]
    fn scatter_and_means_of_a_power_law() {
        let mut rng = ChaCha8Rng::seed_from_u64(7);
        let normal = Normal::new(0.0, 1.0).unwrap();
        let n = 5000;
        let law = |v: f64| 0.1 * (v / 1e-3).powf(0.3);
        let speeds: Vec<f64> = (0..n)
            .map(|i| 1e-5 * 10f64.powf(4.0 * (i as f64 + 0.5) / n as f64))
            .collect();
        let mu = speeds
            .iter()
            .map(|&v| law(v) * (1.0 + 0.03 * normal.sample(&mut rng)))
            .collect();
        let data = Measurements::new(speeds, mu, None, None).unwrap();
        let c = condense(&data).unwrap().unwrap();
        assert_eq!(c.record.bins, 80);
        let s = c.record.scatter.unwrap();
        assert!((s / 0.03 - 1.0).abs() < 0.05, "scatter {s}");
        let sigma = c.data.sigma().unwrap();
        let z: Vec<f64> = c
            .data
            .speeds()
            .iter()
            .zip(c.data.friction())
            .zip(sigma)
            .map(|((v, m), s)| (m - law(*v)) / s)
            .collect();
        let chi2: f64 = z.iter().map(|z| z * z).sum();
        eprintln!("χ² {chi2:.1} over 80 bins; {z:.2?}");
        // χ² of 80 degrees of freedom: 80 ± 16.
        assert!((50.0..120.0).contains(&chi2), "χ² {chi2}");
        assert!(c.note().contains("5000 rows condensed to 80 bins"));
    }

    /// Measured σ: the bin mean is the σ-weighted mean and σ̄ = (Σ 1/σ²)^(−1/2).
    #[test]
    fn measured_sigma_gives_weighted_means() {
        let n = 400;
        let speeds: Vec<f64> = (0..n).map(|i| 1e-3 * (1.0 + 1e-4 * i as f64)).collect();
        let mu: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 0.1 } else { 0.2 }).collect();
        let sigma: Vec<f64> = (0..n)
            .map(|i| if i % 2 == 0 { 0.01 } else { 0.02 })
            .collect();
        let data = Measurements::new(speeds, mu, Some(sigma), None);
        // 400 rows within one bin are fewer than four distinct speeds after
        // condensing: refused.
        let err = condense(&data.unwrap()).unwrap_err().to_string();
        assert!(err.contains("1 distinct speed"), "{err}");

        let speeds: Vec<f64> = (0..n)
            .map(|i| 1e-3 * 10f64.powf((i / 100) as f64))
            .collect();
        let mu: Vec<f64> = (0..n).map(|i| if i % 2 == 0 { 0.1 } else { 0.2 }).collect();
        let sigma: Vec<f64> = (0..n)
            .map(|i| if i % 2 == 0 { 0.01 } else { 0.02 })
            .collect();
        let c = condense(&Measurements::new(speeds, mu, Some(sigma), None).unwrap())
            .unwrap()
            .unwrap();
        assert_eq!(c.record.bins, 4);
        // Weights 4 : 1 → μ̄ = (4·0.1 + 0.2)/5 = 0.12; Σw = 50·(1e4 + 2.5e3).
        for (m, s) in c.data.friction().iter().zip(c.data.sigma().unwrap()) {
            assert!((m - 0.12).abs() < 1e-12, "{m}");
            assert!(
                (s - (50.0 * 12_500.0f64).sqrt().recip()).abs() < 1e-15,
                "{s}"
            );
        }
        assert_eq!(c.record.scatter, None);
    }

    /// 41 rows, or 300 rows at 300 distinct bins, are left as they are.
    #[test]
    fn sparse_data_are_not_condensed() {
        let speeds: Vec<f64> = (0..300)
            .map(|i| 1e-14 * 10f64.powf(i as f64 / 19.0))
            .collect();
        let data = Measurements::new(speeds, vec![0.1; 300], None, None).unwrap();
        assert!(condense(&data).unwrap().is_none());
    }
}
