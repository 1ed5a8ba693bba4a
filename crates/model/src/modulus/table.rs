//! Tabulated master curve: measured storage and loss moduli E′(ω_i), E″(ω_i)
//! on a frequency grid, interpolated in log–log.
//!
//! # Inside the table (ω_min ≤ ω ≤ ω_max)
//!
//! With u = ln ω, ln E′(u) and ln E″(u) are each a piecewise cubic Hermite
//! interpolant: on [u_k, u_{k+1}] of width h, t = (u − u_k)/h, r = 1 − t,
//!
//! ln E(u) = ln E_k + Δ_k t²(3 − 2t) + h t r (m_k r − m_{k+1} t),
//! Δ_k = ln E_{k+1} − ln E_k,
//!
//! fixed by the values at both knots and the slopes m_k, m_{k+1} there, so the
//! curve goes through every table point and is C¹. Log–log because moduli span
//! decades and their terminal and transition behaviour is close to power laws,
//! which become straight lines. The value is evaluated from the nearer knot,
//! as E_k·exp(…) or E_{k+1}·exp(…) with an exponent that vanishes there, so
//! that table points are returned exactly and approached to within rounding
//! of exp (a power series from the left knot alone missed E_{k+1} by up to
//! 20 ulp just before ω_{k+1}: an overshoot of monotone data). The
//! logarithmic slope is the exact derivative of the interpolant:
//!
//! dE*/d ln ω = E′ · d ln E′/du + i E″ · d ln E″/du.
//!
//! Slopes. Each slope starts from the three-point (parabola) estimate
//! p_k = (h_k s_{k−1} + h_{k−1} s_k)/(h_{k−1} + h_k), s_k the secant of interval
//! k and h_k its width (one-sided three-point estimate at the ends, the secant
//! for a two-row table), which makes the interpolant third-order accurate on
//! smooth data. It is then limited so that the curve keeps the shape of the
//! data (after Fritsch & Carlson 1980, Hyman 1983, Steffen 1990):
//! - an interval whose neighbours' secants do not have the opposite sign
//!   (data monotone there) gets end slopes of its secant's sign and at most
//!   three times its secant, which by Fritsch & Carlson's theorem makes the
//!   cubic monotone: monotone data stay monotone and never overshoot;
//! - a flat interval (equal values) stays exactly flat, unless it lies
//!   between a rise and a fall: then it holds an extremum of the data (a
//!   peak sampled symmetrically about its top) and is treated as below;
//! - next to a strict local extremum of the data (a neighbour's secant has
//!   the opposite sign) the three-point slope is kept, so the interpolant
//!   has one extremum there, generally between the table points, where the
//!   real curve has it. If both end slopes of such an interval have its
//!   secant's sign, they are capped at three times the secant as above, so
//!   no spurious wiggle appears.
//!
//! Why not plain PCHIP or Steffen: both set the slope to zero wherever the
//! secants change sign, i.e. they flatten every extremum onto the nearest
//! table point. For the loss peak of a standard linear solid sampled at 10
//! points per decade that costs up to 0.66 % in E″ (with Steffen), against
//! 0.016 % with the rule above; the friction peak sits on the loss peak.
//!
//! # Outside the table
//!
//! The terminal behaviour of a viscoelastic solid:
//! - ω < ω_min: E′ = E′(ω_min), E″ = E″(ω_min) ω/ω_min (rubbery plateau,
//!   loss ∝ ω);
//! - ω > ω_max: E′ = E′(ω_max), E″ = E″(ω_max) ω_max/ω (glassy plateau,
//!   loss ∝ 1/ω).
//!
//! Hence E(0) = E′(ω_min), lim E″/ω = E″(ω_min)/ω_min and the structure range
//! is [ω_min, ω_max]. E* is continuous at the table ends, but its log slope
//! jumps there from the interpolant's to the terminal one (0 for E′, ±1 for
//! ln E″); at ω_min and ω_max themselves the right-hand slope is returned.
//! A table that stops before the moduli reach their plateaus is extrapolated
//! as if they did: that is an assumption about the material, not data.
//!
//! # Interpolation error
//!
//! Between its rows a table is this interpolant, not the material. For rows
//! sampled from a smooth master curve at spacing H in ln ω the three-point
//! slopes err by O(H²), which costs O(H³) in ln E between the rows; with
//! exact slopes the cubic would err by only O(H⁴). So the interpolant's own
//! error is estimated from the rows alone by the same cubic with five-point
//! slopes (error O(H⁴), then the same limits):
//! [`TabulatedModulus::interpolation_comparison`], and
//! [`TabulatedModulus::interpolation_error_estimate`] the largest
//! |ln E − ln E_c| between rows. Measured on a standard linear solid and a
//! 3-term Prony series (tests/table_friction.rs), true relative error of
//! E′ and E″ (estimate):
//!
//! | rows a decade | E′, E″ | μ (sphere, cylinder) |
//! |---|---|---|
//! | 5 | 1.8e-3 … 3.0e-3 (1.2e-3 … 2.2e-3) | 5.6e-6 … 2.7e-4 |
//! | 10 | 1.6e-4 … 3.1e-4 (1.5e-4 … 2.9e-4) | 3.4e-7 … 1.7e-5 |
//! | 20 | 1.9e-5 … 3.7e-5 (1.9e-5 … 3.6e-5) | 2.0e-8 … 1.1e-6 |
//!
//! μ is more accurate than the modulus, and converges one order faster
//! (like H⁴, a factor 16 per doubling of the rows): the O(H³) part of the
//! error, h t r (δm_k r − δm_{k+1} t) for slope errors δm, changes sign
//! inside each interval and largely cancels in the integral over
//! frequency. The friction integral carries the estimate through to μ
//! (`Scene::table_interpolation_error`), within a factor 2 of the true
//! error of μ in every case measured (typically 10–40 % low). So a DMA
//! table of 10 rows a decade gives μ to about 1e-5, one of 20 rows to about
//! 1e-6, whatever tolerance the quadrature is asked for; noise in the rows
//! is not in these numbers and usually dominates them.
//!
//! # In the friction integral
//!
//! ln E is only C¹ at the rows: its second derivative jumps. The product
//! integration of analytic moduli interpolates the friction integrand by
//! polynomials across many rows and loses its order there (1e-3 off at
//! tolerance 1e-6 with 10 rows a decade). A table declares its rows as
//! knots ([`ViscoelasticModulus::knots`]) and μ is then integrated piece by
//! piece between them (`friction/knots.rs`), to the requested tolerance of
//! μ for this interpolant.
//!
//! # References
//! - F.N. Fritsch, R.E. Carlson, "Monotone piecewise cubic interpolation",
//!   SIAM J. Numer. Anal. 17 (1980) 238–246.
//! - J.M. Hyman, "Accurate monotonicity preserving cubic interpolation",
//!   SIAM J. Sci. Stat. Comput. 4 (1983) 645–654.
//! - M. Steffen, "A simple method for monotonic interpolation in one
//!   dimension", Astron. Astrophys. 239 (1990) 443–450.
//! - J.D. Ferry, *Viscoelastic Properties of Polymers*, 3rd ed., Wiley 1980
//!   (terminal and glassy behaviour of E′, E″).

use num_complex::Complex64;

use super::ViscoelasticModulus;
use crate::error::ModelError;

/// Name under which table errors are reported.
const TABLE: &str = "modulus table";

/// Limit on an end slope relative to its interval's secant: the square
/// [0, 3]² of Fritsch & Carlson's monotonicity region.
const SLOPE_CAP: f64 = 3.0;

/// The Hermite cubic of ln E on one interval [u_k, u_{k+1}] of width h, in
/// the fraction t = (u − u_k)/h and its complement r = 1 − t:
///
/// ln E = ln E_k + Δ t²(3 − 2t) + h t r (m_k r − m_{k+1} t),  Δ = ln E_{k+1} − ln E_k,
///
/// which is symmetric under t ↔ r, k ↔ k+1, so it is evaluated from the
/// nearer knot (see [`Cubic::eval`]).
#[derive(Debug, Clone, PartialEq)]
struct Cubic {
    /// E_k and E_{k+1}, the table values at the two knots.
    left: f64,
    right: f64,
    /// Δ = ln E_{k+1} − ln E_k.
    rise: f64,
    /// Δ/h, the secant.
    secant: f64,
    /// h m_k and h m_{k+1}: the end slopes scaled to the interval.
    left_slope_h: f64,
    right_slope_h: f64,
    /// m_k and m_{k+1}, d ln E/d ln ω at the knots.
    left_slope: f64,
    right_slope: f64,
}

impl Cubic {
    /// Hermite cubic from the interval width `h`, the table values at both
    /// ends (`e0`, `e1`) and the end slopes of ln E (`m0`, `m1`).
    fn hermite(h: f64, (e0, e1): (f64, f64), (y0, y1): (f64, f64), m0: f64, m1: f64) -> Self {
        let rise = y1 - y0;
        Cubic {
            left: e0,
            right: e1,
            rise,
            secant: rise / h,
            left_slope_h: h * m0,
            right_slope_h: h * m1,
            left_slope: m0,
            right_slope: m1,
        }
    }

    /// (E, d ln E/d ln ω) at the fraction `t` of the interval, `r` = 1 − t,
    /// `from_right` when the right knot is the nearer one.
    ///
    /// Why from the nearer knot, as E_k·exp(…) or E_{k+1}·exp(…): the
    /// exponent then vanishes at that knot and is small next to it, so both
    /// table values are returned exactly and the curve approaches them to a
    /// few ulp. Anchored at the left knot only (a power series in u − u_k),
    /// the exponent at the right end is a sum of terms several times Δ that
    /// should cancel to Δ; its rounding put E up to 20 ulp beyond E_{k+1},
    /// i.e. an overshoot of monotone data and a jump at the knot.
    #[inline]
    fn eval(&self, t: f64, r: f64, from_right: bool) -> (f64, f64) {
        let (m0h, m1h) = (self.left_slope_h, self.right_slope_h);
        let e = if from_right {
            // ln E − ln E_{k+1} = −Δ r²(3 − 2r) + h t r (m_k r − m_{k+1} t).
            let log_ratio = -self.rise * r * r * (3.0 - 2.0 * r) + t * r * (m0h * r - m1h * t);
            self.right * log_ratio.exp()
        } else {
            let log_ratio = self.rise * t * t * (3.0 - 2.0 * t) + t * r * (m0h * r - m1h * t);
            self.left * log_ratio.exp()
        };
        // d ln E/du = 6 t r Δ/h + m_k r (r − 2t) − m_{k+1} t (2r − t).
        let log_slope = 6.0 * t * r * self.secant + self.left_slope * r * (r - 2.0 * t)
            - self.right_slope * t * (2.0 * r - t);
        (e, log_slope)
    }
}

/// A measured master curve E′(ω), E″(ω), interpolated in log–log with a
/// shape-preserving C¹ cubic and extrapolated with the terminal behaviour of a
/// solid (see the module documentation). Frequencies in rad/s, moduli in Pa.
#[derive(Debug, Clone, PartialEq)]
pub struct TabulatedModulus {
    omega: Vec<f64>,
    storage: Vec<f64>,
    loss: Vec<f64>,
    /// ln ω_k, the knots searched at every evaluation.
    knots: Vec<f64>,
    /// Per interval k (n − 1 of them): the cubics for ln E′ and ln E″.
    storage_cubics: Vec<Cubic>,
    loss_cubics: Vec<Cubic>,
    /// How the knot slopes were first estimated, before the limits.
    slopes: SlopeRule,
}

/// The first estimate of the knot slopes, before the shape-preserving
/// limits: the derivative at u_k of the polynomial through the nearest
/// rows.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum SlopeRule {
    /// Three rows (a parabola): the interpolant's own rule, third order.
    ThreePoint,
    /// Five rows (a quartic), fourth order: the comparison interpolant of
    /// [`TabulatedModulus::interpolation_comparison`].
    FivePoint,
}

impl TabulatedModulus {
    /// Builds a validated table from angular frequencies (rad/s, strictly
    /// increasing), storage and loss moduli (Pa, positive).
    ///
    /// At least two rows are needed, all three columns of equal length and
    /// every entry finite; errors name the offending row (counted from 0).
    pub fn new(omega: Vec<f64>, storage: Vec<f64>, loss: Vec<f64>) -> Result<Self, ModelError> {
        Self::with_slopes(omega, storage, loss, SlopeRule::ThreePoint)
    }

    fn with_slopes(
        omega: Vec<f64>,
        storage: Vec<f64>,
        loss: Vec<f64>,
        slopes: SlopeRule,
    ) -> Result<Self, ModelError> {
        let n = omega.len();
        if n != storage.len() || n != loss.len() {
            return Err(ModelError::table(
                TABLE,
                format!(
                    "omega has {n} rows, E_storage {} and E_loss {}: the columns must have the same length",
                    storage.len(),
                    loss.len()
                ),
            ));
        }
        if n == 0 {
            return Err(ModelError::table(TABLE, "the table is empty"));
        }
        if n == 1 {
            return Err(ModelError::table(
                TABLE,
                "the table has only one row; at least two are needed to interpolate",
            ));
        }
        let knots: Vec<f64> = omega.iter().map(|w| w.ln()).collect();
        for i in 0..n {
            check_row_value(i, "omega", omega[i], "rad/s")?;
            check_row_value(i, "E_storage", storage[i], "Pa")?;
            check_row_value(i, "E_loss", loss[i], "Pa")?;
            if i > 0 {
                let (prev, w) = (omega[i - 1], omega[i]);
                if w <= prev {
                    return Err(ModelError::table(
                        TABLE,
                        format!(
                            "row {i}: omega = {w} rad/s is not greater than row {}'s omega = {prev} rad/s; \
                             frequencies must be strictly increasing",
                            i - 1
                        ),
                    ));
                }
                // Adjacent binary64 frequencies can share a logarithm; the
                // interpolant would then divide by a zero interval width.
                if knots[i] <= knots[i - 1] {
                    return Err(ModelError::table(
                        TABLE,
                        format!(
                            "row {i}: omega = {w} rad/s is too close to row {}'s omega = {prev} rad/s \
                             to be told apart on a logarithmic scale",
                            i - 1
                        ),
                    ));
                }
            }
        }
        let storage_cubics = log_log_cubics(&knots, &storage, slopes);
        let loss_cubics = log_log_cubics(&knots, &loss, slopes);
        Ok(TabulatedModulus {
            omega,
            storage,
            loss,
            knots,
            storage_cubics,
            loss_cubics,
            slopes,
        })
    }

    /// A table of `modulus` sampled at the angular frequencies `omega`
    /// (rad/s, increasing): what a DMA master curve of that material would
    /// hold, for studies of the interpolation error.
    pub fn sampled<M: ViscoelasticModulus + ?Sized>(
        modulus: &M,
        omega: &[f64],
    ) -> Result<Self, ModelError> {
        let e: Vec<Complex64> = omega.iter().map(|&w| modulus.modulus(w)).collect();
        Self::new(
            omega.to_vec(),
            e.iter().map(|z| z.re).collect(),
            e.iter().map(|z| z.im).collect(),
        )
    }

    /// The same rows interpolated with knot slopes of one order higher
    /// (five-row instead of three-row estimates, then the same
    /// shape-preserving limits). The error of this interpolant is dominated
    /// by its slope error, O(H²) per slope for knot spacing H, which costs
    /// O(H³) between the rows; the comparison's slopes err by O(H⁴). So the
    /// difference between the two is the leading part of this interpolant's
    /// own error, computable from the data alone (see the module
    /// documentation, "Interpolation error").
    pub fn interpolation_comparison(&self) -> TabulatedModulus {
        Self::with_slopes(
            self.omega.clone(),
            self.storage.clone(),
            self.loss.clone(),
            SlopeRule::FivePoint,
        )
        .expect("the rows were checked when the table was built")
    }

    /// The estimated relative interpolation error of E′ and of E″ between
    /// the rows: the largest |ln E − ln E_c| over seven points inside every
    /// interval, E_c from [`Self::interpolation_comparison`]. Zero for a
    /// table of fewer than four rows (both rules then coincide). Outside the
    /// table the terminal behaviour is an assumption, not interpolation, and
    /// is not included.
    pub fn interpolation_error_estimate(&self) -> (f64, f64) {
        let comparison = self.interpolation_comparison();
        let mut worst = (0.0f64, 0.0f64);
        for w in self.knots.windows(2) {
            for j in 1..8 {
                let omega = (w[0] + (w[1] - w[0]) * j as f64 / 8.0).exp();
                let (e, c) = (self.modulus(omega), comparison.modulus(omega));
                worst.0 = worst.0.max((e.re / c.re).ln().abs());
                worst.1 = worst.1.max((e.im / c.im).ln().abs());
            }
        }
        worst
    }

    /// The table's angular frequencies ω_i, rad/s.
    pub fn omega(&self) -> &[f64] {
        &self.omega
    }

    /// The table's storage moduli E′(ω_i), Pa.
    pub fn storage(&self) -> &[f64] {
        &self.storage
    }

    /// The table's loss moduli E″(ω_i), Pa.
    pub fn loss(&self) -> &[f64] {
        &self.loss
    }

    /// E*(ω) and dE*/d ln ω (both Pa) for ω ≥ 0.
    #[inline]
    fn evaluate(&self, omega: f64) -> (Complex64, Complex64) {
        let last = self.omega.len() - 1;
        if omega < self.omega[0] {
            let e_loss = self.loss[0] * (omega / self.omega[0]);
            return (
                Complex64::new(self.storage[0], e_loss),
                Complex64::new(0.0, e_loss),
            );
        }
        // ω_max itself goes here too, so that both parts come from one
        // formula there (the last cubic would give the same values).
        if omega >= self.omega[last] {
            let e_loss = self.loss[last] * (self.omega[last] / omega);
            return (
                Complex64::new(self.storage[last], e_loss),
                Complex64::new(0.0, -e_loss),
            );
        }
        let u = omega.ln();
        // Clamped because ln need not be monotone to the last bit: a u that
        // rounds just below its knot is evaluated at the end of the interval
        // before, which is the same curve.
        let k = self
            .knots
            .partition_point(|&knot| knot <= u)
            .saturating_sub(1)
            .min(last - 1);
        // Both distances are measured from their own knot, so that the one
        // that decides the side, and is used there, is accurate to an ulp
        // of itself rather than of the interval width.
        let (from_left, from_right) = (u - self.knots[k], self.knots[k + 1] - u);
        let h = self.knots[k + 1] - self.knots[k];
        let right = from_right < from_left;
        let (t, r) = if right {
            let r = from_right / h;
            (1.0 - r, r)
        } else {
            let t = from_left / h;
            (t, 1.0 - t)
        };
        let (e_storage, slope_storage) = self.storage_cubics[k].eval(t, r, right);
        let (e_loss, slope_loss) = self.loss_cubics[k].eval(t, r, right);
        (
            Complex64::new(e_storage, e_loss),
            Complex64::new(e_storage * slope_storage, e_loss * slope_loss),
        )
    }
}

/// Checks one entry of a row: finite and greater than zero.
fn check_row_value(row: usize, column: &str, value: f64, unit: &str) -> Result<(), ModelError> {
    if !value.is_finite() {
        return Err(ModelError::table(
            TABLE,
            format!("row {row}: {column} = {value} is not a finite number"),
        ));
    }
    if value <= 0.0 {
        return Err(ModelError::table(
            TABLE,
            format!("row {row}: {column} = {value} {unit} must be greater than zero"),
        ));
    }
    Ok(())
}

/// The Hermite cubics of ln `values` against the knots u = ln ω (n ≥ 2,
/// strictly increasing), one per interval.
fn log_log_cubics(knots: &[f64], values: &[f64], rule: SlopeRule) -> Vec<Cubic> {
    let y: Vec<f64> = values.iter().map(|v| v.ln()).collect();
    let slopes = shape_preserving_slopes(knots, &y, rule);
    (0..knots.len() - 1)
        .map(|k| {
            Cubic::hermite(
                knots[k + 1] - knots[k],
                (values[k], values[k + 1]),
                (y[k], y[k + 1]),
                slopes[k],
                slopes[k + 1],
            )
        })
        .collect()
}

/// Knot slopes of a C¹ Hermite interpolant of (x, y) that keeps monotone
/// stretches monotone, flat intervals flat and puts one extremum next to
/// each strict extremum of the data (rules in the module documentation).
fn shape_preserving_slopes(x: &[f64], y: &[f64], rule: SlopeRule) -> Vec<f64> {
    let n = x.len();
    let h: Vec<f64> = x.windows(2).map(|w| w[1] - w[0]).collect();
    let secant: Vec<f64> = (0..n - 1).map(|k| (y[k + 1] - y[k]) / h[k]).collect();
    if n == 2 {
        return vec![secant[0]; 2];
    }
    // A flat interval between a rise and a fall (or a fall and a rise) holds
    // an extremum of the data, like a peak sampled symmetrically about its
    // top; a flat interval anywhere else is a plateau and stays flat.
    let flat_extremum: Vec<bool> = (0..n - 1)
        .map(|k| secant[k] == 0.0 && k > 0 && k < n - 2 && secant[k - 1] * secant[k + 1] < 0.0)
        .collect();
    // An interval is monotone unless a neighbouring secant has the opposite
    // sign, i.e. unless one of its ends is a strict extremum of the data.
    let monotone: Vec<bool> = (0..n - 1)
        .map(|k| {
            !flat_extremum[k]
                && (k == 0 || secant[k - 1] * secant[k] >= 0.0)
                && (k == n - 2 || secant[k] * secant[k + 1] >= 0.0)
        })
        .collect();

    let mut m: Vec<f64> = (0..n)
        .map(|i| {
            if rule == SlopeRule::FivePoint && n >= 4 {
                polynomial_slope(x, y, i, 5)
            } else if i == 0 {
                one_sided_slope(h[0], h[1], secant[0], secant[1])
            } else if i == n - 1 {
                one_sided_slope(h[n - 2], h[n - 3], secant[n - 2], secant[n - 3])
            } else {
                (h[i] * secant[i - 1] + h[i - 1] * secant[i]) / (h[i - 1] + h[i])
            }
        })
        .collect();

    for (i, mi) in m.iter_mut().enumerate() {
        for k in [i.wrapping_sub(1), i] {
            if k >= n - 1 {
                continue;
            }
            let s = secant[k];
            if s == 0.0 && !flat_extremum[k] {
                *mi = 0.0;
            } else if monotone[k] {
                if *mi * s < 0.0 {
                    *mi = 0.0;
                } else if mi.abs() > SLOPE_CAP * s.abs() {
                    *mi = SLOPE_CAP * s;
                }
            }
        }
    }

    // Intervals next to an extremum whose two end slopes both follow the
    // secant must not wiggle either. Only magnitudes shrink here, so the
    // conditions already met by the neighbouring intervals still hold.
    for k in 0..n - 1 {
        let s = secant[k];
        if !monotone[k] && s != 0.0 && m[k] * s >= 0.0 && m[k + 1] * s >= 0.0 {
            for mj in &mut m[k..=k + 1] {
                if mj.abs() > SLOPE_CAP * s.abs() {
                    *mj = SLOPE_CAP * s;
                }
            }
        }
    }
    m
}

/// d y/d x at x[i] of the polynomial through the `points` rows nearest to
/// row i (centred where the table allows, one-sided at its ends; all rows
/// if there are fewer): Σ_j y_j L_j′(x_i) with the Lagrange basis L_j.
fn polynomial_slope(x: &[f64], y: &[f64], i: usize, points: usize) -> f64 {
    let n = x.len();
    let points = points.min(n);
    let first = i.saturating_sub(points / 2).min(n - points);
    let rows = first..first + points;
    let mut slope = 0.0;
    for j in rows.clone() {
        let basis_slope = if j == i {
            rows.clone()
                .filter(|&k| k != i)
                .map(|k| 1.0 / (x[i] - x[k]))
                .sum::<f64>()
        } else {
            let numerator: f64 = rows
                .clone()
                .filter(|&k| k != i && k != j)
                .map(|k| x[i] - x[k])
                .product();
            let denominator: f64 = rows
                .clone()
                .filter(|&k| k != j)
                .map(|k| x[j] - x[k])
                .product();
            numerator / denominator
        };
        slope += (y[j] - y[i]) * basis_slope;
    }
    slope
}

/// Slope at an end knot from the parabola through the first (or last) three
/// points: `h0`, `s0` belong to the end interval, `h1`, `s1` to its neighbour.
fn one_sided_slope(h0: f64, h1: f64, s0: f64, s1: f64) -> f64 {
    s0 + (s0 - s1) * h0 / (h0 + h1)
}

impl ViscoelasticModulus for TabulatedModulus {
    fn modulus(&self, omega: f64) -> Complex64 {
        self.evaluate(omega).0
    }

    fn modulus_and_log_slope(&self, omega: f64) -> (Complex64, Complex64) {
        self.evaluate(omega)
    }

    fn static_modulus(&self) -> f64 {
        self.storage[0]
    }

    fn loss_slope_at_zero(&self) -> f64 {
        self.loss[0] / self.omega[0]
    }

    fn structure_range(&self) -> (f64, f64) {
        (self.omega[0], self.omega[self.omega.len() - 1])
    }

    fn knots(&self) -> Vec<f64> {
        self.omega.clone()
    }

    fn comparison_modulus(&self) -> Option<Box<dyn ViscoelasticModulus>> {
        Some(Box::new(self.interpolation_comparison()))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modulus::StandardLinearSolid;

    /// Log-spaced frequencies from 10^`lo` to 10^`hi`, `per_decade` per decade,
    /// shifted by `offset` of a step.
    fn log_grid(lo: f64, hi: f64, per_decade: usize, offset: f64) -> Vec<f64> {
        let count = ((hi - lo) * per_decade as f64).round() as usize;
        (0..=count)
            .map(|i| 10f64.powf(lo + (i as f64 + offset) / per_decade as f64))
            .collect()
    }

    fn sampled<M: ViscoelasticModulus>(m: &M, omega: &[f64]) -> TabulatedModulus {
        TabulatedModulus::sampled(m, omega).unwrap()
    }

    /// A non-smooth, strictly monotone storage modulus with a plateau, a
    /// near-step and a peaked loss modulus.
    fn rough_table() -> TabulatedModulus {
        let omega = vec![1e-2, 1e-1, 1.0, 2.0, 10.0, 1e2, 1e3, 1.5e3, 1e4, 1e5, 1e6];
        let storage = vec![
            1e6,
            1e6,
            1.001e6,
            2e6,
            5e7,
            5.1e7,
            5.1e7,
            1e8,
            1e10,
            1e10 + 1.0,
            2e10,
        ];
        let loss = vec![1e3, 1e4, 1e5, 3e6, 4e7, 4e8, 3e8, 1e8, 3e8, 1e7, 1e6];
        TabulatedModulus::new(omega, storage, loss).unwrap()
    }

    /// ln ω sampled densely inside each interval of the table (knots excluded).
    fn inside_points(t: &TabulatedModulus, per_interval: usize) -> Vec<f64> {
        t.omega()
            .windows(2)
            .flat_map(|w| {
                let (a, b) = (w[0].ln(), w[1].ln());
                (1..per_interval).map(move |j| (a + (b - a) * j as f64 / per_interval as f64).exp())
            })
            .collect()
    }

    #[test]
    fn reproduces_table_points_exactly() {
        let t = rough_table();
        for i in 0..t.omega().len() {
            let e = t.modulus(t.omega()[i]);
            assert_eq!(e.re, t.storage()[i], "row {i}");
            assert_eq!(e.im, t.loss()[i], "row {i}");
        }
    }

    #[test]
    fn monotone_data_stay_monotone_and_flat_data_flat() {
        let t = rough_table();
        for w in t.omega().windows(2) {
            let (e0, e1) = (t.modulus(w[0]).re, t.modulus(w[1]).re);
            let mut prev = e0;
            for j in 1..=400 {
                let wj = w[0] * (w[1] / w[0]).powf(j as f64 / 400.0);
                let e = t.modulus(wj).re;
                // Rounding of exp(…) allows a few ulp of wobble.
                let tol = 4.0 * f64::EPSILON * e;
                assert!(e >= prev - tol, "E' decreases at {wj}");
                assert!(e >= e0 - tol && e <= e1 + tol, "E' overshoots at {wj}");
                if e0 == e1 {
                    assert_eq!(e, e0, "flat interval not flat at {wj}");
                }
                prev = e;
            }
        }
    }

    #[test]
    fn monotone_stretches_of_peaked_data_stay_monotone() {
        // E″ of the rough table rises to row 5, falls to row 7, rises to row
        // 8 and falls to the end. Intervals not touching an extremum (rows
        // 0–4 and 9–10) must be monotone and within their end values.
        let t = rough_table();
        for k in [0, 1, 2, 3, 9] {
            let (w0, w1) = (t.omega()[k], t.omega()[k + 1]);
            let (l0, l1) = (t.loss()[k], t.loss()[k + 1]);
            let mut prev = l0;
            for j in 1..400 {
                let e = t.modulus(w0 * (w1 / w0).powf(j as f64 / 400.0)).im;
                let tol = 4.0 * f64::EPSILON * e;
                assert!(
                    e >= l0.min(l1) - tol && e <= l0.max(l1) + tol,
                    "interval {k}"
                );
                if l1 > l0 {
                    assert!(e >= prev - tol, "interval {k}");
                } else {
                    assert!(e <= prev + tol, "interval {k}");
                }
                prev = e;
            }
        }
    }

    /// E′ from monotone data: `steps` of (decades to the next frequency,
    /// 0 for a flat step, ln E′ step), all rising or all falling; E″ = 1.
    fn stepped_table(steps: &[(f64, usize, f64)], rising: bool) -> TabulatedModulus {
        let (mut lw, mut le) = (0.0f64, 10.0f64);
        let (mut omega, mut storage) = (vec![1.0], vec![le.exp()]);
        for &(dw, flat, de) in steps {
            lw += dw * std::f64::consts::LN_10;
            le += if flat == 0 {
                0.0
            } else if rising {
                de
            } else {
                -de
            };
            omega.push(lw.exp());
            storage.push(le.exp());
        }
        let n = omega.len();
        TabulatedModulus::new(omega, storage, vec![1.0; n]).unwrap()
    }

    /// The first place where E′ of a table of monotone data (rising if
    /// `sign` > 0) is not monotone or leaves its interval's end values, by
    /// more than rounding of the final exp and product (2 ulp). Sampled, in
    /// increasing order, at each knot, the 16 binary64 frequencies on either
    /// side of it and 63 points inside each interval: the knots are where a
    /// cubic anchored at one end only missed the other end by up to 20 ulp.
    fn monotone_violation(t: &TabulatedModulus, sign: f64) -> Option<String> {
        let next =
            |w: f64, up: bool| f64::from_bits(if up { w.to_bits() + 1 } else { w.to_bits() - 1 });
        let n = t.omega().len();
        let mut prev = t.storage()[0];
        for k in 0..n - 1 {
            let (w0, w1) = (t.omega()[k], t.omega()[k + 1]);
            let (e0, e1) = (t.storage()[k], t.storage()[k + 1]);
            let mut points = vec![w0];
            let mut w = w0;
            for _ in 0..16 {
                w = next(w, true);
                points.push(w);
            }
            points.extend((1..64).map(|j| w0 * (w1 / w0).powf(j as f64 / 64.0)));
            let mut below = Vec::new();
            let mut w = w1;
            for _ in 0..16 {
                w = next(w, false);
                below.push(w);
            }
            points.extend(below.into_iter().rev());
            for w in points {
                let e = t.modulus(w).re;
                let tol = 2.0 * f64::EPSILON * e;
                if sign * (e - prev) < -tol {
                    return Some(format!(
                        "interval {k}: E' = {e:e} at {w:e} goes back from {prev:e}"
                    ));
                }
                if e < e0.min(e1) - tol || e > e0.max(e1) + tol {
                    return Some(format!(
                        "interval {k}: E' = {e:e} at {w:e} is outside [{e0:e}, {e1:e}]"
                    ));
                }
                prev = e;
            }
        }
        let (e_last, e_end) = (t.storage()[n - 1], t.modulus(t.omega()[n - 1]).re);
        (e_end != e_last).then(|| format!("the last knot gives {e_end:e}, not {e_last:e}"))
    }

    #[test]
    fn monotone_data_found_by_the_property_test_give_a_monotone_curve() {
        // The case first found (recorded in proptest-regressions/) and the
        // minimal one proptest shrank the knot test to: a fall of 4.4 in
        // ln E′ within 0.01 decades between two plateaus. With the cubic
        // written as a power series from the left knot, E′ overshot E′_{k+1}
        // by several ulp (up to 20 in random tables) in the last few ulps of
        // ω before ω_{k+1}.
        for steps in [
            vec![
                (0.01, 0, 0.0),
                (0.01, 1, 4.374126230511208),
                (2.520719780355095, 0, 0.0),
            ],
            vec![
                (0.42896838748066213, 1, 4.200766711361163),
                (2.603846879900324, 1, 1.3633562790780025),
                (0.3954269330700939, 1, 1.1714423991203393),
                (1.8316326003105754, 0, 0.0),
                (2.0567966253793917, 1, 3.7177228225506145),
                (2.4939088793445214, 0, 0.0),
                (0.33824119917726003, 1, 3.8522138799328687),
            ],
        ] {
            for (rising, sign) in [(true, 1.0), (false, -1.0)] {
                let t = stepped_table(&steps, rising);
                assert_eq!(
                    monotone_violation(&t, sign),
                    None,
                    "{steps:?} rising {rising}"
                );
            }
        }
    }

    proptest::proptest! {
        // Fixed seed and case count: the same 4096 tables on every run, so
        // CI cannot be flaky; cases recorded in proptest-regressions/ are
        // replayed first.
        #![proptest_config(proptest::test_runner::Config {
            cases: 4096,
            rng_algorithm: proptest::test_runner::RngAlgorithm::ChaCha,
            rng_seed: proptest::test_runner::RngSeed::Fixed(0x0007_ab1e_5eed),
            ..proptest::test_runner::Config::default()
        })]
        #[test]
        fn random_monotone_data_give_a_monotone_curve(
            steps in proptest::collection::vec((0.01f64..3.0, 0usize..4, 0.0f64..5.0), 1..12),
            rising in proptest::bool::ANY,
        ) {
            // Frequencies a random 0.01–3 decades apart; ln E′ steps of 0 to 5
            // (one in four flat) in one direction.
            let t = stepped_table(&steps, rising);
            let violation = monotone_violation(&t, if rising { 1.0 } else { -1.0 });
            proptest::prop_assert!(violation.is_none(), "{}", violation.unwrap_or_default());
        }
    }

    #[test]
    fn plateaus_stay_flat_but_a_flat_top_is_a_peak() {
        let omega = vec![1.0, 10.0, 100.0, 1e3, 1e4];
        let mid =
            |t: &TabulatedModulus, k: usize| t.modulus((t.omega()[k] * t.omega()[k + 1]).sqrt());
        // Rising, flat, rising: the flat interval stays flat.
        let t = TabulatedModulus::new(omega.clone(), vec![1.0, 2.0, 2.0, 3.0, 4.0], vec![1.0; 5])
            .unwrap();
        assert_eq!(mid(&t, 1).re, 2.0);
        // Rising, flat, flat, falling: a plateau, flat.
        let t = TabulatedModulus::new(omega.clone(), vec![1.0, 2.0, 2.0, 2.0, 1.0], vec![1.0; 5])
            .unwrap();
        assert_eq!(mid(&t, 1).re, 2.0);
        assert_eq!(mid(&t, 2).re, 2.0);
        // Rising, flat, falling: the peak lies between the two equal points.
        let t = TabulatedModulus::new(omega, vec![1.0; 5], vec![1.0, 2.0, 2.0, 1.0, 0.5]).unwrap();
        let top = mid(&t, 1).im;
        assert!(top > 2.0 && top < 2.5, "{top}");
        let (_, slope) = t.modulus_and_log_slope((10f64 * 100.0).sqrt());
        assert!(slope.im.abs() < 1e-12);
    }

    #[test]
    fn one_extremum_per_data_extremum() {
        // Sign changes of d ln E″/d ln ω over the whole table: the data have
        // a maximum (row 5), a minimum (row 7) and a maximum (row 8).
        let t = rough_table();
        let mut changes = 0;
        let mut prev = t.modulus_and_log_slope(t.omega()[0]).1.im;
        for w in inside_points(&t, 200) {
            let slope = t.modulus_and_log_slope(w).1.im;
            if slope * prev < 0.0 {
                changes += 1;
            }
            prev = slope;
        }
        assert_eq!(changes, 3);
    }

    #[test]
    fn log_slope_is_the_derivative_of_the_interpolant() {
        let sls = StandardLinearSolid::new(1e6, 1e8, 1.0).unwrap();
        for t in [rough_table(), sampled(&sls, &log_grid(-3.0, 4.0, 3, 0.0))] {
            for w in inside_points(&t, 7) {
                let (e, slope) = t.modulus_and_log_slope(w);
                let eps = 1e-6f64;
                let fd = (t.modulus(w * eps.exp()) - t.modulus(w * (-eps).exp())) / (2.0 * eps);
                assert!(
                    (slope.re - fd.re).abs() <= 1e-7 * e.re + 1e-9 * slope.re.abs(),
                    "{w}"
                );
                assert!(
                    (slope.im - fd.im).abs() <= 1e-7 * e.im + 1e-9 * slope.im.abs(),
                    "{w}"
                );
            }
        }
    }

    #[test]
    fn slope_is_continuous_at_interior_knots() {
        let t = rough_table();
        for &w in &t.omega()[1..t.omega().len() - 1] {
            let (e, left) = t.modulus_and_log_slope(w * (1.0 - 1e-12));
            let (_, right) = t.modulus_and_log_slope(w);
            assert!((left.re - right.re).abs() <= 1e-9 * e.re, "{w}");
            assert!((left.im - right.im).abs() <= 1e-9 * e.im, "{w}");
        }
    }

    #[test]
    fn extrapolates_with_terminal_behaviour() {
        let t = rough_table();
        let (w0, w1) = (1e-2, 1e6);
        for &w in &[0.0, 1e-9, 1e-4, 0.5e-2] {
            let (e, slope) = t.modulus_and_log_slope(w);
            assert_eq!(e.re, 1e6);
            assert!((e.im - 1e3 * w / w0).abs() <= 1e-15 * 1e3);
            assert_eq!(slope.re, 0.0);
            assert_eq!(slope.im, e.im);
        }
        for &w in &[2e6, 1e9, 1e20] {
            let (e, slope) = t.modulus_and_log_slope(w);
            assert_eq!(e.re, 2e10);
            assert!((e.im / (1e6 * w1 / w) - 1.0).abs() < 1e-15);
            assert_eq!(slope.re, 0.0);
            assert_eq!(slope.im, -e.im);
        }
        assert_eq!(t.modulus(f64::INFINITY), Complex64::new(2e10, 0.0));
        assert_eq!(t.static_modulus(), 1e6);
        assert_eq!(t.loss_slope_at_zero(), 1e3 / 1e-2);
        assert_eq!(t.structure_range(), (w0, w1));
        // Continuous at both ends.
        for (w, outward) in [(w0, -1.0), (w1, 1.0)] {
            let inside = t.modulus(w * (1.0 - outward * 1e-12));
            let outside = t.modulus(w * (1.0 + outward * 1e-12));
            assert!((inside - outside).norm() < 1e-10 * inside.norm(), "{w}");
        }
    }

    #[test]
    fn two_rows_interpolate_as_power_laws() {
        let t = TabulatedModulus::new(vec![1.0, 100.0], vec![1e6, 1e8], vec![1e5, 1e4]).unwrap();
        let (e, slope) = t.modulus_and_log_slope(10.0);
        assert!((e.re / 1e7 - 1.0).abs() < 1e-14);
        assert!((e.im / (1e5 * 10f64.powf(-0.5)) - 1.0).abs() < 1e-14);
        assert!((slope.re / e.re - 1.0).abs() < 1e-14);
        assert!((slope.im / e.im + 0.5).abs() < 1e-14);
    }

    #[test]
    fn reproduces_a_standard_linear_solid_between_points() {
        // 10 points per decade over the whole transition, with the grid moved
        // through one step so that the loss peak falls anywhere between points.
        for ratio in [10.0, 1e3] {
            let sls = StandardLinearSolid::new(1e6, 1e6 * ratio, 1.0).unwrap();
            let mut worst = (0.0f64, 0.0f64, 0.0f64);
            for step in 0..10 {
                let t = sampled(
                    &sls,
                    &log_grid(-4.0, 4.0 + ratio.log10(), 10, step as f64 / 10.0),
                );
                for w in inside_points(&t, 16) {
                    let (e, slope) = t.modulus_and_log_slope(w);
                    let (exact, exact_slope) = sls.modulus_and_log_slope(w);
                    worst.0 = worst.0.max((e.re / exact.re - 1.0).abs());
                    worst.1 = worst.1.max((e.im / exact.im - 1.0).abs());
                    // The slope is one order less accurate than the value:
                    // 0.7 % of |E| next to the loss peak.
                    worst.2 = worst.2.max((slope - exact_slope).norm() / exact.norm());
                }
            }
            // Measured: E′ 3.2e-4, E″ 1.6e-4, slope 6.8e-3 (E1/E0 = 10).
            assert!(
                worst.0 < 1e-3 && worst.1 < 1e-3 && worst.2 < 1e-2,
                "E1/E0 = {ratio}: {worst:?}"
            );
        }
    }

    fn table_error(omega: Vec<f64>, storage: Vec<f64>, loss: Vec<f64>) -> String {
        match TabulatedModulus::new(omega, storage, loss) {
            Err(ModelError::InvalidTable { name, problem }) => {
                assert_eq!(name, TABLE);
                problem
            }
            other => panic!("expected a table error, got {other:?}"),
        }
    }

    #[test]
    fn rejects_malformed_tables_naming_the_row() {
        let ok = || {
            (
                vec![1.0, 2.0, 3.0],
                vec![1e6, 2e6, 3e6],
                vec![1e5, 2e5, 1e5],
            )
        };
        assert!(table_error(vec![], vec![], vec![]).contains("empty"));
        assert!(table_error(vec![1.0], vec![1e6], vec![1e5]).contains("only one row"));
        let msg = table_error(vec![1.0, 2.0], vec![1e6], vec![1e5, 1e5]);
        assert!(
            msg.contains("omega has 2 rows, E_storage 1 and E_loss 2"),
            "{msg}"
        );
        let msg = table_error(vec![1.0, 2.0], vec![1e6, 1e6], vec![1e5]);
        assert!(msg.contains("E_loss 1"), "{msg}");

        type Column = fn(&mut (Vec<f64>, Vec<f64>, Vec<f64>)) -> &mut Vec<f64>;
        let columns: [(&str, Column); 3] = [
            ("omega", |t| &mut t.0),
            ("E_storage", |t| &mut t.1),
            ("E_loss", |t| &mut t.2),
        ];
        for (column, pick) in columns {
            for (bad, what) in [
                (f64::NAN, "not a finite number"),
                (f64::INFINITY, "not a finite number"),
                (0.0, "must be greater than zero"),
                (-1.0, "must be greater than zero"),
            ] {
                let mut t = ok();
                pick(&mut t)[2] = bad;
                let msg = table_error(t.0, t.1, t.2);
                assert!(
                    msg.starts_with(&format!("row 2: {column} = {bad}")),
                    "{msg}"
                );
                assert!(msg.contains(what), "{msg}");
            }
        }

        let msg = table_error(vec![1.0, 3.0, 2.0], vec![1.0; 3], vec![1.0; 3]);
        assert!(
            msg.starts_with("row 2: omega = 2 rad/s is not greater than row 1"),
            "{msg}"
        );
        assert!(msg.contains("strictly increasing"), "{msg}");
        let msg = table_error(vec![1.0, 3.0, 3.0], vec![1.0; 3], vec![1.0; 3]);
        assert!(msg.starts_with("row 2:"), "{msg}");
        let w = 1e9f64;
        let next = f64::from_bits(w.to_bits() + 1);
        let msg = table_error(vec![w, next], vec![1.0; 2], vec![1.0; 2]);
        assert!(
            msg.starts_with("row 1:") && msg.contains("logarithmic"),
            "{msg}"
        );
    }
}
