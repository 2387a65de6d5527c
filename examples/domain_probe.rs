//! Where the exact f64 solver stops: every row of an oracle table
//! (`tests/reference/md_oracle.py`) solved with the domain check bypassed, and per lambda the
//! worst error over the accuracy bound (1e-12, plus 1e-15/sqrt(Pbar - Pbar_c) within 1e-6 of
//! the pull-off). A ratio above 1, a status other than ok or a failed context is where the
//! certified domain must end.
//!
//! `python3 tests/reference/md_oracle.py -24 24 2 > wide.csv`
//! `cargo run --release --example domain_probe -- wide.csv`

use tabor::solver::{LambdaContext, Status};

fn rel(x: f64, r: f64) -> f64 {
    if x == r {
        0.0
    } else {
        ((x - r) / r).abs()
    }
}

fn main() {
    let path = std::env::args()
        .nth(1)
        .expect("usage: domain_probe TABLE.csv");
    let mut rdr = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(&path)
        .expect("table");
    let rows: Vec<csv::StringRecord> = rdr.records().map(|r| r.expect("row")).collect();
    let f = |r: &csv::StringRecord, i: usize| -> f64 { r[i].parse().expect("number") };
    let mut lambdas: Vec<f64> = rows.iter().map(|r| f(r, 0)).collect();
    lambdas.dedup();
    println!("lambda,pulloff_load_P,pulloff_load_A,pulloff_disp,worst_state_over_bound,failures");
    for &lambda in &lambdas {
        let ctx = match LambdaContext::new_uncertified(lambda) {
            Ok(c) => c,
            Err(e) => {
                println!("{lambda:e},,,,context: {e}");
                continue;
            }
        };
        let pc = ctx.load_pulloff.load;
        let (mut wl, mut wa, mut wd, mut ws, mut fails) = (0f64, 0f64, 0f64, 0f64, 0);
        for r in rows.iter().filter(|r| f(r, 0) == lambda) {
            let (a, p, d) = (f(r, 2), f(r, 3), f(r, 4));
            match &r[1] {
                "pulloff_load" => {
                    let lp = ctx.load_pulloff;
                    (wl, wa) = (rel(lp.load, p), rel(lp.a, a));
                }
                "pulloff_displacement" => {
                    let dp = ctx.disp_pulloff();
                    let ea = if a == 0.0 { dp.a } else { rel(dp.a, a) };
                    wd = wd.max(rel(dp.load, p)).max(ea);
                }
                _ => {
                    let m1 = f(r, 5);
                    let s = ctx.solve_load(p);
                    if s.status != Status::Ok {
                        eprintln!("lambda {lambda:e} load {p:e}: {}", s.status.name());
                        fails += 1;
                        continue;
                    }
                    let gap = p - pc;
                    let tol = if gap >= 1e-6 {
                        1e-12
                    } else {
                        1e-12 + 1e-15 / gap.max(1e-300).sqrt()
                    };
                    let e = rel(s.a, a)
                        .max(rel(s.m_minus_1, m1))
                        .max((s.approach - d).abs() / d.abs().max(1.0));
                    ws = ws.max(e / tol);
                }
            }
        }
        println!("{lambda:e},{wl:.2e},{wa:.2e},{wd:.2e},{ws:.3},{fails}");
    }
}
