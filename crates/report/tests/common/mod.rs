//! Helpers shared by the picture tests: decoding a rendered PNG and
//! counting its pixels.
#![allow(dead_code)]

use plotters::style::RGBColor;
use rollfit_report::plot::Picture;

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
