use std::path::Path;

use rollfit_fit::{FitParams, Lambda, Method, ScaleAnchor, TermRule};
use rollfit_model::ContactSize;
use rollfit_model::modulus::Arrhenius;

use super::fit;
use super::forward::{ForwardSetup, ShiftApplied};
use super::setup::DEFAULT_POISSON;
use super::sweep::log_spaced;
use super::*;

const SLS: &str = r#"
[geometry]
shape = "sphere"
radius = 0.01
load = 0.15
[material]
model = "sls"
E0 = 1e6
E1 = 1e7
tau = 1
[sweep]
v_min = 1e-6
v_max = 1.0
count = 7
"#;

fn setup(text: &str) -> Result<ForwardSetup, crate::IoError> {
    parse(text)?.forward_setup(Path::new("scene.toml"), &|_| {})
}

#[test]
fn defaults_fill_optional_sections() {
    let s = setup(SLS).unwrap();
    assert_eq!(s.blocks[0].scene.substrate().poisson, 0.5);
    assert_eq!(s.blocks[0].scene.substrate().film_thickness, None);
    assert_eq!(s.blocks[0].scene.contact(), ContactSize::Dynamic);
    assert_eq!(s.speeds.len(), 7);
    assert_eq!(s.speeds[0], 1e-6);
    assert_eq!(s.speeds[6], 1.0);
    assert!((s.speeds[3] - 1e-3).abs() < 1e-15);
    assert!(s.blocks[0].shift.is_none());
    assert_eq!(s.blocks[0].scene.material().static_modulus(), 1e6);
}

#[test]
fn default_count_is_61() {
    let s = setup(&SLS.replace("count = 7\n", "")).unwrap();
    assert_eq!(s.speeds.len(), 61);
}

#[test]
fn prony_and_explicit_speeds() {
    let text = SLS
        .replace("model = \"sls\"\nE0 = 1e6\n", "model = \"prony\"\n")
        .replace("tau = 1", "H = [4e6, 5e6]\ntau = [0.1, 1.0]")
        .replace(
            "v_min = 1e-6\nv_max = 1.0\ncount = 7",
            "v = [1e-3, 2e-3, 1]",
        );
    let s = setup(&text).unwrap();
    assert_eq!(s.speeds, vec![1e-3, 2e-3, 1.0]);
    assert!((s.blocks[0].scene.material().static_modulus() - 1e6).abs() < 1e-6);
}

#[test]
fn fit_section_is_accepted() {
    for anchor in [
        "E0 = 2e6",
        "E_at = { omega = 1.0, E = 1.2e8 }",
        "contact_radius = { v = 1e-6, r = 1e-3 }",
    ] {
        let text =
            format!("{SLS}[fit]\n{anchor}\nE1_max = 1e10\nterms = \"auto\"\nmethod = \"lbfgs\"\n");
        let file = parse(&text).unwrap();
        assert_eq!(file.fit.unwrap().settings.terms, Some(TermRule::Auto));
    }
    let file = parse(&format!("{SLS}[fit]\nterms = 15\n")).unwrap();
    assert_eq!(file.fit.unwrap().settings.terms, Some(TermRule::Count(15)));
    assert!(parse(&format!("{SLS}[fit]\nterms = 0\n")).is_err());
    assert!(parse(&format!("{SLS}[fit]\nterms = \"many\"\n")).is_err());
}

#[test]
fn fit_section_gives_fit_params() {
    let text = format!(
        "{SLS}[fit]\nE_at = {{ omega = 2.0, E = 1.2e8 }}\nE1_max = 5e9\nterms_per_decade = 1.5\n\
         method = \"nelder-mead\"\nlambda = 0\nseed = 7\nstarts = 2\nmax_evaluations = 500\n\
         tolerance = 1e-5\n"
    );
    let (setup, params) = parse(&text).unwrap().fit_setup().unwrap();
    assert_eq!(setup.geometry.radius, 0.01);
    assert_eq!(setup.substrate.poisson, DEFAULT_POISSON);
    assert_eq!(
        params.anchor,
        Some(ScaleAnchor::ModulusAt {
            omega: 2.0,
            modulus: 1.2e8
        })
    );
    assert_eq!(params.e1_max, 5e9);
    assert_eq!(params.terms, TermRule::PerDecade(1.5));
    assert_eq!(params.method, Method::NelderMead);
    assert_eq!(params.lambda, Lambda::Fixed(0.0));
    assert_eq!((params.seed, params.starts), (7, 2));
    assert_eq!(params.max_evaluations, Some(500));
    assert_eq!(params.model_tolerance, 1e-5);
    // The scene's standard linear solid is the starting point.
    let start = params.start.clone().unwrap();
    assert_eq!((start.static_modulus, start.glassy_modulus), (1e6, 1e7));
    assert!(params.check(setup).is_ok());

    // Defaults, a Prony start (E0 = E1 - sum H) and explicit tau.
    let prony = SLS
        .replace("model = \"sls\"\nE0 = 1e6\n", "model = \"prony\"\n")
        .replace("tau = 1", "H = [4e6, 5e6]\ntau = [0.1, 1.0]");
    let (_, params) = parse(&format!(
        "{prony}[fit]\ntau = [1e-3, 1e-2, 1e-1]\nlambda = \"auto\"\n"
    ))
    .unwrap()
    .fit_setup()
    .unwrap();
    assert_eq!(params.terms, TermRule::Explicit(vec![1e-3, 1e-2, 1e-1]));
    assert_eq!(params.lambda, Lambda::Auto);
    assert_eq!(params.anchor, None);
    let start = params.start.unwrap();
    assert!((start.static_modulus - 1e6).abs() < 1e-6);
    let (_, params) = parse(SLS.split("[material]").next().unwrap())
        .unwrap()
        .fit_setup()
        .unwrap();
    assert_eq!(params, FitParams::default());
}

#[test]
fn fit_section_conflicts_are_named() {
    let err = |fit: &str| crate::chain(&parse(&format!("{SLS}[fit]\n{fit}\n")).unwrap_err());
    let m = err("E0 = 1e6\ncontact_radius = { v = 1e-6, r = 1e-3 }");
    assert!(
        m.contains("`E0`, `contact_radius`") && m.contains("at most one"),
        "{m}"
    );
    let m = err("terms = 10\ntau = [1.0, 2.0]");
    assert!(m.contains("`terms` and `tau`"), "{m}");
    assert!(err("lambda = -1").contains("lambda = -1"));
    assert!(err("lambda = \"big\"").contains("auto"));
    assert!(err("method = \"newton\"").contains("unknown method \"newton\""));
    assert!(err("seed = -1").contains("seed"));
    assert!(err("terms_per_decade = 0").contains("terms_per_decade = 0"));
    assert!(err("tau = [1.0, -2.0]").contains("tau[1] = -2"));
    assert!(err("bogus = 1").contains("unknown field `bogus`"));
}

#[test]
fn wlf_shift_is_applied() {
    let text = SLS.replace(
        "tau = 1\n",
        "tau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
    ) + "temperature = 40.0\n";
    let s = setup(&text).unwrap();
    let shift = s.blocks[0].shift.unwrap();
    let expected = -8.86 * 20.0 / (101.6 + 20.0);
    assert!((shift.log10_a_t - expected).abs() < 1e-12);
}

#[test]
fn temperature_list_gives_one_block_per_temperature() {
    let text = SLS.replace(
        "tau = 1\n",
        "tau = 1\n[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n",
    );
    let wlf = |t: f64| -8.86 * (t - 20.0) / (101.6 + t - 20.0);
    let s = setup(&format!("{text}temperature = [40.0, -20, 20.0]\n")).unwrap();
    assert_eq!(s.speeds.len(), 7);
    let shifts: Vec<ShiftApplied> = s.blocks.iter().map(|b| b.shift.unwrap()).collect();
    assert_eq!(
        shifts.iter().map(|s| s.temperature).collect::<Vec<_>>(),
        vec![40.0, -20.0, 20.0]
    );
    for shift in &shifts {
        assert!((shift.log10_a_t - wlf(shift.temperature)).abs() < 1e-12);
    }
    // The same shift as the single-temperature form.
    let one = setup(&format!("{text}temperature = -20.0\n")).unwrap();
    assert_eq!(one.blocks.len(), 1);
    assert_eq!(one.blocks[0].shift, Some(shifts[1]));

    let err =
        |list: &str| crate::chain(&parse(&format!("{text}temperature = {list}\n")).unwrap_err());
    assert!(err("[]").contains("[sweep]: `temperature = []`"));
    let m = err("[1.0, 2.0, 1.0]");
    assert!(
        m.contains("temperature[2] = 1 repeats temperature[0] = 1"),
        "{m}"
    );
    let m = err("[1.0, inf]");
    assert!(
        m.contains("[sweep] temperature[1]") && m.contains("finite"),
        "{m}"
    );
    let m = crate::chain(&parse(&format!("{SLS}temperature = [1.0]\n")).unwrap_err());
    assert!(
        m.contains("[sweep] temperature = [1]") && m.contains("[material.shift]"),
        "{m}"
    );
}

/// An Arrhenius `[material.shift]` gives the model's law; its keys
/// are checked like WLF's.
#[test]
fn arrhenius_shift() {
    let text = SLS.replace(
        "tau = 1\n",
        "tau = 1\n[material.shift]\nmodel = \"arrhenius\"\nT_ref = 20.0\nE_a = 1.5e5\n",
    );
    let s = setup(&format!("{text}temperature = 35.0\n")).unwrap();
    let law = Arrhenius::new(20.0, 1.5e5).unwrap();
    assert_eq!(
        s.blocks[0].shift.unwrap().log10_a_t,
        law.log10_shift(35.0).unwrap()
    );
    let m = crate::chain(&parse(&text.replace("E_a = 1.5e5", "C1 = 8.0")).unwrap_err());
    assert!(m.contains("do not belong to model \"arrhenius\""), "{m}");
    let m = crate::chain(&parse(&text.replace("E_a = 1.5e5", "E_a = -1.0")).unwrap_err());
    assert!(m.contains("E_a"), "{m}");
}

/// A WLF–Arrhenius `[material.shift]` gives WLF above T_g and Arrhenius's
/// slope below (against the model's two laws evaluated directly); missing
/// and foreign keys are named.
#[test]
fn wlf_arrhenius_shift() {
    let text = SLS.replace(
        "tau = 1\n",
        "tau = 1\n[material.shift]\nmodel = \"wlf-arrhenius\"\nT_ref = 20.0\nC1 = 8.86\n\
         C2 = 101.6\nT_g = -20.0\nE_a = 2e5\n",
    );
    let at = |t: f64| {
        setup(&format!("{text}temperature = {t:?}\n"))
            .unwrap()
            .blocks[0]
            .shift
            .unwrap()
            .log10_a_t
    };
    let wlf = rollfit_model::modulus::Wlf::new(20.0, 8.86, 101.6).unwrap();
    assert!((at(35.0) - wlf.log10_shift(35.0).unwrap()).abs() < 1e-12);
    let below = Arrhenius::new(-20.0, 2e5).unwrap();
    let expected = wlf.log10_shift(-20.0).unwrap() + below.log10_shift(-40.0).unwrap();
    assert!((at(-40.0) - expected).abs() < 1e-12);
    let m = crate::chain(&parse(&text.replace("T_g = -20.0\n", "")).unwrap_err());
    assert!(m.contains("needs the keys") && m.contains("T_g"), "{m}");
    let m =
        crate::chain(&parse(&text.replace("E_a = 2e5\n", "E_a = 2e5\nlog_aT = []\n")).unwrap_err());
    assert!(
        m.contains("does not belong to model \"wlf-arrhenius\""),
        "{m}"
    );
}

/// The keys of model = "dma" belong to it alone (`modulus` to "table"
/// as well), and a `[material.shift]` beside it is refused: the shift
/// comes from the isotherms. A missing file names itself.
#[test]
fn dma_material_keys() {
    let dma = "[geometry]\nshape = \"sphere\"\nradius = 0.01\nload = 0.15\n[material]\n\
               model = \"dma\"\nfile = \"absent.csv\"\n";
    let m = crate::chain(
        &setup(&format!("{dma}[sweep]\nv_min = 1e-6\nv_max = 1.0\n"))
            .err()
            .expect("a missing DMA file is an error"),
    );
    assert!(m.contains("absent.csv"), "{m}");
    let m = crate::chain(&parse(&format!("{dma}E1 = 1e7\n")).unwrap_err());
    assert!(m.contains("`E1` does not belong to model \"dma\""), "{m}");
    let m = crate::chain(
        &parse(&format!(
            "{dma}[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.0\nC2 = 100.0\n"
        ))
        .unwrap_err(),
    );
    assert!(m.contains("does not go with model = \"dma\""), "{m}");
    let m = crate::chain(&parse(&SLS.replace("tau = 1\n", "tau = 1\nT_ref = 20.0\n")).unwrap_err());
    assert!(
        m.contains("`T_ref` does not belong to model \"sls\"") && m.contains("\"dma\""),
        "{m}"
    );
    assert!(
        parse(&format!(
            "{dma}T_ref = 25.0\nmodulus = \"shear\"\nshift_law = \"free\"\nvertical = true\n"
        ))
        .is_ok()
    );
    // A [sweep] temperature needs no [material.shift] with "dma".
    assert!(
        parse(&format!(
            "{dma}[sweep]\nv_min = 1e-6\nv_max = 1.0\ntemperature = 30.0\n"
        ))
        .is_ok()
    );
}

const FREE_SHIFT: &str = "tau = 1\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n\
     log_aT = [{ T = 60.0, log_aT = -3.0 }, { T = 0.0, log_aT = 2.0 }]\n";

#[test]
fn free_shift_follows_the_model_rule() {
    let text = SLS.replace("tau = 1\n", FREE_SHIFT);
    let shift_at = |t: f64| {
        setup(&format!("{text}temperature = {t:?}\n")).map(|s| s.blocks[0].shift.unwrap().log10_a_t)
    };
    let model =
        rollfit_model::modulus::FreeShift::new(20.0, vec![(60.0, -3.0), (0.0, 2.0)]).unwrap();
    for t in [0.0, 5.0, 10.0, 20.0, 33.3, 40.0, 60.0] {
        assert_eq!(shift_at(t).unwrap(), model.log10_shift(t).unwrap(), "{t}");
    }
    // Exact at listed temperatures and T_ref, linear in T between them.
    assert_eq!(shift_at(0.0).unwrap(), 2.0);
    assert_eq!(shift_at(20.0).unwrap(), 0.0);
    assert_eq!(shift_at(60.0).unwrap(), -3.0);
    assert!((shift_at(10.0).unwrap() - 1.0).abs() < 1e-12);
    assert!((shift_at(40.0).unwrap() + 1.5).abs() < 1e-12);
    for t in [70.0, -0.5] {
        let err = crate::chain(&shift_at(t).unwrap_err());
        for fragment in [
            "[material.shift] at [sweep] temperature",
            &format!("T = {t} °C"),
            "outside",
            "0 to 60 °C",
            "`log_aT`",
        ] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
    }
}

#[test]
fn free_shift_entries_are_checked_by_the_model_and_named() {
    let err = |log_at: &str| {
        let text = SLS.replace(
            "tau = 1\n",
            &format!("tau = 1\n[material.shift]\nmodel = \"free\"\nT_ref = 20.0\n{log_at}"),
        );
        crate::chain(&parse(&text).unwrap_err())
    };
    let msg = err("log_aT = [{ T = 0.0, log_aT = 2.0 }, { T = 0.0, log_aT = 2.5 }]\n");
    assert!(
        msg.contains("[material.shift]") && msg.contains("`log_aT`: free shift: entry 1"),
        "{msg}"
    );
    assert!(msg.contains("listed before as entry 0"), "{msg}");
    let msg = err("log_aT = [{ T = 20.0, log_aT = 0.5 }]\n");
    assert!(
        msg.contains("`log_aT`") && msg.contains("reference temperature"),
        "{msg}"
    );
    let msg = err("log_aT = []\n");
    assert!(
        msg.contains("`log_aT`") && msg.contains("no temperatures"),
        "{msg}"
    );
    let msg = err("");
    assert!(msg.contains("needs the key `log_aT`"), "{msg}");
    let msg = err("log_aT = [{ T = 0.0, log_aT = 2.0 }]\nC1 = 8.86\n");
    assert!(
        msg.contains("`C1`, `C2`, `T_g` and `E_a` do not belong"),
        "{msg}"
    );
}

#[test]
fn havriliak_negami_and_its_alias() {
    let hn =
        "model = \"havriliak-negami\"\nE0 = 1e6\nE1 = 1e9\ntau = 1e-3\nalpha = 0.5\nbeta = 0.4";
    let text = SLS.replace("model = \"sls\"\nE0 = 1e6\nE1 = 1e7\ntau = 1", hn);
    let s = setup(&text).unwrap();
    assert_eq!(s.blocks[0].scene.material().static_modulus(), 1e6);
    assert_eq!(s.blocks[0].scene.material().loss_exponent_at_zero(), 0.5);
    let alias = setup(&text.replace("\"havriliak-negami\"", "\"hn\"")).unwrap();
    assert_eq!(
        alias.blocks[0].scene.material().modulus(3.0),
        s.blocks[0].scene.material().modulus(3.0)
    );
    let err = crate::chain(&parse(&text.replace("alpha = 0.5\n", "")).unwrap_err());
    assert!(err.contains("needs the key `alpha`"), "{err}");
}

#[test]
fn log_spacing_is_exact_at_the_ends_and_increasing() {
    let v = log_spaced(1e-8, 10.0, 91);
    assert_eq!(v.len(), 91);
    assert_eq!((v[0], v[90]), (1e-8, 10.0));
    assert!(v.windows(2).all(|w| w[0] < w[1]));
    assert!((v[10] / 1e-7 - 1.0).abs() < 1e-13);
}

#[test]
fn non_finite_numbers_are_reported_with_position() {
    let err = crate::chain(&parse(&SLS.replace("radius = 0.01", "radius = nan")).unwrap_err());
    assert!(
        err.contains("line 4") && err.contains("radius") && err.contains("finite"),
        "{err}"
    );
    let err = crate::chain(&parse(&SLS.replace("tau = 1", "tau = -inf")).unwrap_err());
    assert!(err.contains("tau") && err.contains("finite"), "{err}");
}

/// `[fit]` knows the anchors and exactly the keys of the fit library's
/// one parser of settings.
#[test]
fn fit_keys_are_the_anchors_and_the_setting_keys() {
    let mut settings: Vec<&str> = fit::FIT_KEYS[3..].to_vec();
    let mut known = rollfit_fit::settings::SETTING_KEYS.to_vec();
    settings.sort_unstable();
    known.sort_unstable();
    assert_eq!(settings, known);
    assert_eq!(fit::FIT_KEYS[..3], ["E0", "E_at", "contact_radius"]);
}

/// The canonical spelling, the alias and a string for a number are one
/// setting; a bad value of a setting names `[fit]`, the key and its line.
#[test]
fn fit_settings_are_read_by_the_one_parser() {
    let settings = |fit: &str| {
        parse(&format!("{SLS}[fit]\n{fit}\n"))
            .map(|file| file.fit.unwrap().settings)
            .map_err(|e| crate::chain(&e))
    };
    let canonical = settings("terms = \"1.5/decade\"\nseed = 4").unwrap();
    assert_eq!(canonical.terms, Some(TermRule::PerDecade(1.5)));
    assert_eq!(canonical.seed, Some(4));
    let alias = settings("terms_per_decade = 1.5\nseed = \"4\"").unwrap();
    let params = |settings: &rollfit_fit::FitSettings| {
        let mut params = FitParams::default();
        settings.apply(&mut params);
        params
    };
    assert_eq!(params(&alias), params(&canonical));
    let line = SLS.lines().count() + 2;
    for (fit, key) in [
        ("starts = 0", "starts"),
        ("shift = \"sideways\"", "shift"),
        ("cross_check = \"yes\"", "cross_check"),
        ("terms = 2.5", "terms"),
        ("physics = \"exakt\"", "physics"),
        ("physics = 1", "physics"),
    ] {
        let err = settings(fit).unwrap_err();
        for fragment in ["[fit]", &format!("`{key}`"), &format!("line {line}")] {
            assert!(err.contains(fragment), "{fragment:?} in {err}");
        }
    }
}

/// A temperature set's law is "auto" unless the scene says
/// otherwise: `[material.shift]` gives its model as the law (its T_ref, and
/// for WLF its constants as the start), and `[fit] shift` overrides both.
#[test]
fn the_fit_law_is_auto_unless_the_scene_names_one() {
    let kind = |text: &str| parse(text).unwrap().fit_setup().unwrap().1.shift.kind;
    assert_eq!(kind(SLS), rollfit_fit::ShiftKind::Auto);
    let arrhenius =
        format!("{SLS}[material.shift]\nmodel = \"arrhenius\"\nT_ref = 20.0\nE_a = 1.5e5\n");
    assert_eq!(kind(&arrhenius), rollfit_fit::ShiftKind::Arrhenius);
    let wlf =
        format!("{SLS}[material.shift]\nmodel = \"wlf\"\nT_ref = 20.0\nC1 = 8.86\nC2 = 101.6\n");
    assert_eq!(kind(&wlf), rollfit_fit::ShiftKind::Wlf);
    let overridden = format!("{wlf}[fit]\nshift = \"auto\"\n");
    assert_eq!(kind(&overridden), rollfit_fit::ShiftKind::Auto);
}

/// `[fit] dma` is kept as written and resolved against the scene's folder;
/// the joint settings are fit settings of `[fit]`.
#[test]
fn fit_dma_is_relative_to_the_scene_folder() {
    let file = parse(&format!(
        "{SLS}[fit]\ndma = \"dma/iso.csv\"\ndma_sigma = 0.01\nfriction_factor = \"free\"\n"
    ))
    .unwrap();
    assert_eq!(
        file.dma_file(Path::new("scenes")),
        Some(Path::new("scenes").join("dma/iso.csv"))
    );
    let (_, params) = file.fit_setup().unwrap();
    assert_eq!(params.dma_sigma, Some(0.01));
    assert_eq!(params.friction_factor, rollfit_fit::FrictionFactor::Free);
    assert_eq!(parse(SLS).unwrap().dma_file(Path::new("scenes")), None);
    let err = crate::chain(&parse(&format!("{SLS}[fit]\ndma_sigma = 2\n")).unwrap_err());
    assert!(
        err.contains("`dma_sigma`") && err.contains("line 16"),
        "{err}"
    );
}
