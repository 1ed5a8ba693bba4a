//! The pictures `rollfit master` writes (drawn by `rollfit_report::plot`):
//! - frequency sweeps: master.png/.svg, the shifted isotherms with the
//!   Prony series, tan δ and the shift factors, and vgp.png/.svg, the van
//!   Gurp–Palmen plot (δ against |E*| of the isotherms as measured, the
//!   test of superposition that needs no shift);
//! - relaxation isotherms: master.png/.svg, E(t/a_T) with the series, each
//!   point's misfit and the shift factors.
//!
//! Each names the shift law and its constants in the shift panel's legend
//! and carries a verdict that is not "good" in its title. Shear data are
//! drawn as the file's G′, G″ (or G(t)): the Young's moduli of the master
//! curve divided by 2(1+ν), the conversion the reader applied.

use anyhow::Result;
use rollfit_fit::master::quality::MasterQuality;
use rollfit_fit::master::relaxation::TimeQuantity;
use rollfit_fit::master::{ShiftFactors, ShiftLaw};
use rollfit_io::dma::ModulusKind;
use rollfit_report::master_input::frequency::DmaMaster;
use rollfit_report::master_input::time::RelaxationBuilt;
use rollfit_report::plot::dma_master::{
    DmaMasterFigure, MasterCurveFit, ShiftMarker, ShiftedPoint, Verdict,
};
use rollfit_report::plot::relaxation_master::{RelaxationMasterFigure, ShiftedRelaxation};
use rollfit_report::plot::shift_panel::law_legend;
use rollfit_report::plot::van_gurp_palmen::{MeasuredPoint, VanGurpPalmenFigure};
use rollfit_report::plot::{Figure, render};

/// Samples of the law's curve over the measured temperatures.
const LAW_SAMPLES: usize = 100;

/// The files of one picture: `<stem>.png` and `<stem>.svg`.
type PictureFiles = [(&'static str, Vec<u8>); 2];

/// The symbol the pictures use and the factor from the master curve's
/// Young's moduli to the file's: ("G", 1/(2(1+ν))) for shear data.
fn drawn_modulus(kind: ModulusKind, poisson: f64) -> (&'static str, f64) {
    match kind {
        ModulusKind::Young => ("E", 1.0),
        ModulusKind::Shear => ("G", 1.0 / (2.0 * (1.0 + poisson))),
    }
}

/// What the shift panel draws, of `shift`.
struct ShiftParts {
    markers: Vec<ShiftMarker>,
    curve: Vec<(f64, f64)>,
    law: Vec<String>,
}

impl ShiftParts {
    /// The markers, the law's curve and its legend; nothing for a single
    /// isotherm.
    fn of(shift: &ShiftFactors) -> ShiftParts {
        if shift.shifts.len() < 2 {
            return ShiftParts {
                markers: Vec::new(),
                curve: Vec::new(),
                law: Vec::new(),
            };
        }
        let markers = shift
            .shifts
            .iter()
            .map(|s| ShiftMarker {
                temperature: s.temperature,
                log_shift: s.log_shift_measured.unwrap_or(s.log_shift),
                sigma: s.log_shift_measured_sigma,
                determined: s.log_shift_measured.is_some(),
            })
            .collect();
        ShiftParts {
            markers,
            curve: law_curve(shift),
            law: law_legend(shift),
        }
    }
}

/// The applied law over the measured temperatures: WLF, Arrhenius,
/// WLF–Arrhenius, or the free shifts linear between isotherms.
fn law_curve(shift: &ShiftFactors) -> Vec<(f64, f64)> {
    if shift.law == ShiftLaw::Auto {
        return Vec::new();
    }
    let (lo, hi) = (
        shift.shifts[0].temperature,
        shift.shifts[shift.shifts.len() - 1].temperature,
    );
    (0..=LAW_SAMPLES)
        .filter_map(|j| {
            let t = lo + (hi - lo) * j as f64 / LAW_SAMPLES as f64;
            shift.law_at(t).map(|l| (t, l))
        })
        .collect()
}

/// The verdict as the pictures take it.
fn verdict(quality: &MasterQuality) -> Verdict<'_> {
    Verdict {
        verdict: quality.verdict,
        reasons: &quality.reasons,
    }
}

/// `figure` rendered, as its two files.
fn files(figure: &impl Figure, png: &'static str, svg: &'static str) -> Result<PictureFiles> {
    let picture = render(figure).map_err(|e| anyhow::anyhow!("{e}"))?;
    Ok([(png, picture.png), (svg, picture.svg.into_bytes())])
}

/// master.png/.svg and vgp.png/.svg of a frequency-sweep master curve;
/// `curve` is the series (ω, E′, E″) as modulus.csv holds it.
pub(super) fn frequency(
    built: &DmaMaster,
    curve: &[(f64, f64, f64)],
    poisson: f64,
    quality: &MasterQuality,
) -> Result<Vec<(&'static str, Vec<u8>)>> {
    let master = &built.master;
    let (symbol, scale) = drawn_modulus(built.data.kind, poisson);
    let points: Vec<ShiftedPoint> = master
        .points
        .iter()
        .map(|p| ShiftedPoint {
            reduced_omega: p.reduced_omega,
            storage: p.storage * scale,
            loss: p.loss * scale,
            temperature: p.temperature,
        })
        .collect();
    let fit = MasterCurveFit {
        omega: curve.iter().map(|c| c.0).collect(),
        storage: curve.iter().map(|c| c.1 * scale).collect(),
        loss: curve.iter().map(|c| c.2 * scale).collect(),
    };
    let shift = ShiftParts::of(&master.shift);
    let t_ref = built.settings.t_ref();
    let master_files = files(
        &DmaMasterFigure {
            points: &points,
            fit: &fit,
            t_ref,
            shifts: &shift.markers,
            shift_curve: &shift.curve,
            shift_law: &shift.law,
            modulus_symbol: symbol,
            verdict: Some(verdict(quality)),
        },
        "master.png",
        "master.svg",
    )?;
    // As measured: the vertical factor b_T the master points were divided
    // by is undone, so that no shift of any kind enters.
    let vertical = |t: f64| {
        master
            .shift
            .shifts
            .iter()
            .find(|s| s.temperature == t)
            .map_or(1.0, |s| 10f64.powf(s.log_vertical))
    };
    let measured: Vec<MeasuredPoint> = points
        .iter()
        .map(|p| {
            let b = vertical(p.temperature);
            MeasuredPoint {
                storage: p.storage * b,
                loss: p.loss * b,
                temperature: p.temperature,
            }
        })
        .collect();
    let vgp_files = files(
        &VanGurpPalmenFigure {
            points: &measured,
            fit: &fit,
            t_ref,
            modulus_symbol: symbol,
        },
        "vgp.png",
        "vgp.svg",
    )?;
    Ok(master_files.into_iter().chain(vgp_files).collect())
}

/// master.png/.svg of a relaxation or creep master curve; `grid` is the
/// reduced times relaxation.csv holds the series at. A creep curve is
/// drawn as the compliance the file held: D, or J = 2(1+ν) D.
pub(super) fn relaxation(
    built: &RelaxationBuilt,
    grid: &[f64],
    poisson: f64,
    quality: &MasterQuality,
) -> Result<PictureFiles> {
    let master = &built.master;
    let creep = master.quantity == TimeQuantity::Creep;
    let series_at = master.quantity.of_series(&master.fit.prony);
    let (symbol, scale) = match (drawn_modulus(built.data.kind, poisson), creep) {
        ((symbol, scale), false) => (symbol, scale),
        (("E", _), true) => ("D", 1.0),
        ((_, scale), true) => ("J", 1.0 / scale),
    };
    let points: Vec<ShiftedRelaxation> = master
        .points
        .iter()
        .map(|p| ShiftedRelaxation {
            reduced_time: p.reduced_time,
            modulus: p.value * scale,
            fitted: series_at(p.reduced_time) * scale,
            temperature: p.temperature,
        })
        .collect();
    let series: Vec<(f64, f64)> = grid.iter().map(|&t| (t, series_at(t) * scale)).collect();
    let shift = ShiftParts::of(&master.shift);
    files(
        &RelaxationMasterFigure {
            points: &points,
            series: &series,
            t_ref: built.settings.t_ref(),
            shifts: &shift.markers,
            shift_curve: &shift.curve,
            shift_law: &shift.law,
            modulus_symbol: symbol,
            creep,
            verdict: Some(verdict(quality)),
        },
        "master.png",
        "master.svg",
    )
}
