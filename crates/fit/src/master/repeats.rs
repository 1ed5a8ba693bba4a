//! Repeated abscissae within one isotherm merged, for every kind of
//! isotherm alike: a frequency (rad/s) or a time stamp (s) printed with
//! too few digits repeats, and two sweeps merged at one temperature meet
//! at equal frequencies. Each run of consecutive points at one abscissa
//! becomes one point whose measured quantities (E′ and E″, or E(t), or
//! D(t)) are the arithmetic means of the run's: at equal abscissa that is
//! what a least-squares fit through all of them would see.
//!
//! Only consecutive equal abscissae are a run: a sweep that comes back to
//! an abscissa after others is no rounding but a restart, which the
//! callers refuse ([`super::sweep_turn`], or times that fall).

/// The points of one isotherm with each run of equal abscissae averaged.
#[derive(Debug, Clone, PartialEq)]
pub struct Averaged {
    /// The abscissa of each run (ω in rad/s or t in s), in order.
    pub abscissa: Vec<f64>,
    /// For each measured quantity, its mean over each run.
    pub quantities: Vec<Vec<f64>>,
    /// The index of each run's first point.
    pub firsts: Vec<usize>,
    /// How many points lie in runs of more than one.
    pub repeated_points: usize,
    /// How many runs have more than one point.
    pub repeated_runs: usize,
}

impl Averaged {
    /// Whether any run had more than one point.
    pub fn merged_any(&self) -> bool {
        self.repeated_runs > 0
    }
}

/// The points `indices` (in measured order) of an isotherm, each run of
/// consecutive points at one `abscissa` averaged into one point over each
/// of `quantities`.
pub fn average_repeats(
    indices: &[usize],
    abscissa: impl Fn(usize) -> f64,
    quantities: &[&dyn Fn(usize) -> f64],
) -> Averaged {
    let mut averaged = Averaged {
        abscissa: Vec::new(),
        quantities: vec![Vec::new(); quantities.len()],
        firsts: Vec::new(),
        repeated_points: 0,
        repeated_runs: 0,
    };
    for run in indices.chunk_by(|&a, &b| abscissa(a) == abscissa(b)) {
        averaged.abscissa.push(abscissa(run[0]));
        for (column, quantity) in averaged.quantities.iter_mut().zip(quantities) {
            column.push(run.iter().map(|&i| quantity(i)).sum::<f64>() / run.len() as f64);
        }
        averaged.firsts.push(run[0]);
        if run.len() > 1 {
            averaged.repeated_points += run.len();
            averaged.repeated_runs += 1;
        }
    }
    averaged
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Runs of equal abscissae, and only consecutive ones, are averaged;
    /// the counts are those of the runs, checked against a hand count.
    #[test]
    fn runs_are_averaged() {
        let x = [1.0, 2.0, 2.0, 2.0, 3.0, 4.0, 4.0, 2.0];
        let y = [10.0, 1.0, 2.0, 6.0, 5.0, 7.0, 8.0, 9.0];
        let order: Vec<usize> = (0..x.len()).collect();
        let averaged = average_repeats(&order, |i| x[i], &[&|i| y[i], &|i| -y[i]]);
        assert_eq!(averaged.abscissa, [1.0, 2.0, 3.0, 4.0, 2.0]);
        assert_eq!(averaged.quantities[0], [10.0, 3.0, 5.0, 7.5, 9.0]);
        assert_eq!(averaged.quantities[1], [-10.0, -3.0, -5.0, -7.5, -9.0]);
        assert_eq!(averaged.firsts, [0, 1, 4, 5, 7]);
        assert_eq!((averaged.repeated_points, averaged.repeated_runs), (5, 2));
        let plain = average_repeats(&[0, 4, 5], |i| x[i], &[&|i| y[i]]);
        assert!(!plain.merged_any());
    }
}
