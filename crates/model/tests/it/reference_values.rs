//! μ(v) against the independent high-accuracy reference values
//! (fixtures/forward_reference.json, copied from the project's shared
//! reference set; relative accuracy about 1e-8).

use rollfit_model::{ContactSize, Geometry, Prony, Scene, Shape, StandardLinearSolid, Substrate};
use serde_json::Value;

struct Case {
    id: String,
    scene: Scene<Prony>,
    points: Vec<(f64, f64)>,
}

fn cases() -> Vec<Case> {
    let text = include_str!("../fixtures/forward_reference.json");
    let records: Vec<Value> = serde_json::from_str(text).unwrap();
    records
        .iter()
        .map(|r| {
            let shape = match r["shape"].as_str().unwrap() {
                "sphere" => Shape::Sphere,
                _ => Shape::Cylinder,
            };
            let contact = match r["contact"].as_str().unwrap() {
                "static" => ContactSize::Static,
                _ => ContactSize::Dynamic,
            };
            let m = &r["material"];
            let prony = match m["kind"].as_str().unwrap() {
                "sls" => StandardLinearSolid::new(
                    m["E0"].as_f64().unwrap(),
                    m["E1"].as_f64().unwrap(),
                    m["tau"].as_f64().unwrap(),
                )
                .unwrap()
                .to_prony(),
                _ => Prony::new(
                    m["E_inf"].as_f64().unwrap(),
                    m["H"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap())
                        .collect(),
                    m["tau"]
                        .as_array()
                        .unwrap()
                        .iter()
                        .map(|x| x.as_f64().unwrap())
                        .collect(),
                )
                .unwrap(),
            };
            let scene = Scene::new(
                Geometry {
                    shape,
                    radius: r["R"].as_f64().unwrap(),
                    load: r["load"].as_f64().unwrap(),
                },
                Substrate {
                    poisson: r["nu"].as_f64().unwrap(),
                    film_thickness: r["film_thickness"].as_f64(),
                },
                contact,
                prony,
            )
            .unwrap();
            let expected_size = r["static_contact_size"].as_f64().unwrap();
            assert!(
                (scene.static_contact_size() / expected_size - 1.0).abs() < 1e-12,
                "{}",
                r["id"]
            );
            Case {
                id: r["id"].as_str().unwrap().to_string(),
                scene,
                points: r["points"]
                    .as_array()
                    .unwrap()
                    .iter()
                    .map(|p| (p["v"].as_f64().unwrap(), p["mu"].as_f64().unwrap()))
                    .collect(),
            }
        })
        .collect()
}

/// Reference points our independent brute-force integration disagrees with
/// (see `disputed_point_matches_brute_force`).
const DISPUTED: [(&str, f64); 1] = [("paper-sphere", 10.400419115259524)];

fn is_disputed(id: &str, v: f64) -> bool {
    DISPUTED
        .iter()
        .any(|&(i, dv)| i == id && (v / dv - 1.0).abs() < 1e-12)
}

fn worst_error(case: &Case, scene: &Scene<Prony>) -> f64 {
    let mut worst: f64 = 0.0;
    for &(v, mu_ref) in &case.points {
        if is_disputed(&case.id, v) {
            continue;
        }
        let mu = scene.friction(v).unwrap();
        let err = (mu / mu_ref - 1.0).abs();
        eprintln!(
            "{} v={v:e} mu={mu:.12e} ref={mu_ref:.12e} rel={err:.2e}",
            case.id
        );
        worst = worst.max(err);
    }
    worst
}

#[test]
fn every_reference_point_within_1e_6_at_default_tolerance() {
    for case in cases().into_iter().filter(|c| !is_film_sphere(c)) {
        let worst = worst_error(&case, &case.scene);
        assert!(worst <= 1e-6, "{}: worst relative error {worst:e}", case.id);
    }
}

#[test]
fn sweep_agrees_with_single_points() {
    for case in cases().into_iter().filter(|c| !is_film_sphere(c)) {
        let speeds: Vec<f64> = case.points.iter().map(|p| p.0).collect();
        let sweep = case.scene.friction_sweep(&speeds).unwrap();
        for (&(v, mu_ref), mu) in case.points.iter().zip(sweep) {
            if is_disputed(&case.id, v) {
                continue;
            }
            assert!(
                (mu / mu_ref - 1.0).abs() <= 1e-6,
                "{} v={v}: {mu} vs {mu_ref}",
                case.id
            );
        }
    }
}

fn is_film_sphere(case: &Case) -> bool {
    case.scene.geometry().shape == Shape::Sphere && case.scene.substrate().film_thickness.is_some()
}

#[test]
fn film_under_sphere_reference() {
    for case in cases().into_iter().filter(is_film_sphere) {
        let worst = worst_error(&case, &case.scene);
        assert!(worst <= 1e-6, "{}: worst relative error {worst:e}", case.id);
    }
}

/// The reference's paper-sphere point at vτ/r0 = 1e4 is 2.24e-5 above what we
/// compute; a slow, direct Gauss–Legendre integration of the one-dimensional
/// form μ = 18F/(π²v²) ∫dω ω L(ω) G(ω r(ω)/v), written here and independent
/// of the product integration (G itself is checked against an mpmath
/// evaluation in the kernel's unit tests), agrees with our value to 1e-9.
#[test]
fn disputed_point_matches_brute_force() {
    use rollfit_model::ViscoelasticModulus;
    use rollfit_model::kernel::sphere;
    let case = cases()
        .into_iter()
        .find(|c| c.id == "paper-sphere")
        .unwrap();
    let (v, mu_ref) = *case
        .points
        .iter()
        .find(|p| is_disputed(&case.id, p.0))
        .unwrap();
    let material = case.scene.material().clone();
    let (load, radius) = (0.15, 0.01);
    let size = |w: f64| (0.75 * load * radius / material.modulus(w).norm()).cbrt();
    let integrand = |ln_w: f64, smooth_only: bool| {
        let w = ln_w.exp();
        let loss_compliance = -(1.0 / material.modulus(w)).im;
        let x = w * size(w) / v;
        let g = if smooth_only {
            sphere::smooth_part(x)
        } else {
            sphere::g(x)
        };
        w * w * loss_compliance * g
    };
    let gauss = [
        (-0.8611363115940526, 0.3478548451374538),
        (-0.3399810435848563, 0.6521451548625461),
        (0.3399810435848563, 0.6521451548625461),
        (0.8611363115940526, 0.3478548451374538),
    ];
    let panel_sum = |lo: f64, width: f64, count: usize, smooth_only: bool| -> f64 {
        (0..count)
            .map(|i| {
                let a = lo + i as f64 * width;
                gauss
                    .iter()
                    .map(|&(x, w)| {
                        w * 0.5 * width * integrand(a + 0.5 * width * (1.0 + x), smooth_only)
                    })
                    .sum::<f64>()
            })
            .sum()
    };
    // Up to x = 3000 with the full kernel, beyond with its smooth part (the
    // oscillating remainder there is below 1e-9 of μ).
    let mut top = 0.0f64;
    while top.exp() * size(top.exp()) / v < 3000.0 {
        top += 0.01;
    }
    let bottom = (1e-14f64).ln();
    let count = ((top - bottom) / 0.005) as usize;
    let body = panel_sum(bottom, (top - bottom) / count as f64, count, false);
    let tail = panel_sum(top, 0.01, 4000, true);
    let brute = 18.0 * load / (std::f64::consts::PI.powi(2) * v * v) * (body + tail);
    let mu = case.scene.friction(v).unwrap();
    assert!(
        (mu / brute - 1.0).abs() < 1e-8,
        "{mu} vs brute force {brute}"
    );
    let disagreement = mu_ref / brute - 1.0;
    eprintln!("reference exceeds the brute-force value by {disagreement:e}");
    assert!(
        disagreement > 1e-5,
        "the reference now agrees: remove the dispute"
    );
}
