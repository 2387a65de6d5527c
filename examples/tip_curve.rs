//! Writes one synthetic AFM force curve (CSV: segment, height_m, force_n) of Maugis-Dugdale on
//! a tip that is not a sphere (docs/PHYSICS.md section 12) under a cantilever spring: the input
//! of the guide's fit with `--tip` and of the Python test of tip fits.
//!
//! cargo run --release --example tip_curve -- OUT.csv [tip: cone:65] [E*, Pa: 1e6]
//!     [w, J/m^2: 0.02] [lambda: 1] [spring, N/m: 0.5] [noise, N: 0]
//!
//! The tip as `tabor fit --tip` takes it; 300 points a segment, the contact point at 300 nm.
use tabor::fit::synthetic::{try_synthetic_on, Synthetic};
use tabor::fit::{Geometry, Model, Params};
use tabor::physics::tip::TipInput;

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let usage = "usage: tip_curve OUT.csv [tip] [E*] [w] [lambda] [spring] [noise]";
    let out = args.first().expect(usage);
    let num = |i: usize, default: f64| {
        args.get(i)
            .map_or(default, |s| s.parse().expect("a number"))
    };
    let tip: TipInput = args
        .get(1)
        .map_or("cone:65", |s| s.as_str())
        .parse()
        .unwrap_or_else(|e| panic!("{e}"));
    let geometry = Geometry::of(&tip).unwrap_or_else(|e| panic!("{e}"));
    let s = Synthetic {
        model: Model::Md,
        params: Params {
            e_star: num(2, 1e6),
            w: num(3, 0.02),
            lambda: num(4, 1.0),
            zc: 300e-9,
            f0: 0.0,
        },
        radius: f64::NAN,
        spring: num(5, 0.5),
        points: 300,
        depth: 6.0,
        noise: num(6, 0.0),
        seed: 5,
    };
    let c = try_synthetic_on(&s, geometry).unwrap_or_else(|e| panic!("{e}"));
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
