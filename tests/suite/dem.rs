//! The DEM force-overlap law (`tabor::dem`): its table against exact solves, its stiffness
//! against differences, its history against the rigid-grip cycle of `tabor cycle`, its limits
//! (JKR, DMT), and an independent reference written from the equations alone
//! (tests/data/dem_reference.py).

use tabor::dem::{Branch, DemLaw};

const LAMBDAS: [f64; 13] = [
    0.01, 0.1, 0.5, 0.8, 0.9, 0.93, 0.94, 1.0, 3.0, 10.0, 100.0, 1e3, 1e4,
];

#[test]
fn the_table_is_the_exact_branch_within_its_target() {
    for &lambda in &LAMBDAS {
        let law = DemLaw::new(lambda, 50.0).unwrap();
        assert!(law.error <= 1e-6, "lambda {lambda}: {}", law.error);
        // Off the nodes and midpoints: 997 overlaps spread over the branch, denser at the fold.
        let mut worst = 0.0f64;
        for k in 0..997 {
            let t = (k as f64 + 0.3137) / 997.0;
            let d = law.delta_out + (50.0 - law.delta_out) * t * t * t;
            let want = law.exact(Branch::Contact, d).unwrap();
            let got = law.contact_branch(d).0;
            worst = worst.max((got - want).abs() / law.load_pulloff.abs().max(want.abs()));
        }
        println!(
            "lambda {lambda}: step {}, {} nodes, reported {:.2e}, measured off the nodes {worst:.2e}",
            law.step, law.nodes, law.error
        );
        assert!(worst <= 2e-6, "lambda {lambda}: {worst}");
    }
}

#[test]
fn the_stiffness_is_the_slope_of_the_exact_branches() {
    for &lambda in &LAMBDAS {
        let law = DemLaw::new(lambda, 50.0).unwrap();
        let scale = law.load_pulloff.abs();
        for &d in &[
            law.delta_out + 0.05,
            law.delta_in.max(law.delta_out) + 0.3,
            2.0,
            20.0,
        ] {
            let h = 1e-5 * (1.0 + d.abs());
            let f = |x: f64| law.exact(Branch::Contact, x).unwrap();
            let fd = (f(d + h) - f(d - h)) / (2.0 * h);
            let k = law.contact_branch(d).1;
            assert!(
                (k - fd).abs() <= 1e-4 * fd.abs().max(scale),
                "lambda {lambda}, contact at {d}: {k} against {fd}"
            );
        }
        if let Some(nc) = law.delta_nc {
            let d = 0.5 * (nc - law.h0);
            // The branch's root c*^2 + 2 (d + h0) is c*^2 / 2 there: a step well inside it.
            let h = 1e-4 * (d - nc);
            let f = |x: f64| law.non_contact_branch(x).0;
            let fd = (f(d + h) - f(d - h)) / (2.0 * h);
            let k = law.non_contact_branch(d).1;
            assert!(
                (k - fd).abs() <= 1e-6 * fd.abs().max(scale),
                "lambda {lambda}, non-contact at {d}: {k} against {fd}"
            );
        }
    }
}

#[test]
fn the_loop_is_the_rigid_grip_cycle_of_tabor_cycle() {
    for &lambda in &[0.1, 0.5, 1.0, 3.0, 10.0] {
        let law = DemLaw::new(lambda, 50.0).unwrap();
        let c = tabor::cycle(lambda, tabor::Drive::RigidGrips, 2.0).unwrap();
        let dmax = tabor::solve_one(lambda, 2.0, tabor::Control::Load).approach;
        let area = law.loop_area(dmax).unwrap();
        let want = c.hysteresis.unwrap();
        println!("lambda {lambda}: loop {area}, cycle {want}");
        // tabor cycle sums trapezoids over its sampled path (a few hundred states): within
        // its sampling error of the quadrature here.
        assert!(
            (area - want).abs() <= 5e-3 * want.abs(),
            "lambda {lambda}: loop {area} against tabor cycle's {want}"
        );
    }
}

#[test]
fn the_folds_are_the_limits_at_both_ends() {
    // JKR (large lambda): the fold under rigid grips at Pbar = -5/6, load-controlled -3/2.
    let jkr = DemLaw::new(1e6, 10.0).unwrap();
    assert!(
        (jkr.disp_pulloff + 5.0 / 6.0).abs() < 1e-3,
        "{}",
        jkr.disp_pulloff
    );
    assert!((jkr.load_pulloff + 1.5).abs() < 1e-3);
    // DMT (small lambda): the pull-off -2, reached at the contact's edge.
    let dmt = DemLaw::new(1e-3, 10.0).unwrap();
    assert!(
        (dmt.load_pulloff + 2.0).abs() < 1e-2,
        "{}",
        dmt.load_pulloff
    );
}

#[test]
fn the_history_follows_the_branches_each_way() {
    for &lambda in &LAMBDAS {
        let law = DemLaw::new(lambda, 10.0).unwrap();
        let (app, ret) = law.drive(law.lowest_overlap() - 0.5, 5.0, 2001);
        // Apart at the start, in contact at the top, apart again at the end.
        assert_eq!(app[0].1.branch, Branch::Free);
        assert_eq!(app.last().unwrap().1.branch, Branch::Contact);
        assert_eq!(ret.last().unwrap().1.branch, Branch::Free);
        // The approach enters contact at delta_in, the retract leaves it below delta_out.
        for (d, e) in &app {
            assert_eq!(
                e.branch == Branch::Contact,
                *d >= law.delta_in,
                "lambda {lambda} at {d}"
            );
        }
        for (d, e) in &ret {
            assert_eq!(
                e.branch == Branch::Contact,
                *d >= law.delta_out,
                "lambda {lambda} at {d}"
            );
        }
        // The retract is never above the approach (energy is lost, never gained).
        for ((da, a), (dr, r)) in app.iter().zip(ret.iter().rev()) {
            assert_eq!(da, dr);
            assert!(
                r.load <= a.load + 1e-12,
                "lambda {lambda} at {da}: {} above {}",
                r.load,
                a.load
            );
        }
    }
}

#[test]
fn bad_input_is_refused_or_marked() {
    assert!(DemLaw::new(f64::NAN, 10.0).is_err());
    assert!(DemLaw::new(1.0, f64::INFINITY).is_err());
    let e = DemLaw::new(1.0, 1e5).unwrap_err().to_string();
    assert!(e.contains("overlap_max = 100000 is outside"), "{e}");
    let law = DemLaw::new(1.0, 5.0).unwrap();
    let mut h = Branch::Contact;
    let e = law.eval(f64::NAN, &mut h);
    assert!(e.load.is_nan() && h == Branch::Contact);
    let e = law.eval(6.0, &mut h);
    assert!(e.beyond_table && e.load.is_finite());
}

/// tests/data/dem_reference.csv: written from Maugis's equations and the Dugdale disc on a
/// half-space alone (tests/data/dem_reference.py, 50-digit arithmetic), with its own jump rules
/// from the branches' stability under rigid grips.
#[test]
fn the_law_is_the_independent_reference() {
    let text = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/dem_reference.csv"
    ))
    .unwrap();
    let rows: Vec<Vec<String>> = text
        .lines()
        .skip(1)
        .map(|l| l.split(',').map(str::to_string).collect())
        .collect();
    let mut lambdas: Vec<f64> = rows.iter().map(|r| r[0].parse().unwrap()).collect();
    lambdas.dedup();
    assert_eq!(lambdas.len(), 6);
    for &lambda in &lambdas {
        let law = DemLaw::new(lambda, 10.0).unwrap();
        let pc = law.load_pulloff.abs();
        let mine: Vec<&Vec<String>> = rows
            .iter()
            .filter(|r| r[0].parse::<f64>().unwrap() == lambda)
            .collect();
        let mut history = Branch::Free;
        let mut compared = 0;
        for r in &mine {
            let (phase, d, load, branch) = (&r[1], r[2].parse::<f64>().unwrap(), &r[3], &r[4]);
            let want: f64 = load.parse().unwrap();
            if phase == "mark" {
                let got = match branch.as_str() {
                    "non_contact_start" => -law.h0,
                    "jump_in" => law.delta_in,
                    "jump_out" => law.delta_out,
                    "non_contact_end" => law.delta_nc.unwrap(),
                    _ => continue,
                };
                assert!(
                    (got - d).abs() <= 1e-9 * d.abs().max(1.0),
                    "lambda {lambda}, {branch}: {got} against {d}"
                );
                continue;
            }
            let e = law.eval(d, &mut history);
            assert_eq!(e.branch.name(), branch, "lambda {lambda}, {phase} at {d}");
            assert!(
                (e.load - want).abs() <= 1e-6 * pc.max(want.abs()),
                "lambda {lambda}, {phase} at {d}: {} against {want}",
                e.load
            );
            compared += 1;
        }
        assert_eq!(compared, 82, "lambda {lambda}");
    }
    let energy = std::fs::read_to_string(concat!(
        env!("CARGO_MANIFEST_DIR"),
        "/tests/data/dem_reference_energy.csv"
    ))
    .unwrap();
    for l in energy.lines().skip(1) {
        let v: Vec<f64> = l.split(',').map(|x| x.parse().unwrap()).collect();
        let law = DemLaw::new(v[0], 10.0).unwrap();
        let area = law.loop_area(v[1]).unwrap();
        assert!(
            (area - v[2]).abs() <= 1e-8 * v[2],
            "lambda {}: loop {area} against {}",
            v[0],
            v[2]
        );
    }
}
