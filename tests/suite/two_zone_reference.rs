//! The two-zone (solid + meniscus) Dugdale contact against an independent numerical solution:
//! `tests/data/two_zone_reference.csv`, made by `tests/reference/two_zone_reference.py` from
//! the equations alone (flat-punch superposition by 50-digit quadrature, re-solved with the
//! ring-load kernel), without the closed-form gaps tabor uses. Every row, including the ones
//! that reduce to MD (one zone absent, equal ranges), to 1e-6 as the issue asks; the figure
//! reached is printed.

use tabor::solver::two_zone::state_at_radius_dimensional;
use tabor::solver::Status;

#[test]
fn states_match_the_independent_reference() {
    let path = concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/two_zone_reference.csv"
    );
    let mut rd = csv::ReaderBuilder::new()
        .comment(Some(b'#'))
        .from_path(path)
        .expect("the reference table");
    let head = rd.headers().unwrap().clone();
    let col = |name: &str| head.iter().position(|h| h == name).unwrap();
    let names = [
        "k", "r", "s1", "h1", "s2", "h2", "a", "load", "approach", "c1", "c2",
    ];
    let idx: Vec<usize> = names.iter().map(|n| col(n)).collect();
    let mut rows = 0;
    let mut worst = 0.0f64;
    for rec in rd.records() {
        let rec = rec.unwrap();
        let v: Vec<f64> = idx
            .iter()
            .map(|&i| rec[i].trim().parse().unwrap())
            .collect();
        let (k, r, s1, h1, s2, h2, a) = (v[0], v[1], v[2], v[3], v[4], v[5], v[6]);
        let st = state_at_radius_dimensional(k, r, s1, h1, s2, h2, a)
            .unwrap_or_else(|e| panic!("row {rows}: {e:?}"));
        assert_eq!(st.status, Status::Ok, "row {rows}");
        // The load on the scale of the adhesive force and the approach on that of the ranges
        // (both cross zero), the radii relative.
        let w = s1 * h1 + s2 * h2;
        let scale_p = v[7].abs().max(std::f64::consts::PI * w * r);
        let errs = [
            (st.load - v[7]).abs() / scale_p,
            (st.approach - v[8]).abs() / v[8].abs().max(h1.max(h2)),
            (st.c1 - v[9]).abs() / v[9],
            (st.c2 - v[10]).abs() / v[10],
        ];
        for (e, what) in errs.iter().zip(["load", "approach", "c1", "c2"]) {
            assert!(
                *e < 1e-6,
                "row {rows} (s1 {s1} h1 {h1} s2 {s2} h2 {h2} a {a}): {what} off by {e:.2e}"
            );
            worst = worst.max(*e);
        }
        rows += 1;
    }
    assert!(rows >= 20, "{rows} rows");
    println!("two-zone states: {rows} rows, largest relative difference {worst:.2e}");
}
