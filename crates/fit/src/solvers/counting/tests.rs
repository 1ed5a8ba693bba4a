use super::*;
use crate::data::Measurements;
use crate::parametrization::Parametrization;
use crate::params::{Method, ModulusAnchor};
use crate::solvers::{Tolerance, run};

/// A small anchored problem: nine speeds over eight decades, eight terms.
fn data() -> Measurements {
    let speeds: Vec<f64> = (0..9).map(|i| 1e-7 * 10f64.powi(i)).collect();
    let mu = speeds
        .iter()
        .map(|v| 0.01 + 0.001 * v.log10().abs())
        .collect();
    Measurements::new(speeds, mu, None, None).unwrap()
}

fn objective<'a>(setup: &'a crate::params::RollingSetup, data: &'a Measurements) -> Objective<'a> {
    let tau = (0..8).map(|k| 10f64.powf(k as f64 - 5.0)).collect();
    let anchor = ModulusAnchor {
        omega: 0.0,
        modulus: 2e6,
        source: "E0",
    };
    Objective {
        setup,
        data,
        scales: data.residual_scales(),
        param: Parametrization::new(tau, Some(anchor)),
        shift: None,
        lambda: 0.3,
        e1_max: 1e10,
        tolerance: 1e-6,
        vertical: None,
        dma: None,
        friction_factor: false,
        noise_known: data.sigma().is_some(),
    }
}

/// Two starts of the anchored problem, the first with the larger V.
fn worse_and_better(objective: &Objective<'_>) -> (Vec<f64>, Vec<f64>) {
    let a = vec![3.0; 8];
    let b: Vec<f64> = (0..8).map(|k| 3.0 + 0.4 * (k as f64).sin()).collect();
    let v = |theta: &[f64]| objective.evaluate(theta, false).unwrap().objective();
    assert_ne!(v(&a), v(&b));
    if v(&a) > v(&b) { (a, b) } else { (b, a) }
}

#[test]
fn budget_refuses_further_evaluations_and_keeps_the_count() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let (theta, _) = worse_and_better(&objective);
    let counted = Counted::new(&objective, 3);
    for _ in 0..3 {
        assert!(counted.halt().is_none());
        counted.evaluate(&theta, false).unwrap();
    }
    assert_eq!(counted.halt(), Some(Halt::Budget(3)));
    match counted.evaluate(&theta, true) {
        Err(Refusal::Halted(Halt::Budget(3))) => {}
        other => panic!("expected the budget to refuse, got {other:?}"),
    }
    let tally = counted.into_tally();
    assert_eq!(tally.evaluations, 3);
    assert_eq!(tally.history.len(), 3);
    assert_eq!(tally.abandoned, None);
}

#[test]
fn best_point_is_kept_and_history_is_the_best_so_far() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let (worse, better) = worse_and_better(&objective);
    let v_worse = objective.evaluate(&worse, false).unwrap().objective();
    let v_better = objective.evaluate(&better, false).unwrap().objective();
    let counted = Counted::new(&objective, 10);
    for theta in [&worse, &better, &worse] {
        counted.evaluate(theta, false).unwrap();
    }
    let tally = counted.into_tally();
    assert_eq!(tally.best, Some((v_better, better)));
    assert_eq!(
        tally.history,
        vec![(1, v_worse), (2, v_better), (3, v_better)]
    );
}

#[test]
fn abandonment_is_its_own_outcome() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let (theta, _) = worse_and_better(&objective);
    let rule = Abandonment {
        after: 2,
        above: 0.0,
    };
    // The budget runs out at the same evaluation: abandonment still wins.
    let counted = Counted::new(&objective, 2).abandoning(Some(rule));
    counted.evaluate(&theta, false).unwrap();
    assert!(counted.halt().is_none(), "not tested before `after`");
    counted.evaluate(&theta, false).unwrap();
    assert_eq!(counted.halt(), Some(Halt::Abandoned(rule)));
    match counted.evaluate(&theta, false) {
        Err(Refusal::Halted(Halt::Abandoned(r))) => assert_eq!(r, rule),
        other => panic!("expected the abandonment to refuse, got {other:?}"),
    }
    let tally = counted.into_tally();
    assert_eq!(tally.abandoned, Some(rule));
    assert_eq!(tally.evaluations, 2);
    assert!(matches!(
        Halt::Abandoned(rule).stop_reason(),
        StopReason::Abandoned(_)
    ));

    // A start that is good enough by then is not abandoned.
    let lenient = Abandonment {
        after: 1,
        above: f64::INFINITY,
    };
    let counted = Counted::new(&objective, 5).abandoning(Some(lenient));
    counted.evaluate(&theta, false).unwrap();
    counted.evaluate(&theta, false).unwrap();
    assert!(counted.halt().is_none());
    assert_eq!(counted.into_tally().abandoned, None);
}

#[test]
fn failed_evaluation_is_counted_but_not_recorded() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let counted = Counted::new(&objective, 5);
    let bad = vec![f64::NAN; 8];
    assert!(matches!(
        counted.evaluate(&bad, false),
        Err(Refusal::Failed(_))
    ));
    // argmin sees a very poor but finite V and goes on.
    let cost = (&counted).cost(&DVector::from_vec(bad)).unwrap();
    assert_eq!(cost, REFUSED_OBJECTIVE);
    let tally = counted.into_tally();
    assert_eq!(tally.evaluations, 2);
    assert!(tally.history.is_empty() && tally.best.is_none());
}

/// Through each solver: a budget ends the run as `Budget`, an abandonment
/// as `Abandoned`, and the run keeps its best point. (Nelder–Mead gets at
/// least the n + 1 evaluations of its first simplex: argmin's Nelder–Mead
/// cannot stop inside its initialisation.)
#[test]
fn solvers_report_budget_and_abandonment_by_type() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let (start, _) = worse_and_better(&objective);
    let v_start = objective.evaluate(&start, false).unwrap().objective();
    let simplex = start.len() + 1;
    for (method, budget, after) in [
        (Method::LevenbergMarquardt, 3, 1),
        (Method::Lbfgs, 3, 1),
        (Method::NelderMead, simplex + 3, simplex),
    ] {
        let r = run(
            method,
            Counted::new(&objective, budget),
            &start,
            Tolerance::Final,
        );
        assert_eq!(r.stop, StopReason::Budget, "{method:?}");
        assert!(r.evaluations <= budget, "{method:?}: {}", r.evaluations);
        assert!(r.objective <= v_start, "{method:?}");

        let rule = Abandonment { after, above: 0.0 };
        let counted = Counted::new(&objective, 1000).abandoning(Some(rule));
        let r = run(method, counted, &start, Tolerance::Final);
        assert_eq!(r.stop, rule.stop_reason(), "{method:?}");
        assert!(!r.stop.converged() && r.stop != StopReason::Budget);
        assert_eq!(r.evaluations, after, "{method:?}");
        assert!(r.objective <= v_start, "{method:?}");
        if after == 1 {
            assert_eq!((r.objective, r.theta), (v_start, start.clone()));
        }
    }
}

/// A budget smaller than Nelder–Mead's first simplex ends the run at its
/// start point as `Budget` (argmin would panic inside its initialisation).
#[test]
fn nelder_mead_below_its_simplex_stops_at_the_start() {
    let setup = crate::params::example_setup();
    let data = data();
    let objective = objective(&setup, &data);
    let (start, _) = worse_and_better(&objective);
    let v_start = objective.evaluate(&start, false).unwrap().objective();
    for budget in [1, 2, start.len()] {
        let r = run(
            Method::NelderMead,
            Counted::new(&objective, budget),
            &start,
            Tolerance::Final,
        );
        assert_eq!(r.stop, StopReason::Budget, "budget {budget}");
        assert_eq!(r.evaluations, 1, "budget {budget}");
        assert_eq!((r.objective, r.theta.clone()), (v_start, start.clone()));
    }
}
