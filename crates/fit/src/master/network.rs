//! All horizontal shifts at once from the pairs that determine them.
//!
//! The pairs (i, j) with determined relative shifts s_ij ± σ_ij
//! ([`super::pairwise`]) are the edges of a graph on the isotherms. The
//! shifts x_i = log10 a_{T_i} (up to a constant) of one connected part
//! minimise
//!
//!   χ² = Σ_(i,j) (x_j − x_i − s_ij)² / σ_ij²,
//!
//! a weighted least-squares problem on a graph (the normal matrix is the
//! weighted graph Laplacian) fixed by x_g = 0 at the part's coldest
//! isotherm; the covariance of x is the inverse of the reduced normal
//! matrix. On a chain of neighbours this is the chain of pairwise shifts
//! with variances added along it; where a bridging pair closes a cycle the
//! redundancy is used, and χ²/dof > 1 scales the covariance (the Birge
//! ratio), so that inconsistent pairs widen the errors instead of hiding.
//!
//! Pairs: every neighbour pair, and the next-neighbour pair (i, i+2)
//! wherever a neighbour pair around it is undetermined, to bridge an
//! isotherm that overlaps poorly. Not every overlapping pair: pairs that
//! reuse the same points would count the same noise twice and make the
//! errors too small.
//!
//! The reference part is the connected part with the most information,
//! Σ 1/σ_ij² over its pairs (the one nearest T_ref on a tie), not the one
//! with the most isotherms: eight isotherms joined by pairs of σ = 0.02
//! decade say more than nine joined by pairs of σ = 0.3. The shifts of
//! every other isotherm relative to it are not determined by the data.
//!
//! # References
//! - P.R. Bevington, D.K. Robinson, *Data Reduction and Error Analysis for
//!   the Physical Sciences*, 3rd ed., McGraw-Hill 2003, ch. 7–8 (weighted
//!   least squares, errors of fitted parameters).
//! - R.T. Birge, "The calculation of errors by the method of least
//!   squares", Phys. Rev. 40 (1932) 207 (scaling errors by χ²/dof).

use nalgebra::{DMatrix, DVector};

use super::pairwise::{PairShift, PairVerdict};

/// The determined shifts and their covariance.
#[derive(Debug, Clone)]
pub(crate) struct Network {
    /// Whether each isotherm (ascending T) belongs to the determined part.
    pub determined: Vec<bool>,
    /// log10 a_T relative to the determined part's coldest isotherm (0
    /// outside it).
    pub log_shift: Vec<f64>,
    /// Covariance of `log_shift` (zero rows and columns outside the
    /// determined part and at its gauge isotherm).
    pub covariance: DMatrix<f64>,
    /// The determined pairs used, for the laws.
    pub pairs: Vec<PairShift>,
}

/// Solves the most informative part of the graph of `pairs` on `count`
/// isotherms at `temps`, the part nearest `t_ref` winning a tie. None if
/// no pair is determined.
pub(crate) fn solve(pairs: &[PairShift], temps: &[f64], t_ref: f64) -> Option<Network> {
    let count = temps.len();
    let used: Vec<PairShift> = pairs
        .iter()
        .filter(|p| p.verdict == PairVerdict::Determined && p.sigma.is_finite() && p.sigma > 0.0)
        .copied()
        .collect();
    if used.is_empty() {
        return None;
    }
    // Connected parts by union–find.
    let mut parent: Vec<usize> = (0..count).collect();
    fn root(parent: &mut [usize], mut i: usize) -> usize {
        while parent[i] != i {
            parent[i] = parent[parent[i]];
            i = parent[i];
        }
        i
    }
    for p in &used {
        let (a, b) = (root(&mut parent, p.lower), root(&mut parent, p.upper));
        if a != b {
            parent[a.max(b)] = a.min(b);
        }
    }
    let roots: Vec<usize> = (0..count).map(|i| root(&mut parent, i)).collect();
    let information = |r: usize| {
        used.iter()
            .filter(|p| roots[p.lower] == r)
            .map(|p| 1.0 / (p.sigma * p.sigma))
            .sum::<f64>()
    };
    let distance = |r: usize| {
        (0..count)
            .filter(|&i| roots[i] == r)
            .map(|i| (temps[i] - t_ref).abs())
            .fold(f64::INFINITY, f64::min)
    };
    let main = used.iter().map(|p| roots[p.lower]).max_by(|&a, &b| {
        information(a)
            .total_cmp(&information(b))
            .then(distance(b).total_cmp(&distance(a)))
    })?;
    let members: Vec<usize> = (0..count).filter(|&i| roots[i] == main).collect();
    let pairs: Vec<PairShift> = used
        .into_iter()
        .filter(|p| roots[p.lower] == main)
        .collect();
    // Unknowns: every member but the gauge (the first).
    let m = members.len() - 1;
    let column = |i: usize| {
        members
            .iter()
            .position(|&q| q == i)
            .and_then(|k| k.checked_sub(1))
    };
    let mut normal = DMatrix::<f64>::zeros(m, m);
    let mut rhs = DVector::<f64>::zeros(m);
    for p in &pairs {
        let w = 1.0 / (p.sigma * p.sigma);
        let (a, b) = (column(p.lower), column(p.upper));
        // Residual x_b − x_a − s.
        if let Some(b) = b {
            normal[(b, b)] += w;
            rhs[b] += w * p.shift;
        }
        if let Some(a) = a {
            normal[(a, a)] += w;
            rhs[a] -= w * p.shift;
        }
        if let (Some(a), Some(b)) = (a, b) {
            normal[(a, b)] -= w;
            normal[(b, a)] -= w;
        }
    }
    let inverse = normal.clone().cholesky()?.inverse();
    let solution = &inverse * &rhs;
    let mut log_shift = vec![0.0; count];
    for (k, &i) in members.iter().enumerate().skip(1) {
        log_shift[i] = solution[k - 1];
    }
    let chi2: f64 = pairs
        .iter()
        .map(|p| ((log_shift[p.upper] - log_shift[p.lower] - p.shift) / p.sigma).powi(2))
        .sum();
    let dof = pairs.len() as f64 - m as f64;
    let birge = if dof >= 1.0 {
        (chi2 / dof).max(1.0)
    } else {
        1.0
    };
    let mut covariance = DMatrix::<f64>::zeros(count, count);
    for (k, &i) in members.iter().enumerate().skip(1) {
        for (l, &j) in members.iter().enumerate().skip(1) {
            covariance[(i, j)] = birge * inverse[(k - 1, l - 1)];
        }
    }
    let mut determined = vec![false; count];
    for &i in &members {
        determined[i] = true;
    }
    Some(Network {
        determined,
        log_shift,
        covariance,
        pairs,
    })
}

impl Network {
    /// Variance of the linear combination Σ c_i x_i.
    pub(crate) fn variance(&self, c: &[f64]) -> f64 {
        let v = DVector::from_column_slice(c);
        (v.transpose() * &self.covariance * &v)[(0, 0)].max(0.0)
    }
}
