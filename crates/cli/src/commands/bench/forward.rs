//! The forward-model chart of `rollfit bench`: every rung of the model
//! ladder at each setting of its dial, timed per μ and compared with the
//! reference over the scene's sweep (see the parent module).

use std::path::Path;
use std::sync::Arc;
use std::time::Instant;

use anyhow::{Context, Result, anyhow};
use rollfit_fit::RollingSetup;
use rollfit_model::exact::{ExactSettings, RollingCylinder};
use rollfit_model::{ContactSize, Prony, Scene, ViscoelasticModulus};

use super::{Dials, ForwardRow, REFERENCE_TOLERANCE};
use rollfit_io::scene as scene_file;

/// Times `f` (one call evaluates `count` μ) until at least `min_time` has
/// passed; seconds per μ.
fn time_per_mu(count: usize, min_time: f64, mut f: impl FnMut() -> Result<()>) -> Result<f64> {
    let started = Instant::now();
    let mut calls = 0usize;
    loop {
        f()?;
        calls += 1;
        let elapsed = started.elapsed().as_secs_f64();
        if elapsed >= min_time {
            return Ok(elapsed / (calls * count) as f64);
        }
    }
}

fn errors(values: &[f64], reference: &[f64]) -> (f64, f64) {
    let relative: Vec<f64> = values
        .iter()
        .zip(reference)
        .map(|(v, r)| ((v - r) / r).abs())
        .collect();
    let max = relative.iter().copied().fold(0.0, f64::max);
    let rms = (relative.iter().map(|e| e * e).sum::<f64>() / relative.len() as f64).sqrt();
    (max, rms)
}

/// The forward chart's measurements and what they were compared with.
pub(super) struct Forward {
    pub(super) rows: Vec<ForwardRow>,
    /// What the errors are relative to.
    pub(super) reference: String,
    /// Speeds compared, m/s.
    pub(super) speeds: Vec<f64>,
}

pub(super) fn forward_rows(path: &Path, dials: &Dials<'_>) -> Result<Forward> {
    let note = |note: &str| eprintln!("note: {note}");
    let file = scene_file::load(path)?;
    let section = file
        .material
        .as_ref()
        .context("bench needs a [material] section")?;
    let base = path.parent().unwrap_or(Path::new(""));
    let bench = Rungs {
        material: Arc::from(section.build(base, &note)?),
        setup: file.rolling_setup(),
    };
    let sweep = file
        .sweep
        .as_ref()
        .context("bench needs a [sweep] section")?
        .speeds()?;
    let paper = bench
        .scene(ContactSize::Dynamic, REFERENCE_TOLERANCE)?
        .friction_sweep(&sweep)
        .map_err(|e| anyhow!("{e}"))?;
    let peak = paper
        .iter()
        .enumerate()
        .max_by(|a, b| a.1.total_cmp(b.1))
        .map_or(0, |(i, _)| i);
    let v_peak = sweep[peak];

    // With the exact solution (cylinder, half-space, SLS or Prony) the
    // errors are against it, from three decades below the friction maximum
    // up (lower, its edge layers need more terms than the reference has);
    // otherwise against the paper's theory at a tight tolerance.
    let reference = match file.exact_material(section, base, None, &note) {
        Ok(prony) => {
            let kept: Vec<f64> = sweep
                .iter()
                .copied()
                .filter(|&v| v >= v_peak * 1e-3)
                .collect();
            let speeds = thin(&kept, dials.max_speeds);
            let settings = ExactSettings {
                terms: Some(REFERENCE_TERMS),
                max_terms: REFERENCE_TERMS,
                ..ExactSettings::default()
            };
            let cylinder = file.exact_cylinder_with(&prony, settings)?;
            let for_auto = file.exact_cylinder_with(&prony, ExactSettings::default())?;
            Reference {
                mu: exact_sweep(&cylinder, &speeds)?,
                speeds,
                name: format!("the exact rolling cylinder with {REFERENCE_TERMS} Chebyshev terms"),
                exact: Some((prony, for_auto)),
            }
        }
        Err(why) => {
            // `{:#}` of anyhow: the message and its sources.
            let why = anyhow::Error::from(why);
            let speeds = thin(&sweep, dials.max_speeds);
            Reference {
                mu: bench
                    .scene(ContactSize::Dynamic, REFERENCE_TOLERANCE)?
                    .friction_sweep(&speeds)
                    .map_err(|e| anyhow!("{e}"))?,
                speeds,
                name: format!(
                    "Eq. (11) with the dynamic contact size at tolerance {REFERENCE_TOLERANCE:.0e} \
                     (no exact rung: {why:#})"
                ),
                exact: None,
            }
        }
    };

    let mut rows = Vec::new();
    rows.extend(bench.asymptote_row(&reference, v_peak, dials)?);
    rows.extend(bench.quadrature_rows(&reference, dials)?);
    if let Some((prony, _)) = &reference.exact {
        for &n in dials.terms {
            let settings = ExactSettings {
                terms: n,
                ..ExactSettings::default()
            };
            let cylinder = file.exact_cylinder_with(prony, settings)?;
            rows.push(exact_row(&cylinder, n, &reference, dials.min_time)?);
        }
    }
    rows.extend(bench.auto_rows(&reference, dials)?);
    Ok(Forward {
        rows,
        reference: reference.name,
        speeds: reference.speeds,
    })
}

/// The material and set-up of the forward scene, to build each rung's scene.
struct Rungs {
    material: Arc<dyn ViscoelasticModulus>,
    setup: RollingSetup,
}

/// What the rungs are compared with.
struct Reference {
    /// Speeds compared, m/s.
    speeds: Vec<f64>,
    /// μ of the reference at `speeds`.
    mu: Vec<f64>,
    /// What the reference is.
    name: String,
    /// The Prony series of an exact rung and its default exact cylinder
    /// (None: the scene has no exact solution).
    exact: Option<(Prony, RollingCylinder)>,
}

impl Rungs {
    fn scene(
        &self,
        contact: ContactSize,
        tolerance: f64,
    ) -> Result<Scene<Arc<dyn ViscoelasticModulus>>> {
        Scene::new(
            self.setup.geometry,
            self.setup.substrate,
            contact,
            Arc::clone(&self.material),
        )
        .and_then(|s| s.with_tolerance(tolerance))
        .map_err(|e| anyhow!("{e}"))
    }

    /// The asymptote is a low-speed law (μ ∝ v^p grows without bound): its
    /// error is measured where it is meant to hold, two decades and more
    /// below the speed of the friction maximum.
    fn asymptote_row(
        &self,
        reference: &Reference,
        v_peak: f64,
        dials: &Dials<'_>,
    ) -> Result<Option<ForwardRow>> {
        let speeds = &reference.speeds;
        let low: Vec<usize> = (0..speeds.len())
            .filter(|&i| speeds[i] <= v_peak / 100.0)
            .collect();
        if low.is_empty() {
            return Ok(None);
        }
        let asymptotic = self.scene(ContactSize::Static, dials.tolerances[0])?;
        let low_speeds: Vec<f64> = low.iter().map(|&i| speeds[i]).collect();
        let mut values = Vec::new();
        let time = time_per_mu(low_speeds.len(), dials.min_time, || {
            values = low_speeds
                .iter()
                .map(|&v| asymptotic.low_speed_asymptote(v))
                .collect();
            Ok(())
        })?;
        let low_reference: Vec<f64> = low.iter().map(|&i| reference.mu[i]).collect();
        let (max_error, rms_error) = errors(&values, &low_reference);
        Ok(Some(ForwardRow {
            rung: "asymptote",
            setting: "v ≤ v_peak/100".into(),
            time_per_mu: time,
            max_error,
            rms_error,
            numerical_error: f64::NAN,
        }))
    }

    /// Eq. (11)/(17) with the static and the dynamic contact size at each
    /// tolerance of the dial.
    fn quadrature_rows(&self, reference: &Reference, dials: &Dials<'_>) -> Result<Vec<ForwardRow>> {
        let speeds = &reference.speeds;
        let mut rows = Vec::new();
        for (rung, contact) in [
            ("static", ContactSize::Static),
            ("dynamic", ContactSize::Dynamic),
        ] {
            let tight = self
                .scene(contact, REFERENCE_TOLERANCE)?
                .friction_sweep(speeds)
                .map_err(|e| anyhow!("{e}"))?;
            for &tolerance in dials.tolerances {
                let s = self.scene(contact, tolerance)?;
                let mut values = Vec::new();
                let time = time_per_mu(speeds.len(), dials.min_time, || {
                    values = s.friction_sweep(speeds).map_err(|e| anyhow!("{e}"))?;
                    Ok(())
                })?;
                let (max_error, rms_error) = errors(&values, &reference.mu);
                rows.push(ForwardRow {
                    rung,
                    setting: format!("{tolerance:.0e}"),
                    time_per_mu: time,
                    max_error,
                    rms_error,
                    numerical_error: errors(&values, &tight).0,
                });
            }
        }
        Ok(rows)
    }

    /// auto: the cheapest rung per speed for each requested accuracy, timed
    /// on one thread (its contact solves would otherwise share the cores,
    /// which the other rungs' timings do not).
    fn auto_rows(&self, reference: &Reference, dials: &Dials<'_>) -> Result<Vec<ForwardRow>> {
        let speeds = &reference.speeds;
        let exact_for_auto = match &reference.exact {
            Some((_, cylinder)) => Ok(cylinder),
            None => Err("no exact rung for this scene".to_string()),
        };
        let one_thread = rayon::ThreadPoolBuilder::new()
            .num_threads(1)
            .build()
            .context("cannot start a one-thread pool")?;
        let auto_scene = self.scene(ContactSize::Dynamic, dials.tolerances[0])?;
        let mut rows = Vec::new();
        for &accuracy in dials.accuracies {
            let mut values = Vec::new();
            let time = one_thread.install(|| {
                time_per_mu(speeds.len(), dials.min_time, || {
                    values = auto_scene
                        .friction_auto(speeds, accuracy, exact_for_auto.clone())
                        .map_err(|e| anyhow!("{e}"))?
                        .mu;
                    Ok(())
                })
            })?;
            let (max_error, rms_error) = errors(&values, &reference.mu);
            rows.push(ForwardRow {
                rung: "auto",
                setting: format!("ε = {accuracy:.0e}"),
                time_per_mu: time,
                max_error,
                rms_error,
                numerical_error: f64::NAN,
            });
        }
        Ok(rows)
    }
}

/// The exact cylinder with `terms` Chebyshev terms (None: automatic), one
/// speed after another: the time of one contact solve.
fn exact_row(
    cylinder: &RollingCylinder,
    terms: Option<usize>,
    reference: &Reference,
    min_time: f64,
) -> Result<ForwardRow> {
    let speeds = &reference.speeds;
    let mut values = Vec::new();
    let time = time_per_mu(speeds.len(), min_time, || {
        values = speeds
            .iter()
            .map(|&v| cylinder.solve(v).map(|s| s.mu))
            .collect::<Result<Vec<f64>, _>>()
            .map_err(|e| anyhow!("{e}"))?;
        Ok(())
    })?;
    let (max_error, rms_error) = errors(&values, &reference.mu);
    Ok(ForwardRow {
        rung: "exact",
        setting: terms.map_or_else(|| "N auto".to_string(), |n| format!("N = {n}")),
        time_per_mu: time,
        max_error,
        rms_error,
        numerical_error: max_error,
    })
}

/// Chebyshev terms of the exact reference.
const REFERENCE_TERMS: usize = 160;

/// At most `count` of `speeds`, evenly spread over the list (ends kept).
fn thin(speeds: &[f64], count: usize) -> Vec<f64> {
    if speeds.len() <= count || count < 2 {
        return speeds.to_vec();
    }
    (0..count)
        .map(|i| speeds[i * (speeds.len() - 1) / (count - 1)])
        .collect()
}

/// μ of the exact solution at every speed (in parallel).
fn exact_sweep(cylinder: &RollingCylinder, speeds: &[f64]) -> Result<Vec<f64>> {
    use rayon::prelude::*;
    speeds
        .par_iter()
        .map(|&v| cylinder.solve(v).map(|s| s.mu))
        .collect::<Result<Vec<f64>, _>>()
        .map_err(|e| anyhow!("exact reference: {e}"))
}
