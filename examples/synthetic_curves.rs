//! Writes synthetic AFM force curves (CSV: curve, segment, height_m, force_n) from the exact
//! Maugis-Dugdale path under a cantilever spring, with Gaussian force noise: the input of the
//! fitting example in the README and of the force-map benchmark.
//!
//! cargo run --release --example synthetic_curves -- OUT.csv [curves] [points per segment]
//!     [spring constant, N/m: 2] [force noise, N: 5e-11]
use tabor::fit::synthetic::{map_curve, synthetic};

fn main() {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let out = args
        .first()
        .expect("usage: synthetic_curves OUT.csv [curves] [points]");
    let curves: usize = args.get(1).map_or(1, |s| s.parse().expect("curves"));
    let points: usize = args.get(2).map_or(500, |s| s.parse().expect("points"));
    let spring: f64 = args
        .get(3)
        .map_or(2.0, |s| s.parse().expect("spring constant"));
    let noise: f64 = args.get(4).map_or(5e-11, |s| s.parse().expect("noise"));
    let side = (curves as f64).sqrt().ceil() as usize;
    let mut w = csv::Writer::from_path(out).expect("writable output");
    w.write_record(["x", "y", "segment", "height_m", "force_n"])
        .unwrap();
    for i in 0..curves {
        let c = synthetic(&map_curve(i, curves, points, spring, noise));
        for k in 0..c.len() {
            w.write_record([
                (i % side).to_string(),
                (i / side).to_string(),
                c.segment[k].name().to_string(),
                format!("{:.9e}", c.height[k]),
                format!("{:.9e}", c.force[k]),
            ])
            .unwrap();
        }
    }
    w.flush().unwrap();
}
