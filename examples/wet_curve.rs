//! Writes one synthetic AFM force curve (CSV: segment, height_m, force_n) from the two-zone law
//! (the solid's Dugdale zone plus the water meniscus of a humidity) under a cantilever spring:
//! the input of the README's humid fit and of the Python test of the two-zone shape fit.
//!
//! cargo run --release --example wet_curve -- OUT.csv [relative humidity: 0.7]
//!     [contact angle, degrees: 10] [solid w, J/m^2: 0.03] [solid lambda: 0.5] [noise, N: 0]
//!
//! The tip: R = 20 nm, E* = 1.5 GPa, a 2 N/m cantilever, 400 points a segment.
use tabor::fit::synthetic::{try_synthetic_wet, Synthetic};
use tabor::fit::{Model, Params};
use tabor::scene::humidity::HumidityInput;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .expect("usage: wet_curve OUT.csv [rh] [angle] [w] [lambda] [noise]");
    let num = |i: usize, default: f64| {
        args.get(i)
            .map_or(default, |s| s.parse().expect("a number"))
    };
    let humidity = HumidityInput::water(num(1, 0.7), num(2, 10.0));
    let meniscus = humidity
        .stress_and_range()
        .expect("a meniscus: a humidity in (0, 1) and a contact angle below 90 degrees");
    let s = Synthetic {
        model: Model::SolidAndMeniscus,
        params: Params {
            e_star: 1.5e9,
            w: num(3, 0.03),
            lambda: num(4, 0.5),
            zc: 40e-9,
            f0: 0.0,
        },
        radius: 20e-9,
        spring: 2.0,
        points: 400,
        depth: 6.0,
        noise: num(5, 0.0),
        seed: 3,
    };
    let c = try_synthetic_wet(&s, meniscus).unwrap_or_else(|e| panic!("{e}"));
    let mut w = csv::Writer::from_path(out).expect("writable output");
    w.write_record(["segment", "height_m", "force_n"]).unwrap();
    for k in 0..c.len() {
        w.write_record([
            c.segment[k].name().to_string(),
            format!("{:e}", c.height[k]),
            format!("{:e}", c.force[k]),
        ])
        .unwrap();
    }
    w.flush().unwrap();
}
