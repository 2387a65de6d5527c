//! The DEM force-overlap law (`tabor::dem`): its table against exact solves, its stiffness
//! against differences, its history against the rigid-grip cycle of `tabor cycle`, its limits
//! (JKR, DMT), an independent reference written from the equations alone
//! (tests/data/dem_reference.py), and the wet law (a meniscus beside the solid's zone) against
//! the wet summits of rough surfaces and the two-zone cycle.

use tabor::dem::{Branch, DemLaw, History};
use tabor::law::ContactLaw;

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
            let want = law.exact_contact(d).unwrap();
            let got = law.contact_branch(d).0;
            worst = worst.max((got - want).abs() / law.load_pulloff.abs().max(want.abs()));
        }
        // Every non-contact stretch, at 397 overlaps off its nodes, denser at its ends.
        for code in 1..law.stretch_count() as u8 - 1 {
            let h = law.history(code).unwrap();
            let (lo, hi) = law.stretch_range(h);
            for k in 0..397 {
                let t = (k as f64 + 0.3137) / 397.0;
                let d = lo + (hi - lo) * 0.5 * (1.0 - (std::f64::consts::PI * t).cos());
                let want = law.exact(h, d).unwrap();
                let got = law.eval(d, &mut h.clone()).load;
                worst = worst.max((got - want).abs() / law.load_pulloff.abs().max(want.abs()));
            }
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
            let f = |x: f64| law.exact_contact(x).unwrap();
            let fd = (f(d + h) - f(d - h)) / (2.0 * h);
            let k = law.contact_branch(d).1;
            assert!(
                (k - fd).abs() <= 1e-4 * fd.abs().max(scale),
                "lambda {lambda}, contact at {d}: {k} against {fd}"
            );
        }
        // Every non-contact stretch, halfway between its ends.
        for code in 1..law.stretch_count() as u8 - 1 {
            let mut h = law.history(code).unwrap();
            let (lo, hi) = law.stretch_range(h);
            let d = 0.5 * (lo + hi);
            let step = 1e-4 * (hi - lo);
            let f = |x: f64| law.exact(h, x).unwrap();
            let fd = (f(d + step) - f(d - step)) / (2.0 * step);
            let k = law.eval(d, &mut h).stiffness;
            assert!(
                (k - fd).abs() <= 1e-4 * fd.abs().max(scale),
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
        assert_loop(&law, &c, dmax, &format!("lambda {lambda}"));
    }
}

/// The law's loop up to `dmax` is the rigid-grip cycle's `c` (the same stretches, probed up to
/// another overlap: to rounding), and the trapezoids over the cycle's sampled steps (a few
/// hundred states) are another measure of it, within their sampling error.
fn assert_loop(law: &DemLaw, c: &tabor::cycle::Cycle, dmax: f64, what: &str) {
    let area = law.loop_area(dmax).unwrap();
    let h = c.hysteresis.unwrap();
    assert!((h - area).abs() <= 1e-12 * area.abs(), "{what}: {h} {area}");
    let want = tabor::cycle::trapezoid_loop(&c.steps);
    println!("{what}: loop {area}, the cycle's trapezoids {want}");
    assert!(
        (area - want).abs() <= 5e-3 * want.abs(),
        "{what}: loop {area} against the trapezoids' {want}"
    );
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
    let contact = law.history(law.stretch_count() as u8 - 1).unwrap();
    let mut h = contact;
    let e = law.eval(f64::NAN, &mut h);
    assert!(e.load.is_nan() && h == contact && e.branch == Branch::Contact);
    assert!(law.history(law.stretch_count() as u8).is_none());
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
        let mut history = History::NEW;
        let mut compared = 0;
        for r in &mine {
            let (phase, d, load, branch) = (&r[1], r[2].parse::<f64>().unwrap(), &r[3], &r[4]);
            let want: f64 = load.parse().unwrap();
            if phase == "mark" {
                let got = match branch.as_str() {
                    "non_contact_start" => law.attraction_from,
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

/// Two-zone laws (lambda_s, stress ratio, range ratio) whose paths differ in kind: the retract
/// lands on a meniscus stretch (1, 0.5, 3), the approach jumps from free into contact (2, 1,
/// 2), a long meniscus (1, 0.2, 5), a DMT-like solid entering contact at A -> 0 (0.3, 0.05, 10),
/// and a DMT-like solid in a short, strong meniscus (0.01, 5, 0.3), whose non-contact path turns
/// back by 5e-4 where the second disc starts, a turn evenly spread probes did not see (the law
/// was refused).
const WET: [(f64, f64, f64); 5] = [
    (1.0, 0.5, 3.0),
    (2.0, 1.0, 2.0),
    (1.0, 0.2, 5.0),
    (0.3, 0.05, 10.0),
    (0.01, 5.0, 0.3),
];

fn wet(l: f64, rho: f64, eta: f64) -> (DemLaw, tabor::law::TwoZones) {
    let law = ContactLaw::solid_and_meniscus(l, rho, eta);
    let ContactLaw::SolidAndMeniscus(z) = law else {
        unreachable!("a two-zone law")
    };
    (DemLaw::of_law(law, 10.0).unwrap(), z)
}

/// The wet summit of rough surfaces (`rough::wet::WetSummit`) finds its stretches by sampling
/// and golden sections, and solves its loads by the two-zone solver at the approach and by
/// Illinois steps on the discs: another code for the same rules.
#[test]
fn the_wet_law_is_the_wet_summit_of_rough_surfaces() {
    use tabor::rough::wet::WetSummit;
    use tabor::rough::SummitBranch;
    for &(l, rho, eta) in &WET {
        let (dem, z) = wet(l, rho, eta);
        let summit = WetSummit::new(z.zones().unwrap(), None).unwrap();
        let case = format!("lambda_s {l}, rho {rho}, eta {eta}");
        // The same stretches, end for end.
        assert_eq!(dem.stretch_count(), summit.stretches.len(), "{case}");
        for (k, s) in summit.stretches.iter().enumerate() {
            let (lo, hi) = dem.stretch_range(dem.history(k as u8).unwrap());
            for (a, b) in [(lo, s.lo), (hi, s.hi)] {
                assert!(
                    a == b || (a - b).abs() <= 1e-9 * (1.0 + b.abs()),
                    "{case}, stretch {k}: {a} against {b}"
                );
            }
        }
        assert!(
            (dem.delta_in - summit.approach_enter()).abs() <= 1e-9,
            "{case}"
        );
        let pc = dem.load_pulloff.abs();
        let top = 5.0;
        let (app, ret) = dem.drive(dem.lowest_overlap() - 0.5, top, 1601);
        for (leg, half) in [("approach", &app), ("retract", &ret)] {
            for (d, e) in half.iter() {
                let k = if leg == "approach" {
                    summit.approach_stretch(*d)
                } else {
                    summit.retract_stretch(*d, top)
                };
                let kind = match summit.stretches[k].branch() {
                    SummitBranch::Free => Branch::Free,
                    SummitBranch::NonContact => Branch::NonContact,
                    SummitBranch::Contact => Branch::Contact,
                };
                assert_eq!(e.branch, kind, "{case}, {leg} at {d}");
                let want = summit.load(k, *d).unwrap();
                assert!(
                    (e.load - want).abs() <= 1e-6 * pc.max(want.abs()),
                    "{case}, {leg} at {d}: {} against {want}",
                    e.load
                );
            }
        }
        assert!(dem.error <= 1e-6, "{case}: {}", dem.error);
    }
}

#[test]
fn the_wet_loop_is_the_two_zone_cycle_of_tabor_cycle() {
    // (The fifth law's loop, 7.8e-8, is the turn at the second disc's start, 5e-4 wide: below
    // what the cycle's samples resolve; it has its own test against the exact states.)
    for &(l, rho, eta) in &WET[..4] {
        let (dem, z) = wet(l, rho, eta);
        let c = tabor::cycle::run(&z, tabor::Drive::RigidGrips, 2.0).unwrap();
        let dmax = z.context().unwrap().state_at_load(2.0).approach;
        assert_loop(
            &dem,
            &c,
            dmax,
            &format!("lambda_s {l}, rho {rho}, eta {eta}"),
        );
        // The cycle's jump out of contact is the exact fold, and lands where the law's retract
        // goes on: a meniscus stretch or free. Without a jump (contact lost at A -> 0 onto the
        // meniscus) the law's retract goes on across the gap too.
        let mut h = dem.history(dem.stretch_count() as u8 - 1).unwrap();
        let after = dem.eval(dem.delta_out - 1e-9, &mut h).branch;
        let out = c.jumps.iter().find(|j| {
            j.phase == tabor::cycle::Phase::Retract && j.from.branch == tabor::law::Branch::Contact
        });
        match out {
            Some(out) => {
                assert!(
                    (out.from.approach - dem.delta_out).abs() <= 1e-9,
                    "{l}, {rho}, {eta}"
                );
                // (The cycle's landing is interpolated on its sampled path: a landing at the
                // free branch's end carries a load of 0, whatever its label.)
                let landed = out.to.map(|p| p.load);
                assert_eq!(
                    after == Branch::NonContact,
                    landed.is_some_and(|p| p < 0.0),
                    "{l}, {rho}, {eta}: {after:?} against {landed:?}"
                );
            }
            None => assert_eq!(after, Branch::NonContact, "{l}, {rho}, {eta}"),
        }
    }
}

/// Where the meniscus's second disc starts, the non-contact path turns back (its parameter runs
/// on while the overlap falls) with the load's slope in the overlap continuous: the stretch
/// below ends there with a finite stiffness, and the loop of that turn, for (0.01, 5, 0.3) all
/// of the law's hysteresis, is the integral of the exact states along the two stretches.
#[test]
fn a_turn_where_the_second_disc_starts_ends_a_stretch_with_a_finite_stiffness() {
    use tabor::law::{Law, Piece};
    for &(l, rho, eta) in &[(1.0, 0.5, 3.0), (0.01, 5.0, 0.3)] {
        let (dem, z) = wet(l, rho, eta);
        let case = format!("lambda_s {l}, rho {rho}, eta {eta}");
        let brk = z.breaks(Piece::NonContact)[0];
        let at = |t: f64| z.state(Piece::NonContact, t);
        // The turn: the overlap's slope along the path changes sign at the break, the load's
        // slope in the overlap does not (measured 1e-5 apart; checked to 1e-3).
        let (below, above) = (at(brk - 1e-9), at(brk + 1e-9));
        assert!(below.dapproach > 0.0 && above.dapproach < 0.0, "{case}");
        let k_exact = below.dload / below.dapproach;
        assert!(
            (above.dload / above.dapproach - k_exact).abs() <= 1e-3 * k_exact.abs(),
            "{case}"
        );
        // The stretch below ends at the break's overlap, and its stiffness there and next to it
        // is the exact slope.
        let h = dem.history(1).unwrap();
        let (_, top) = dem.stretch_range(h);
        assert!(
            (top - at(brk).approach).abs() <= 1e-12 * (1.0 + top.abs()),
            "{case}"
        );
        for d in [top, top - 1e-12, top - 1e-9, top - 1e-6] {
            let k = dem.eval(d, &mut h.clone()).stiffness;
            assert!(
                (k - k_exact).abs() <= 1e-3 * k_exact.abs().max(1e-2),
                "{case} at {} from the top: {k} against {k_exact}",
                d - top
            );
        }
    }
    // The loop of (0.01, 5, 0.3): up the first stretch from the overlap of the second's fold to
    // the break, back down the second from where it holds the break's overlap to its fold.
    let (dem, z) = wet(0.01, 5.0, 0.3);
    let brk = z.breaks(Piece::NonContact)[0];
    let at = |t: f64| z.state(Piece::NonContact, t);
    let (_, top) = dem.stretch_range(dem.history(1).unwrap());
    let (fold, _) = dem.stretch_range(dem.history(2).unwrap());
    // The parameter where the overlap is `d`, on a run of rising overlap from `a` to `b`.
    let find = |mut a: f64, mut b: f64, d: f64| {
        for _ in 0..200 {
            let m = 0.5 * (a + b);
            if at(m).approach < d {
                a = m
            } else {
                b = m
            }
        }
        0.5 * (a + b)
    };
    // The fold's parameter: where the overlap's slope along the path turns positive again.
    let (mut a, mut b) = (brk + 1e-9, brk + 1.0);
    for _ in 0..200 {
        let m = 0.5 * (a + b);
        if at(m).dapproach < 0.0 {
            a = m
        } else {
            b = m
        }
    }
    let t_fold = 0.5 * (a + b);
    assert!(
        (at(t_fold).approach - fold).abs() <= 1e-9,
        "{} against {fold}",
        at(t_fold).approach
    );
    // Simpson's rule in t for the integral of P dD/dt (the differences' slope is exact enough
    // here: 20000 panels agree with 80000 to 2e-7).
    let integral = |t0: f64, t1: f64| {
        let n = 20000;
        let h = (t1 - t0) / n as f64;
        (0..n)
            .map(|i| {
                let x = t0 + i as f64 * h;
                let (p0, pm, p1) = (at(x), at(x + 0.5 * h), at(x + h));
                (p0.load + 4.0 * pm.load + p1.load) / 6.0 * (p1.approach - p0.approach)
            })
            .sum::<f64>()
    };
    let first = find(brk - 1.0, brk, fold);
    let second = find(t_fold, brk + 1.0, top);
    let want = integral(first, brk) - integral(t_fold, second);
    let area = dem.loop_area(2.0).unwrap();
    // tabor cycle's loop under grips is the stretches' too (its samples' trapezoids gave
    // 7.69e-8, 1.7% short: the turn is 5e-4 wide in overlap).
    let cycle = tabor::cycle::run(&z, tabor::Drive::RigidGrips, 2.0).unwrap();
    let h = cycle.hysteresis.unwrap();
    assert!(
        (h - want).abs() <= 1e-3 * want,
        "tabor cycle {h} against {want}"
    );
    assert!(
        (area - want).abs() <= 1e-3 * want,
        "loop {area} against {want}"
    );
}

/// A meniscus of vanishing stress (through the two-range code: rho = 1e-6, eta = 3) is the dry
/// law, and one of no stress is the dry law's own code.
#[test]
fn a_meniscus_without_stress_is_the_dry_law() {
    for &l in &[0.3, 0.7, 3.0] {
        let dry = DemLaw::new(l, 10.0).unwrap();
        let (none, _) = wet(l, 0.0, 3.0);
        let (a, b) = (dry.drive(-5.0, 8.0, 801), none.drive(-5.0, 8.0, 801));
        assert_eq!(format!("{a:?}"), format!("{b:?}"), "lambda {l}");
        let (faint, _) = wet(l, 1e-6, 3.0);
        assert!(faint.stretch_count() >= dry.stretch_count(), "lambda {l}");
        let pc = dry.load_pulloff.abs();
        assert!(
            (faint.load_pulloff - dry.load_pulloff).abs() <= 4e-6 * pc,
            "lambda {l}"
        );
        assert!(
            (faint.delta_out - dry.delta_out).abs() <= 4e-6,
            "lambda {l}"
        );
        let c = faint.drive(-5.0, 8.0, 801);
        for ((d, x), (_, y)) in c.0.iter().chain(&c.1).zip(a.0.iter().chain(&a.1)) {
            // Away from the jumps, which move by the meniscus's reach (3 h0 beyond the solid's).
            if (d - dry.attraction_from).abs() < 4.0 * dry.attraction_from.abs()
                && x.branch != y.branch
            {
                continue;
            }
            // The faint meniscus's own pull, of order rho eta C^2 in these units.
            assert!(
                (x.load - y.load).abs() <= 2e-5 * pc.max(y.load.abs()),
                "lambda {l} at {d}: {} against {}",
                x.load,
                y.load
            );
        }
    }
}

/// Where a stretch ends without a fold (contact entered or left at A -> 0, the meniscus's disc
/// running on into contact) the stiffness is the branch's finite slope, at the end itself and
/// next to it: not a spline's end error over a vanishing square root.
#[test]
fn the_stiffness_is_finite_and_right_where_a_stretch_ends_without_a_fold() {
    let laws = [
        ("md 0.5", DemLaw::new(0.5, 10.0).unwrap()),
        ("md 0.1", DemLaw::new(0.1, 10.0).unwrap()),
        ("wet 0.3 0.05 10", wet(0.3, 0.05, 10.0).0),
    ];
    for (name, law) in &laws {
        let scale = law.load_pulloff.abs();
        // The slope of the exact stretch `h` at `d`: central differences inside; within 1e-7 of
        // its end `end` (the load there may carry a half power of the distance) the end's own
        // slope, by a one-sided difference into the stretch (`inward`).
        let slope = |h: History, d: f64, end: f64, inward: f64| {
            let f = |x: f64| law.exact(h, x).unwrap();
            if (d - end).abs() > 1e-7 {
                let e = 1e-8;
                (f(d + e) - f(d - e)) / (2.0 * e)
            } else {
                let e = 1e-7 * inward;
                (-3.0 * f(end) + 4.0 * f(end + e) - f(end + 2.0 * e)) / (2.0 * e)
            }
        };
        // The contact stretch's low end (contact lost at A -> 0: no fold), from above; the
        // non-contact stretch that runs on into contact, at its top from below.
        let contact = law.history(law.stretch_count() as u8 - 1).unwrap();
        let nc = law.history(law.stretch_count() as u8 - 2).unwrap();
        let (lo, _) = law.stretch_range(contact);
        let (_, hi) = law.stretch_range(nc);
        let cases = [
            (contact, lo, 1.0, [lo, lo + 1e-12, lo + 1e-9, lo + 1e-6]),
            (nc, hi, -1.0, [hi, hi - 1e-12, hi - 1e-9, hi - 1e-6]),
        ];
        for (h, end, inward, ds) in cases {
            for d in ds {
                let want = slope(h, d, end, inward);
                let k = law.eval(d, &mut h.clone()).stiffness;
                assert!(
                    k.is_finite() && (k - want).abs() <= 1e-3 * want.abs().max(scale),
                    "{name}, {:?} at {d} ({} from its end): {k} against {want}",
                    law.branch(h),
                    d - end
                );
            }
        }
    }
}

/// Two glass microspheres in humid air: the pair's SI law is the wet scene's.
#[test]
fn a_humid_pair_is_the_wet_scene() {
    let json = r#"{
        "body1": {"youngs_modulus_pa": 70e9, "poisson_ratio": 0.17, "radius_m": 5e-6},
        "body2": {"youngs_modulus_pa": 70e9, "poisson_ratio": 0.17, "radius_m": 5e-6},
        "work_of_adhesion_j_m2": 0.1,
        "z0_m": 3e-10,
        "humidity": {"relative_humidity": 0.5, "contact_angle_deg": 20}
    }"#;
    let s: tabor::SceneInput = serde_json::from_str(json).unwrap();
    let pair = tabor::dem::Pair::from_scene(&s, None).unwrap();
    let scene = tabor::solve_scene(&s).unwrap();
    let m = scene.meniscus.unwrap();
    assert_eq!(pair.meniscus, Some(m));
    let c = pair.contact;
    let w = c.work + m.work_of_adhesion_j_m2;
    let rel = |a: f64, b: f64| (a - b).abs() / b.abs();
    assert!(rel(pair.force_scale, std::f64::consts::PI * w * c.radius) < 1e-14);
    assert!(
        rel(
            pair.law.disp_pulloff * pair.force_scale,
            scene.pulloff_force_displacement_control_N
        ) < 1e-8,
        "{} against {}",
        pair.law.disp_pulloff * pair.force_scale,
        scene.pulloff_force_displacement_control_N
    );
    assert!(
        rel(
            pair.law.load_pulloff * pair.force_scale,
            scene.pulloff_force_load_control_N
        ) < 1e-9
    );
    // (The fold is found by two codes: the solver's and the stretches' bisection on the
    // approach's slope; measured 6e-9 apart.)
    // Dry, the same pair is Maugis-Dugdale at the solid's lambda.
    let mut dry = s.clone();
    dry.humidity = None;
    let d = tabor::dem::Pair::from_scene(&dry, None).unwrap();
    assert!(d.meniscus.is_none() && d.law.law == ContactLaw::md(c.lambda()));
}

/// Any law of the law layer with a rigid-grip path exports: a paraboloid tip (n = 2) in its
/// units is the sphere's law, and a cone's loop is its `tabor cycle` loop.
#[test]
fn a_tip_exports_its_law_too() {
    use tabor::law::Tip;
    use tabor::physics::tip::Shape;
    for &l in &[0.3, 3.0] {
        let tip = DemLaw::of_law(
            ContactLaw::Tip(Tip::new(Shape::Power { exponent: 2.0 }, l).unwrap()),
            10.0,
        )
        .unwrap();
        let sphere = DemLaw::new(l, 10.0).unwrap();
        let pc = sphere.load_pulloff.abs();
        assert!(
            (tip.load_pulloff - sphere.load_pulloff).abs() <= 1e-9 * pc,
            "lambda {l}"
        );
        assert!(
            (tip.delta_out - sphere.delta_out).abs() <= 1e-9,
            "lambda {l}"
        );
        let (a, b) = (tip.drive(-4.0, 8.0, 601), sphere.drive(-4.0, 8.0, 601));
        for ((d, x), (_, y)) in a.0.iter().chain(&a.1).zip(b.0.iter().chain(&b.1)) {
            assert_eq!(x.branch, y.branch, "lambda {l} at {d}");
            assert!(
                (x.load - y.load).abs() <= 2e-6 * pc.max(y.load.abs()),
                "lambda {l} at {d}"
            );
        }
    }
    let cone = Tip::new(Shape::Power { exponent: 1.0 }, 1.0).unwrap();
    let dem = DemLaw::of_law(ContactLaw::Tip(cone), 10.0).unwrap();
    assert!(dem.error <= 1e-6);
    let c = tabor::cycle::run(&cone, tabor::Drive::RigidGrips, 2.0).unwrap();
    let top = c
        .steps
        .iter()
        .filter(|s| s.phase == tabor::cycle::Phase::Approach)
        .map(|s| s.point.approach)
        .fold(f64::NEG_INFINITY, f64::max);
    let (area, want) = (dem.loop_area(top).unwrap(), c.hysteresis.unwrap());
    assert!(
        (area - want).abs() <= 5e-3 * want,
        "cone: loop {area} against {want}"
    );
}

/// The stretches found from the law's states (probes, folds refined by bisection) put the jumps
/// where the solver's summit of rough surfaces does (`rough::Summit`: the solver's pull-offs and
/// the closed-form non-contact branch), across lambda and densely near lambda_D, where the
/// contact branch folds twice within a small range of overlaps.
#[test]
fn the_marks_are_the_solvers_across_lambda() {
    let near_d = (0..=90).map(|k| 0.9 + 0.0005 * k as f64);
    let across = (0..=48).map(|k| 10f64.powf(-2.0 + 6.0 * k as f64 / 48.0));
    for lambda in near_d.chain(across) {
        let law = DemLaw::new(lambda, 10.0).unwrap();
        let s = tabor::Summit::new(lambda).unwrap();
        let close = |a: f64, b: f64| (a - b).abs() <= 1e-9 * (1.0 + b.abs());
        assert!(
            close(law.delta_out, s.delta_out),
            "lambda {lambda}: out {} against {}",
            law.delta_out,
            s.delta_out
        );
        assert!(
            close(law.delta_in, s.delta_in),
            "lambda {lambda}: in {} against {}",
            law.delta_in,
            s.delta_in
        );
        match (law.delta_nc, s.delta_nc) {
            (Some(a), Some(b)) => assert!(close(a, b), "lambda {lambda}: nc {a} against {b}"),
            (a, b) => assert_eq!(
                a.is_some(),
                b.is_some(),
                "lambda {lambda}: nc {a:?} against {b:?}"
            ),
        }
        assert!(
            close(law.load_pulloff, s.smooth_pulloff()),
            "lambda {lambda}"
        );
    }
}
