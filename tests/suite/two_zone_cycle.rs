//! The two-zone (solid + meniscus) approach-retract cycle: its MD limits, its pull-offs against
//! the two-zone solver's, the branches meeting, bad input, the wet cantilever scene and the
//! command line.

use tabor::cycle::{self, Branch, Cycle, Drive, Phase};
use tabor::physics::two_zone::{Shape, Zones};
use tabor::solver::two_zone::TwoZoneContext;

fn wet(l: f64, rho: f64, eta: f64, d: Drive) -> Cycle {
    tabor::cycle::run(&tabor::ContactLaw::solid_and_meniscus(l, rho, eta), d, 2.0).unwrap()
}

fn same(a: &Cycle, b: &Cycle, tol: f64) {
    assert_eq!(a.steps.len(), b.steps.len());
    for (s, t) in a.steps.iter().zip(&b.steps) {
        assert_eq!(
            (s.phase, s.point.branch, s.jump),
            (t.phase, t.point.branch, t.jump)
        );
        for (x, y) in [
            (s.point.load, t.point.load),
            (s.point.approach, t.point.approach),
            (s.point.a, t.point.a),
        ] {
            assert!((x - y).abs() <= tol * (1.0 + y.abs()), "{x} vs {y}");
        }
    }
    assert_eq!(a.jumps.len(), b.jumps.len());
    for (j, k) in a.jumps.iter().zip(&b.jumps) {
        assert!(
            (j.from.load - k.from.load).abs() <= tol
                && (j.from.approach - k.from.approach).abs() <= tol
        );
    }
    match (a.hysteresis, b.hysteresis) {
        (Some(x), Some(y)) => assert!((x - y).abs() <= tol * y, "{x} vs {y}"),
        (x, y) => assert_eq!(x, y),
    }
}

#[test]
fn no_meniscus_or_one_range_is_the_md_cycle() {
    for d in [Drive::RigidGrips, Drive::DeadLoad, Drive::Spring(0.7)] {
        for l in [0.3, 2.0] {
            // rho = 0: the solid alone, in its own units.
            same(
                &wet(l, 0.0, 3.0, d),
                &cycle::cycle(l, d, 2.0).unwrap(),
                1e-9,
            );
            // eta = 1: one range, MD with lambda_1 + lambda_2 in the total-w units.
            let rho = 0.5;
            let z = Zones::from_ratios(l, rho, 1.0).unwrap();
            let total = z.lambda[0] + z.lambda[1];
            assert!((total - l * (1.0f64 + rho).powf(2.0 / 3.0)).abs() < 1e-12);
            same(
                &wet(l, rho, 1.0, d),
                &cycle::cycle(total, d, 2.0).unwrap(),
                1e-9,
            );
        }
    }
}

#[test]
fn a_faint_meniscus_approaches_the_md_cycle() {
    // Two ranges, so the two-zone path (its own sampling) is used: rho = 1e-7 moves the
    // physics by ~1e-7, the rest is the two samplings' difference.
    let (l, d) = (2.0, Drive::RigidGrips);
    let w = wet(l, 1e-7, 3.0, d);
    let md = cycle::cycle(l, d, 2.0).unwrap();
    let out = |c: &Cycle| {
        c.jumps
            .iter()
            .find(|j| j.phase == Phase::Retract)
            .unwrap()
            .from
    };
    let (a, b) = (out(&w), out(&md));
    assert!(
        (a.load - b.load).abs() < 1e-5 && (a.approach - b.approach).abs() < 1e-5,
        "{a:?} {b:?}"
    );
    let (hw, hm) = (w.hysteresis.unwrap(), md.hysteresis.unwrap());
    eprintln!("hysteresis {hw} vs MD {hm}");
    assert!((hw / hm - 1.0).abs() < 2e-3, "{hw} vs {hm}");
}

#[test]
fn pulloffs_are_the_solvers() {
    for (l, rho, eta) in [(2.0, 0.3, 3.0), (0.5, 0.1, 5.0), (5.0, 0.05, 4.0)] {
        let z = Zones::from_ratios(l, rho, eta).unwrap();
        assert!(matches!(z.shape(), Shape::Two { .. }));
        let ctx = TwoZoneContext::new(z).unwrap();
        for (d, exact) in [
            (Drive::RigidGrips, ctx.disp_pulloff),
            (Drive::DeadLoad, ctx.load_pulloff),
        ] {
            let c = wet(l, rho, eta, d);
            let j = c.jumps.iter().find(|j| j.phase == Phase::Retract).unwrap();
            if exact.at_zero_radius() {
                continue;
            }
            assert_eq!(j.from.branch, Branch::Contact);
            // The follower's fold (a secant on the control's slope) against the solver's
            // pull-off (a golden-section extreme, placed to about the square root of the
            // rounding): the controlled variable, stationary there, agrees to rounding, the
            // other to its slope times that.
            let close = |x: f64, y: f64, tol: f64| (x - y).abs() <= tol * y.abs().max(1.0);
            let (held, other) = match d {
                Drive::DeadLoad => ((j.from.load, exact.load), (j.from.approach, exact.approach)),
                _ => ((j.from.approach, exact.approach), (j.from.load, exact.load)),
            };
            assert!(
                close(held.0, held.1, 1e-12) && close(other.0, other.1, 1e-7),
                "{l} {rho} {eta} {d:?}: the fold {held:?} {other:?}"
            );
            // The step before the jump (or before separating) is the fold itself.
            let k = c
                .steps
                .iter()
                .rposition(|s| s.phase == Phase::Retract && s.jump)
                .unwrap_or(c.steps.len());
            let last = c.steps[k - 1].point;
            assert!(
                close(last.load, j.from.load, 1e-12),
                "{l} {rho} {eta} {d:?}"
            );
            if d == Drive::DeadLoad {
                assert!(j.to.is_none() && c.hysteresis.is_none());
            }
        }
    }
}

#[test]
fn non_contact_meets_contact() {
    for (l, rho, eta) in [(2.0, 0.3, 3.0), (0.3, 1.0, 2.0), (1.0, 0.2, 0.5)] {
        let c = wet(l, rho, eta, Drive::RigidGrips);
        let k = c
            .path
            .iter()
            .position(|p| p.branch == Branch::Contact)
            .unwrap();
        let (nc, ct) = (c.path[k - 1], c.path[k]);
        // The first contact radius is ~1e-4 of the curve's scale: both within that.
        assert!(
            (nc.load - ct.load).abs() < 1e-3 && (nc.approach - ct.approach).abs() < 1e-3,
            "{nc:?} {ct:?}"
        );
        assert!((nc.c - ct.c).abs() < 1e-3 * nc.c.max(1.0), "{nc:?} {ct:?}");
        // The free segment ends where the longer zone first reaches the axis.
        let z = Zones::from_ratios(l, rho, eta).unwrap();
        let first = c
            .path
            .iter()
            .find(|p| p.branch == Branch::NonContact)
            .unwrap();
        assert!((first.approach + z.range[0].max(z.range[1])).abs() < 1e-12 && first.load == 0.0);
    }
}

#[test]
fn bad_input_is_one_line() {
    let g = Drive::RigidGrips;
    for (l, rho, eta, d, word) in [
        (1.0, -0.1, 2.0, g, "stress ratio"),
        (1.0, 0.1, f64::NAN, g, "range ratio"),
        (f64::NAN, 0.1, 2.0, g, "lambda"),
        (1.0, 0.1, 2.0, Drive::Spring(0.0), "stiffness"),
        (1.0, 0.1, 2.0, Drive::Spring(-1.0), "stiffness"),
    ] {
        let e = tabor::cycle::run(&tabor::ContactLaw::solid_and_meniscus(l, rho, eta), d, 2.0)
            .unwrap_err()
            .to_string();
        assert!(e.contains(word) && !e.contains('\n'), "{e}");
    }
    let e = tabor::cycle::run(
        &tabor::ContactLaw::solid_and_meniscus(1.0, 0.1, 2.0),
        g,
        -1.0,
    )
    .unwrap_err()
    .to_string();
    assert!(e.contains("largest load") && !e.contains('\n'), "{e}");
}

use tabor::scene::humidity::HumidityInput;
use tabor::scene::{preset, solve_scene, SceneControl};

#[test]
fn wet_cantilever_scene_lies_between_the_two_controls() {
    // A stiff cantilever pulls off as rigid grips do, a soft one as dead load (the wet pull-offs
    // of the same scene under those controls; the silicon tip has a small lambda, so the two
    // differ by 0.3% only).
    let wet = |control| {
        let mut s = preset("afm-si").unwrap();
        s.humidity = Some(HumidityInput::water(0.4, 20.0));
        s.control = Some(control);
        solve_scene(&s).unwrap()
    };
    let r = wet(SceneControl::Load);
    let (load, disp) = (
        r.pulloff_force_load_control_N,
        r.pulloff_force_displacement_control_N,
    );
    assert!(load < disp);
    let stiff = wet(SceneControl::CantileverNM(1e7)).pulloff_force_under_control_N;
    let soft = wet(SceneControl::CantileverNM(1e-4)).pulloff_force_under_control_N;
    eprintln!("load {load} disp {disp} stiff {stiff} soft {soft}");
    assert!(
        (stiff - disp).abs() < 1e-3 * disp.abs(),
        "{stiff} vs {disp}"
    );
    assert!((soft - load).abs() < 1e-3 * load.abs(), "{soft} vs {load}");
}

#[test]
fn command_line_wet_cycle_is_the_librarys() {
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args([
            "cycle",
            "--lambda",
            "2",
            "--stress-ratio",
            "0.3",
            "--range-ratio",
            "3",
        ])
        .args([
            "--control",
            "spring",
            "--stiffness",
            "0.7",
            "--format",
            "json",
        ])
        .output()
        .unwrap();
    assert!(o.status.success(), "{}", String::from_utf8_lossy(&o.stderr));
    let v: serde_json::Value = serde_json::from_slice(&o.stdout).unwrap();
    let c = tabor::cycle::run(
        &tabor::ContactLaw::solid_and_meniscus(2.0, 0.3, 3.0),
        Drive::Spring(0.7),
        2.0,
    )
    .unwrap();
    assert_eq!(v["hysteresis"].as_f64(), c.hysteresis);
    assert_eq!(v["steps"].as_array().unwrap().len(), c.steps.len());
    let o = std::process::Command::new(env!("CARGO_BIN_EXE_tabor"))
        .args([
            "cycle",
            "--lambda",
            "2",
            "--stress-ratio",
            "-1",
            "--range-ratio",
            "3",
        ])
        .output()
        .unwrap();
    let e = String::from_utf8_lossy(&o.stderr);
    assert!(
        !o.status.success() && e.contains("stress ratio") && e.trim().lines().count() == 1,
        "{e}"
    );
}

/// Under a spring the retract leaves the contact curve at its fold, where dPbar/dDbar = -kbar:
/// found here independently, parametrised by the contact radius (the solver's states at a
/// radius, central differences of load and approach, bisection on the sign of
/// dPbar/dA + kbar dDbar/dA), it agrees with the cycle's jump-out to 1e-9; the sampled path
/// alone was off by far more.
#[test]
fn spring_jump_out_is_the_fold_found_exactly() {
    let (mut worst, mut folds) = (0.0f64, 0);
    for (l, rho, eta) in [(0.5, 0.3, 3.0), (2.0, 0.5, 0.4), (1.0, 2.0, 5.0)] {
        let ctx = TwoZoneContext::new(Zones::from_ratios(l, rho, eta).unwrap()).unwrap();
        for k in [0.3, 1.0, 4.0] {
            let c = wet(l, rho, eta, Drive::Spring(k));
            let Some(j) = c
                .jumps
                .iter()
                .find(|j| j.phase == Phase::Retract && j.from.branch == Branch::Contact)
            else {
                continue;
            };
            // d(Pbar + kbar Dbar)/dA by a central difference in A.
            let f = |a: f64| {
                let h = 1e-6 * a;
                let (p, m) = (ctx.state_at_radius(a + h), ctx.state_at_radius(a - h));
                (p.load - m.load) + k * (p.approach - m.approach)
            };
            // The stable side (large A): the control rises with A.
            let (mut lo, mut hi) = (0.7 * j.from.a, 1.4 * j.from.a);
            assert!(f(lo) < 0.0 && f(hi) > 0.0, "l {l} k {k}: no fold bracketed");
            for _ in 0..100 {
                let m = 0.5 * (lo + hi);
                if f(m) < 0.0 {
                    lo = m;
                } else {
                    hi = m;
                }
            }
            let fold = ctx.state_at_radius(0.5 * (lo + hi));
            let d = (j.from.load - fold.load).abs();
            assert!(
                d < 1e-9,
                "lambda {l}, rho {rho}, eta {eta}, k {k}: jump-out {} against the fold {}",
                j.from.load,
                fold.load
            );
            assert!((j.from.approach - fold.approach).abs() < 1e-9);
            assert!((j.from.a - fold.a).abs() < 1e-6 * fold.a);
            // The landing on the free branch is at the spring's base there.
            if let Some(to) = j.to.as_ref().filter(|t| t.branch == Branch::Free) {
                assert!((to.approach - (fold.approach + fold.load / k)).abs() < 1e-9);
            }
            worst = worst.max(d);
            folds += 1;
        }
    }
    eprintln!("spring jump-out against the independent fold: {folds} folds, worst {worst:.2e}");
    assert!(folds >= 6, "{folds}");
}

/// The one entry of the command line and Python: a contact law (MD, or with both ratios the
/// two-zone law; a lone ratio refused, naming both) and a drive; the same cycle as each law's
/// own function, bit for bit, and the same refusals.
#[test]
fn the_cycle_spec_dispatches_on_the_law() {
    use tabor::cycle::CycleSpec;
    use tabor::{ContactLaw, ContactModel};
    let json = |c: &Cycle| serde_json::to_string(c).unwrap();
    let e = ContactLaw::new(1.0, Some(0.2), None).unwrap_err();
    assert_eq!(
        e.keys().collect::<Vec<_>>(),
        ["stress_ratio", "range_ratio"]
    );
    let e = e.to_string();
    assert!(
        e.contains("stress_ratio") && e.contains("range_ratio"),
        "{e}"
    );
    for d in [Drive::RigidGrips, Drive::DeadLoad, Drive::Spring(0.7)] {
        let md = ContactLaw::new(0.8, None, None).unwrap();
        assert_eq!(md.model(), ContactModel::Md);
        let spec = CycleSpec {
            law: md,
            drive: d,
            max_load: 2.0,
        };
        assert_eq!(
            json(&spec.run().unwrap()),
            json(&cycle::cycle(0.8, d, 2.0).unwrap())
        );
        let law = ContactLaw::new(2.0, Some(0.3), Some(3.0)).unwrap();
        assert_eq!(
            (law.model(), law.lambda()),
            (ContactModel::SolidAndMeniscus, Some(2.0))
        );
        let spec = CycleSpec { law, ..spec };
        assert_eq!(json(&spec.run().unwrap()), json(&wet(2.0, 0.3, 3.0, d)));
    }
    let bad = CycleSpec {
        law: ContactLaw::md(1.0),
        drive: Drive::Spring(-1.0),
        max_load: 2.0,
    };
    let e = bad.run().unwrap_err().to_string();
    assert!(e.contains("spring stiffness") && e.contains("-1"), "{e}");
    let bad = CycleSpec {
        law: ContactLaw::new(1.0, Some(0.2), Some(-1.0)).unwrap(),
        ..bad
    };
    assert!(bad
        .run()
        .unwrap_err()
        .to_string()
        .contains("range ratio = -1"));
}
