//! Helpers of the report crate's tests that need its types (the shared
//! fixtures are rollfit-testkit's): decoding a rendered PNG and counting
//! its pixels; the committed example fits under examples/fits/ and their
//! scenes under data/, read as any user's would be.

use plotters::style::RGBColor;
use rollfit_io::FitDir;
use rollfit_report::fitted_friction::{FittedLine, RollingScene};
use rollfit_report::plot::Picture;
pub use rollfit_testkit::files::{TempDir, workspace};
pub use rollfit_testkit::run::assert_contains;

/// The committed fit examples/fits/`name`.
pub fn committed_fit(name: &str) -> FitDir {
    FitDir::read(&workspace().join("examples/fits").join(name)).expect("the committed fit reads")
}

/// What the fitted μ(v) needs of the scene data/`name`.toml.
pub fn scene(name: &str) -> RollingScene {
    let path = workspace().join("data").join(format!("{name}.toml"));
    let (setup, params) = rollfit_io::scene::load(&path)
        .and_then(|s| s.fit_setup())
        .expect("the example scene reads");
    RollingScene::new(setup, &params)
}

/// The dense fitted line of the committed fit `name` under its own scene
/// (the fit and the scene share the name).
pub fn dense_line(fit: &FitDir, name: &str) -> FittedLine {
    let line = FittedLine::of(fit, &scene(name));
    assert!(matches!(line, FittedLine::Dense(_)), "{line:?}");
    line
}

/// A decoded RGB image.
pub struct Decoded {
    pub width: u32,
    pub height: u32,
    pub rgb: Vec<u8>,
}

/// Decodes a picture's PNG, which must be 8-bit RGB.
pub fn decode(p: &Picture) -> Decoded {
    let decoder = png::Decoder::new(p.png.as_slice());
    let mut reader = decoder.read_info().expect("a PNG header");
    let mut rgb = vec![0; reader.output_buffer_size()];
    let info = reader.next_frame(&mut rgb).expect("PNG image data");
    assert_eq!(info.color_type, png::ColorType::Rgb, "{}", p.name);
    rgb.truncate(info.buffer_size());
    Decoded {
        width: info.width,
        height: info.height,
        rgb,
    }
}

/// Pixels of exactly this colour.
pub fn count(image: &Decoded, c: RGBColor) -> usize {
    image
        .rgb
        .chunks_exact(3)
        .filter(|px| px[0] == c.0 && px[1] == c.1 && px[2] == c.2)
        .count()
}

/// μ of the fit's master curve under `scene` at the scene's own load, at
/// speed `v` (m/s), computed alone.
pub fn model(scene: &RollingScene, fit: &FitDir, v: f64) -> f64 {
    let s = scene.setup;
    rollfit_model::Scene::new(s.geometry, s.substrate, s.contact, fit.master_curve.clone())
        .and_then(|m| m.with_tolerance(scene.tolerance))
        .and_then(|m| m.friction_sweep(&[v]))
        .unwrap()[0]
}
