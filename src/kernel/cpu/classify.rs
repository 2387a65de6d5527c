//! The CPU mirror of `shaders/classify.wgsl`: a solved grid point's region and adequate models
//! as one byte, in f64 on the f32 state, as the kernel computes them. Read it side by side with
//! the shader.

use crate::kernel::layout::{ClassifyParams, Out};

/// The kernel's parameters for a tolerance.
pub fn params(tol: f64) -> ClassifyParams {
    ClassifyParams {
        cube_lo: (1.0 - tol).powi(3),
        cube_hi: (1.0 + tol).powi(3),
        tol,
        nx: 0,
        offset: 0,
        count: 0,
        picks: 0,
        marks_words: 0,
        _pad: 0,
    }
}

/// The byte of one result `o` at `lambda` and load `p`: the region in bits 0-2 (`map::Region`
/// as u8) and the adequate models in bits 3-6 (Hertz, rigid, DMT, JKR).
pub fn mark(o: &Out, lambda: f64, p: f64, c: &ClassifyParams) -> u8 {
    let status = o.code & 0xff;
    if status == 1 {
        return 0;
    }
    if status != 0 {
        return 6;
    }
    let (a, approach) = (o.a as f64, o.other as f64);
    let a3 = a * a * a;
    let lo = c.cube_lo * a3;
    let hi = c.cube_hi * a3;
    let within = |m3: f64| m3 >= lo && m3 <= hi;
    let mut bits = 0u8;
    if p >= 0.0 && p >= lo && p <= hi {
        bits |= 1;
    }
    if std::f64::consts::FRAC_PI_2 * lambda * (a * a).max(approach.abs()) <= c.tol {
        bits |= 2;
    }
    if within(p + 2.0) {
        bits |= 4;
    }
    if p >= -1.5 && within(p + 3.0 + (9.0 + 6.0 * p).max(0.0).sqrt()) {
        bits |= 8;
    }
    let region = if bits != 0 {
        bits.trailing_zeros() as u8 + 1
    } else {
        5
    };
    region | (bits << 3)
}
