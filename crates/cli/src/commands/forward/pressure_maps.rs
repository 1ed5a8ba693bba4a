//! The pressure maps of `rollfit forward -o OUT.csv`: where μ
//! comes from the exact rolling contact (`[contact] size = "exact"`, or
//! `"auto"` at the speeds where it used the exact rung), the pressure under
//! the body and the contact's outline at the sweep's speed of largest μ —
//! the contact furthest from Hertz's — and at each `--pressure-map` speed,
//! per temperature block. Files and columns: `rollfit_io::pressure_map`.
//!
//! Every map is solved, encoded and drawn before the first file of the
//! command is written, so that a failure leaves no output behind.

use std::path::Path;

use anyhow::{Context, Result, bail};
use rayon::prelude::*;
use rollfit_io::output;
use rollfit_io::pressure_map::{self, PressureMapCsv, PressureMapFiles};
use rollfit_io::scene::{ForwardBlock, ForwardRung, ForwardSetup};
use rollfit_model::Shape;
use rollfit_model::exact::{ExactRolling, PressureMap};
use rollfit_model::ladder::Rung;
use rollfit_report::plot::{self, Picture, pressure_map::PressureMapFigure};

use super::Solved;

/// The speeds rollfit accepts anywhere (the contract's `[sweep]` range),
/// m/s.
const SPEED_RANGE: (f64, f64) = (1e-15, 1000.0);

/// `--pressure-map`: a speed in m/s, finite and within the range of a
/// scene's `[sweep]` speeds. It need not be one of the sweep's: the exact
/// solution is solved afresh at it.
pub(super) fn parse_speed(text: &str) -> Result<f64, String> {
    let v: f64 = text
        .trim()
        .parse()
        .map_err(|_| format!("expected a rolling speed in m/s such as 1e-3, got {text:?}"))?;
    let (lo, hi) = SPEED_RANGE;
    if v.is_finite() && (lo..=hi).contains(&v) {
        Ok(v)
    } else {
        Err(format!(
            "the rolling speed must be a number from {lo:e} to {hi} m/s (the range of [sweep] \
             speeds), got {v}"
        ))
    }
}

/// The exact body a block's maps come from, borrowed from the sweep or
/// discretised as `auto` discretised its exact rung.
enum Body<'a> {
    Borrowed(&'a dyn ExactRolling),
    Owned(Box<dyn ExactRolling>),
}

impl Body<'_> {
    fn get(&self) -> &dyn ExactRolling {
        match self {
            Body::Borrowed(b) => *b,
            Body::Owned(b) => b.as_ref(),
        }
    }
}

/// The exact body of `block` as its sweep used it and the index of the
/// speed with the largest exact μ (None where no speed was exact); or why
/// the block has no exact body.
fn block_body<'a>(
    block: &'a ForwardBlock,
    solved: Option<&Solved>,
) -> Result<(Body<'a>, Option<usize>), String> {
    let largest = |indices: &mut dyn Iterator<Item = usize>, mu: &[f64]| {
        indices.max_by(|&a, &b| mu[a].total_cmp(&mu[b]))
    };
    match (&block.rung, solved) {
        (ForwardRung::Exact(body), solved) => {
            let peak = solved.and_then(|s| largest(&mut (0..s.mu.len()), &s.mu));
            Ok((Body::Borrowed(body.as_ref()), peak))
        }
        (ForwardRung::Auto { exact, .. }, solved) => {
            let body = exact.as_ref().map_err(|why| {
                format!("[contact] size = \"auto\" has no exact rolling body here: {why}")
            })?;
            let auto = solved.and_then(|s| s.auto.as_ref());
            let peak = auto.and_then(|a| {
                let mut exact_rows = (0..a.rungs.len()).filter(|&i| a.rungs[i] == Rung::Exact);
                largest(&mut exact_rows, &a.mu)
            });
            // The map's μ is then the sweep's at its speed.
            let body = match auto {
                Some(a) => Body::Owned(body.with_accuracy(a.exact_accuracy())),
                None => Body::Borrowed(body.as_ref()),
            };
            Ok((body, peak))
        }
        (ForwardRung::Paper | ForwardRung::LowSpeed, _) => Err(
            "pressure maps come from the exact rolling contact: set [contact] size = \"exact\" \
             (or \"auto\")"
                .into(),
        ),
    }
}

/// Refuses `--pressure-map` speeds for a scene without an exact rolling
/// body, before the sweep's computation.
pub(super) fn check_request(setup: &ForwardSetup, requested: &[f64], scene: &Path) -> Result<()> {
    if requested.is_empty() {
        return Ok(());
    }
    for block in &setup.blocks {
        if let Err(why) = block_body(block, None) {
            bail!(
                "--pressure-map {}: scene file {}: {why}",
                requested[0],
                scene.display()
            );
        }
    }
    Ok(())
}

/// One map, solved, encoded and drawn: ready to write.
pub(super) struct MapOutput {
    files: PressureMapFiles,
    csv: PressureMapCsv,
    picture: Picture,
    /// Speed, m/s; temperature, °C; whether --pressure-map asked for it.
    speed: f64,
    temperature: Option<f64>,
    requested: bool,
}

/// The maps of every block whose μ came from the exact contact: at the
/// speed of its largest exact μ and at each of `requested` (m/s), files
/// named beside `out`.
pub(super) fn solve(
    setup: &ForwardSetup,
    solved: &[Solved],
    requested: &[f64],
    out: &Path,
    scene: &Path,
) -> Result<Vec<MapOutput>> {
    let mut jobs = Vec::new();
    for (block, solved) in setup.blocks.iter().zip(solved) {
        let Ok((body, peak)) = block_body(block, Some(solved)) else {
            // check_request has refused requests for such a block.
            continue;
        };
        let mut speeds: Vec<(f64, bool)> = requested.iter().map(|&v| (v, true)).collect();
        if let Some(i) = peak {
            let v = setup.speeds[i];
            speeds.retain(|&(s, _)| s != v);
            speeds.push((v, requested.contains(&v)));
        }
        speeds.sort_by(|a, b| a.0.total_cmp(&b.0));
        speeds.dedup_by(|a, b| a.0 == b.0);
        let temperature = block.shift.map(|s| s.temperature);
        let body = std::sync::Arc::new(body);
        jobs.extend(
            speeds
                .into_iter()
                .map(|(v, requested)| (std::sync::Arc::clone(&body), v, requested, temperature)),
        );
    }
    let shape = setup.blocks[0].scene.geometry().shape;
    // Up to a second a sphere map: in parallel, like the sweep.
    jobs.par_iter()
        .map(|(body, v, requested, temperature)| {
            let map = body.get().pressure_map(*v).map_err(anyhow::Error::msg);
            let at = temperature
                .map(|t| format!(" at T = {t} °C"))
                .unwrap_or_default();
            map.and_then(|map| encode(&map, shape, *temperature, out, scene))
                .map(|(files, csv, picture)| MapOutput {
                    files,
                    csv,
                    picture,
                    speed: *v,
                    temperature: *temperature,
                    requested: *requested,
                })
                .with_context(|| {
                    format!(
                        "pressure map at v = {v:e} m/s{at} for scene file {}",
                        scene.display()
                    )
                })
        })
        .collect()
}

/// The files, CSV text and picture of one map.
fn encode(
    map: &PressureMap,
    shape: Shape,
    temperature: Option<f64>,
    out: &Path,
    scene: &Path,
) -> Result<(PressureMapFiles, PressureMapCsv, Picture)> {
    let files = PressureMapFiles::beside(out, map.speed, temperature);
    let csv = pressure_map::encode(map)?;
    let body = match shape {
        Shape::Sphere => "exact sphere",
        Shape::Cylinder => "exact cylinder",
    };
    let mut label = format!(
        "{}: {body}",
        scene
            .file_name()
            .map_or_else(String::new, |n| n.to_string_lossy().into_owned())
    );
    if let Some(t) = temperature {
        label += &format!(", T = {t} °C");
    }
    let picture =
        plot::render(&PressureMapFigure { map, label }).map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok((files, csv, picture))
}

/// Writes every map's four files, each atomically; returns one line per
/// map for the summary.
pub(super) fn write(maps: &[MapOutput]) -> Result<Vec<String>> {
    let mut lines = Vec::new();
    for map in maps {
        let f = &map.files;
        output::write_atomically(&f.pressure, &map.csv.pressure)?;
        output::write_atomically(&f.outline, &map.csv.outline)?;
        output::write_atomically(&f.png, &map.picture.png)?;
        output::write_atomically(&f.svg, map.picture.svg.as_bytes())?;
        let at = map
            .temperature
            .map(|t| format!(" at T = {t} °C"))
            .unwrap_or_default();
        let why = if map.requested {
            "--pressure-map"
        } else {
            "largest sampled exact μ"
        };
        lines.push(format!(
            "pressure map at v = {:e} m/s{at} ({why}): {}, {} and its picture .png/.svg",
            map.speed,
            f.pressure.display(),
            f.outline.display()
        ));
    }
    Ok(lines)
}
