//! Figures: plotters draws axes, log ticks, labels and legends with an embedded font (identical
//! output on every machine); the map raster is coloured here and placed as one bitmap.

pub mod map;
pub mod plots;

use std::sync::Once;

/// Registers the embedded DejaVu Sans as "sans-serif" (no system fonts are used).
pub fn fonts() {
    static ONCE: Once = Once::new();
    ONCE.call_once(|| {
        let bytes: &'static [u8] = include_bytes!("../../assets/fonts/DejaVuSans.ttf");
        let _ =
            plotters::style::register_font("sans-serif", plotters::style::FontStyle::Normal, bytes);
    });
}

/// "1e-3"-style tick labels for log axes: 0.001 .. 1000 as plain numbers, beyond as powers.
pub fn log_label(v: f64) -> String {
    if v <= 0.0 || !v.is_finite() {
        return String::new();
    }
    let e = v.log10();
    if (e - e.round()).abs() > 1e-6 {
        return String::new();
    }
    let e = e.round() as i32;
    if (-2..=3).contains(&e) {
        // From the exponent: 10^-2 is not exactly 0.01 in binary.
        format!("{}", 10f64.powi(e))
    } else {
        format!("1e{e}")
    }
}

/// Encodes an RGB buffer as PNG (deterministic: same pixels, same bytes).
pub fn png_bytes(rgb: &[u8], w: u32, h: u32) -> Result<Vec<u8>, image::ImageError> {
    use image::ImageEncoder;
    let mut out = Vec::new();
    image::codecs::png::PngEncoder::new(&mut out).write_image(
        rgb,
        w,
        h,
        image::ExtendedColorType::Rgb8,
    )?;
    Ok(out)
}
