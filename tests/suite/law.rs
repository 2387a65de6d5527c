//! The conformance suite of the law layer: every law ([`ContactLaw`]'s variants, each through
//! the one trait) must pass it. Its pieces join, its slopes in the piece's parameter (and in
//! lambda) are the differences of its states, its pull-off is its path's most tensile load, its
//! exact folds are the extremes of its contact piece, its cycle exists or is refused in one
//! line and follows its drive (folds of the control, jumps at constant control), the one
//! follower at infinite stiffness follows its rigid-grip stretches, and its limits hold (MD towards DMT and JKR, two zones of one range or without a
//! meniscus = MD). A new law adds itself to `laws()`.

use std::sync::OnceLock;
use tabor::cycle::{self, Drive, Phase};
use tabor::law::{ContactLaw, Law, Piece, Tip, TipClosed, A_START};
use tabor::physics::tip::Shape;
use tabor::physics::two_zone::Zones;
use tabor::ContactModel;

/// Every law, at parameters across its range: the closed forms, MD from the DMT side to the
/// JKR side, two zones with the meniscus longer, much longer and shorter than the solid's zone.
fn laws() -> Vec<ContactLaw> {
    let mut v = vec![ContactLaw::Hertz, ContactLaw::Dmt, ContactLaw::Jkr];
    v.extend([0.05, 0.7, 6.0, 40.0].map(ContactLaw::md));
    v.extend(
        [(0.5, 0.2, 5.0), (2.0, 0.05, 10.0), (1.0, 3.0, 0.3)]
            .map(|(l, r, e)| ContactLaw::solid_and_meniscus(l, r, e)),
    );
    v.extend(
        [(1.0, 0.3), (1.5, 2.0), (3.0, 0.8), (4.0, 10.0)]
            .map(|(n, l)| ContactLaw::Tip(Tip::new(Shape::Power { exponent: n }, l).unwrap())),
    );
    let capped = Shape::CappedCone {
        rho: 1.5,
        half_angle: 20f64.to_radians(),
    };
    v.extend([0.2, 3.0].map(|l| ContactLaw::Tip(Tip::new(capped, l).unwrap())));
    for shape in [
        Shape::Power { exponent: 1.0 },
        Shape::Power { exponent: 3.0 },
        capped,
    ] {
        v.extend(
            [false, true].map(|adhesive| ContactLaw::TipClosed(TipClosed { shape, adhesive })),
        );
    }
    v
}

/// The free piece ends where the first piece starts (DMT's load apart: its adhesion, -2, acts
/// from the touch); each piece's end is the next one's start (the contact piece starts at
/// A = 1e-9, where JKR's approach is -(2/3) sqrt(6 A), 5e-5: joints within 1e-4); the contact
/// piece reaches the radius asked for.
#[test]
fn each_laws_pieces_join() {
    for law in laws() {
        let at = format!("{law:?}");
        let pieces = law.pieces(4.0);
        let first = law.state(pieces[0].0, pieces[0].1);
        assert!((first.approach - law.free_end()).abs() <= 1e-4, "{at}");
        let touch = if law.model() == ContactModel::Dmt {
            -2.0
        } else {
            0.0
        };
        assert!((first.load - touch).abs() <= 1e-6, "{at}: {}", first.load);
        for w in pieces.windows(2) {
            let (end, start) = (law.state(w[0].0, w[0].2), law.state(w[1].0, w[1].1));
            assert!(
                (end.load - start.load).abs() <= 1e-4,
                "{at}: {end:?} {start:?}"
            );
            assert!((end.approach - start.approach).abs() <= 1e-4, "{at}");
        }
        let (piece, t0, t1) = *pieces.last().unwrap();
        assert_eq!(piece, Piece::Contact, "{at}");
        let (bottom, top) = (law.state(piece, t0), law.state(piece, t1));
        assert!(
            (bottom.a / A_START - 1.0).abs() <= 1e-6,
            "{at}: {}",
            bottom.a
        );
        assert!((top.a / 4.0 - 1.0).abs() <= 1e-12, "{at}: {}", top.a);
        assert_eq!(law.t_of_radius(4.0), t1, "{at}");
    }
}

/// Every state's slopes in t are the central differences of the states, on every piece.
#[test]
fn slopes_in_t_are_the_differences() {
    for law in laws() {
        for (piece, t0, t1) in law.pieces(3.0) {
            for k in 1..20 {
                let t = t0 + (t1 - t0) * k as f64 / 20.0;
                let h = 1e-5 * (1.0 + t.abs());
                let (p, up, down) = (
                    law.state(piece, t),
                    law.state(piece, t + h),
                    law.state(piece, t - h),
                );
                for (name, slope, diff) in [
                    ("load", p.dload, (up.load - down.load) / (2.0 * h)),
                    (
                        "approach",
                        p.dapproach,
                        (up.approach - down.approach) / (2.0 * h),
                    ),
                    ("a", p.da, (up.a - down.a) / (2.0 * h)),
                ] {
                    let scale = diff.abs().max(1e-3);
                    assert!(
                        (slope - diff).abs() <= 1e-5 * scale,
                        "{law:?}, {piece:?} t {t}: d{name}/dt {slope} against {diff}"
                    );
                }
            }
        }
    }
}

/// Maugis-Dugdale's slopes in lambda at fixed t are the differences of the states at lambda
/// +- h; the closed forms have none (zero), the two-zone law's are taken by differences (NaN).
#[test]
fn lambda_slopes_are_the_differences() {
    for lambda in [0.05, 0.7, 6.0] {
        let c_end = tabor::physics::md::zero_radius_end(lambda).c;
        for (piece, t) in [
            (Piece::NonContact, 0.3 * c_end),
            (Piece::NonContact, 0.9 * c_end),
            (Piece::Contact, -3.0),
            (Piece::Contact, 0.5),
            (Piece::Contact, 4.0),
        ] {
            let (dl, dd) = ContactLaw::md(lambda).state_dlambda(piece, t);
            let h = 1e-5 * lambda;
            let (p, m) = (
                ContactLaw::md(lambda + h).state(piece, t),
                ContactLaw::md(lambda - h).state(piece, t),
            );
            let fl = (p.load - m.load) / (2.0 * h);
            let fd = (p.approach - m.approach) / (2.0 * h);
            let at = format!("{piece:?} at lambda {lambda}, t {t}");
            assert!(
                (dl - fl).abs() <= 1e-7 * fl.abs().max(1.0),
                "{at}: {dl} {fl}"
            );
            assert!(
                (dd - fd).abs() <= 1e-7 * fd.abs().max(1.0),
                "{at}: {dd} {fd}"
            );
        }
    }
    assert_eq!(
        ContactLaw::Jkr.state_dlambda(Piece::Contact, 2.0),
        (0.0, 0.0)
    );
    assert_eq!(
        ContactLaw::md(1.0).state_dlambda(Piece::Free, 2.0),
        (0.0, 0.0)
    );
    assert!(ContactLaw::solid_and_meniscus(1.0, 0.2, 5.0)
        .state_dlambda(Piece::Contact, 1.0)
        .0
        .is_nan());
}

/// The most tensile load along the contact piece and the smallest approach: sampled at 4000
/// points, then twice more densely (1000 points) around each sampled extreme, a step 2e-9 of
/// the piece at the end. Computed once for the laws (all but Hertz) and shared by the tests.
fn contact_extremes(law: &ContactLaw) -> (f64, f64) {
    static ALL: OnceLock<Vec<(ContactLaw, (f64, f64))>> = OnceLock::new();
    let all = ALL.get_or_init(|| {
        laws()
            .into_iter()
            .filter(|l| l.model() != ContactModel::Hertz)
            .map(|l| {
                let e = sampled_extremes(&l);
                (l, e)
            })
            .collect()
    });
    all.iter()
        .find(|(l, _)| l == law)
        .map(|(_, e)| *e)
        .expect("a law of laws()")
}

fn sampled_extremes(law: &ContactLaw) -> (f64, f64) {
    let (_, t0, t1) = *law.pieces(8.0).last().unwrap();
    let at = |t: f64| law.state(Piece::Contact, t);
    let lowest = |value: &dyn Fn(f64) -> f64| {
        // The least of n + 1 samples over [lo, hi] and where it is.
        let scan = |lo: f64, hi: f64, n: usize| {
            (0..=n)
                .map(|i| lo + (hi - lo) * i as f64 / n as f64)
                .filter(|&t| t >= t0 && t <= t1)
                .map(|t| (t, value(t)))
                .filter(|(_, v)| v.is_finite())
                .fold((t0, f64::INFINITY), |b, p| if p.1 < b.1 { p } else { b })
        };
        let h = (t1 - t0) / 4000.0;
        let (c, _) = scan(t0, t1, 4000);
        let (c, _) = scan(c - h, c + h, 1000);
        let h = h / 500.0;
        scan(c - h, c + h, 1000).1
    };
    (lowest(&|t| at(t).load), lowest(&|t| at(t).approach))
}

/// The load-controlled pull-off a fit starts w from is the law's most tensile load on contact:
/// exact for the closed forms and two zones, within 2% for Maugis-Dugdale (the
/// Johnson-Greenwood fit); MD's tends to DMT's and JKR's at its ends; Hertz has none.
#[test]
fn pulloffs_are_the_paths_most_tensile_loads() {
    assert_eq!(ContactLaw::Hertz.pulloff(), 0.0);
    assert!((ContactLaw::md(1e-4).pulloff() - ContactLaw::Dmt.pulloff()).abs() < 1e-3);
    assert!((ContactLaw::md(1e4).pulloff() - ContactLaw::Jkr.pulloff()).abs() < 1e-3);
    for law in laws()
        .into_iter()
        .filter(|l| l.model() != ContactModel::Hertz)
    {
        let (lowest, _) = contact_extremes(&law);
        let tol = if law.model() == ContactModel::Md {
            0.02
        } else {
            1e-6
        };
        assert!(
            (-lowest / law.pulloff() - 1.0).abs() < tol,
            "{law:?}: {lowest} {}",
            law.pulloff()
        );
    }
}

/// The exact folds a cycle puts its jumps at: under dead load the most tensile load of the
/// contact piece, under rigid grips its smallest approach (MD's and two zones'; each law's
/// folds from its own solver, the extremes from its states).
#[test]
fn folds_are_the_extremes_of_the_contact_piece() {
    for law in laws()
        .into_iter()
        .filter(|l| l.lambda().is_some_and(|l| l < 20.0))
    {
        let (lowest_load, lowest_approach) = contact_extremes(&law);
        let near = |a: f64| tabor::cycle::PathPoint {
            branch: tabor::cycle::Branch::Contact,
            approach: 0.0,
            load: 0.0,
            a,
            c: 0.0,
        };
        let dead = law.fold(Drive::DeadLoad, &near(1.0));
        let grips = law.fold(Drive::RigidGrips, &near(1.0));
        // A fold at A = 0 (the contact branch has none above it) is not a jump of the branch.
        if let Some(f) = dead {
            assert!(
                (f.load - lowest_load).abs() <= 1e-6 * lowest_load.abs(),
                "{law:?}: dead-load fold {} against {lowest_load}",
                f.load
            );
        }
        if let Some(f) = grips {
            assert!(
                (f.approach - lowest_approach).abs() <= 1e-6 * lowest_approach.abs().max(1.0),
                "{law:?}: rigid-grip fold {} against {lowest_approach}",
                f.approach
            );
        }
        assert!(dead.is_some() || grips.is_some(), "{law:?}: no fold at all");
    }
}

/// Every law with a Maugis parameter has a cycle through the one follower, whose retract
/// leaves the contact branch at the law's fold; a closed form's is refused in one line naming
/// it.
#[test]
fn cycles_jump_at_the_laws_folds_or_are_refused() {
    for law in laws() {
        let c = cycle::run(&law, Drive::RigidGrips, 2.0);
        if law.lambda().is_none() {
            let e = c.unwrap_err().to_string();
            assert!(
                e.contains(law.model().label()) && e.contains("cycle") && !e.contains('\n'),
                "{e}"
            );
            continue;
        }
        let c = c.unwrap();
        assert_eq!(Some(c.lambda), law.lambda());
        let j = c
            .jumps
            .iter()
            .find(|j| j.phase == Phase::Retract && j.from.branch == cycle::Branch::Contact);
        if let Some(j) = j {
            // The follower's fold (a secant on the control's slope) against the law's own (its
            // solver's pull-off): the approach, stationary there, agrees to rounding; the load
            // to the placing of the law's fold (the two-zone solver's is a golden-section
            // extreme, good to about the square root of the rounding).
            let f = law.fold(Drive::RigidGrips, &j.from).unwrap();
            assert!(
                (j.from.load - f.load).abs() <= 1e-7 * f.load.abs().max(1.0)
                    && (j.from.approach - f.approach).abs() <= 1e-12 * f.approach.abs().max(1.0),
                "{law:?}: the cycle's fold ({}, {}) against the law's ({}, {})",
                j.from.load,
                j.from.approach,
                f.load,
                f.approach
            );
        }
    }
}

/// Every cycle of every law under every drive is a path its drive can take: the control never
/// turns back (rising on the approach, falling on the retract, the same across a jump), and
/// each jump off the contact branch leaves it at a fold of that control (its slope along the
/// branch zero: under a spring dPbar/dDbar = -kbar, taken from the law's states) or at its
/// A -> 0 end; the branch changes only between equal states or by a jump; under a dead load
/// the retract's jump separates the surfaces for good.
#[test]
fn cycles_follow_their_drive() {
    let drives = [
        Drive::RigidGrips,
        Drive::DeadLoad,
        Drive::Spring(0.5),
        Drive::Spring(20.0),
    ];
    // With MD far on the DMT side, where the snap onto the zone alone is shorter than the
    // nodes' spacing (C = 16 lambda / (3 pi)).
    let small = [0.01, 1e-3].map(ContactLaw::md);
    for law in laws()
        .into_iter()
        .filter(|l| l.lambda().is_some())
        .chain(small)
    {
        for drive in drives {
            let at = format!("{law:?} {drive:?}");
            let c = cycle::run(&law, drive, 2.0).unwrap();
            // The branch changes between equal states (the pieces join within 1e-4), unless by
            // a jump, and each jump's landing is the step after its fold.
            let near = |x: f64, y: f64| (x - y).abs() <= 1e-4 * (1.0 + x.abs());
            for w in c
                .steps
                .windows(2)
                .filter(|w| w[0].phase == w[1].phase && !w[1].jump)
            {
                let (a, b) = (w[0].point, w[1].point);
                assert!(
                    a.branch == b.branch || (near(a.load, b.load) && near(a.approach, b.approach)),
                    "{at}: {a:?} to {b:?} without a jump"
                );
            }
            let landings = c.steps.iter().filter(|s| s.jump).count();
            assert_eq!(
                landings,
                c.jumps.iter().filter(|j| j.to.is_some()).count(),
                "{at}"
            );
            let u = |p: &cycle::PathPoint| tabor::law::path::control_of(p, drive);
            for w in c.steps.windows(2).filter(|w| w[0].phase == w[1].phase) {
                let (a, b) = (u(&w[0].point), u(&w[1].point));
                let rise = if w[0].phase == Phase::Approach {
                    b - a
                } else {
                    a - b
                };
                assert!(rise >= -1e-9 * (1.0 + a.abs()), "{at}: {a} then {b}");
            }
            for j in &c.jumps {
                if let Some(to) = j.to {
                    let (a, b) = (u(&j.from), u(&to));
                    assert!((a - b).abs() <= 1e-9 * (1.0 + a.abs()), "{at}: {a} to {b}");
                }
                if j.from.branch != cycle::Branch::Contact || j.from.a < 1e-6 {
                    continue;
                }
                let p = law.state(Piece::Contact, law.t_of_radius(j.from.a));
                // The control's slope against the state's speed along the branch.
                let slope = match drive {
                    Drive::RigidGrips => p.dapproach,
                    Drive::DeadLoad => p.dload,
                    Drive::Spring(k) => p.dapproach + p.dload / k,
                };
                let terms = p.dapproach.abs() + p.dload.abs();
                // (Slopes in t that vanish: the branch's far end, A -> 0 as t -> -inf.)
                assert!(
                    slope.abs() <= 1e-6 * terms || terms <= 1e-12,
                    "{at}: slope {slope} of {terms} at A = {}",
                    j.from.a
                );
            }
            let out = c.jumps.iter().rfind(|j| j.phase == Phase::Retract);
            assert_eq!(
                drive == Drive::DeadLoad,
                out.is_some_and(|j| j.to.is_none()) && c.hysteresis.is_none(),
                "{at}"
            );
        }
    }
}

/// Two zones of one range are Maugis-Dugdale at the summed lambda, and a meniscus without
/// stress is Maugis-Dugdale at the solid's: the same pieces and states, bit for bit.
#[test]
fn one_zone_two_zone_laws_are_md() {
    let (dry, md) = (
        ContactLaw::solid_and_meniscus(0.8, 0.0, 3.0),
        ContactLaw::md(0.8),
    );
    assert_eq!(dry.pieces(2.0), md.pieces(2.0));
    let t = md.t_of_radius(1.3);
    assert_eq!(dry.state(Piece::Contact, t), md.state(Piece::Contact, t));
    let z = Zones::from_ratios(0.8, 0.5, 1.0).unwrap();
    let summed = ContactLaw::md(z.lambda[0] + z.lambda[1]);
    let one_range = ContactLaw::solid_and_meniscus(0.8, 0.5, 1.0);
    assert_eq!(one_range.pieces(2.0), summed.pieces(2.0));
    let t = summed.t_of_radius(0.9);
    assert_eq!(
        one_range.state(Piece::Contact, t),
        summed.state(Piece::Contact, t)
    );
    let exact = tabor::LambdaContext::new(z.lambda[0] + z.lambda[1])
        .unwrap()
        .load_pulloff
        .load;
    assert!((one_range.pulloff() + exact).abs() <= 1e-12);
}

/// The two-zone non-contact piece's first stretch is the longer zone's disc alone: its load
/// `-(pi/2) lambda_L C^2` in closed form, its slope `-pi lambda_L C`; the free end is the longer
/// range; the pull-off lies within the two-zone bounds [3/2, 2].
#[test]
fn two_zone_closed_forms_and_bounds() {
    let pi = std::f64::consts::PI;
    let law = ContactLaw::solid_and_meniscus(0.5, 0.2, 5.0);
    let z = Zones::from_ratios(0.5, 0.2, 5.0).unwrap();
    let long = 1;
    assert_eq!(law.free_end(), -z.range[long]);
    let c_l = law.pieces(3.0)[0].2 - tabor::physics::two_zone::non_contact_ends(&z).unwrap().1;
    for c in [0.0, 0.3 * c_l, c_l] {
        let p = law.state(Piece::NonContact, c);
        let l = z.lambda[long];
        assert!((p.load + pi / 2.0 * l * c * c).abs() <= 1e-15, "C {c}");
        assert!(
            (p.dload + pi * l * c).abs() <= 1e-6 * (1.0 + c),
            "C {c}: {}",
            p.dload
        );
    }
    for law in laws()
        .into_iter()
        .filter(|l| l.model() == ContactModel::SolidAndMeniscus)
    {
        let p = law.pulloff();
        assert!((1.5..=2.0).contains(&p), "{law:?}: {p}");
    }
}

/// The value front ends build serialises as before the law layer: the model's name under
/// `model`, then the law's numbers.
#[test]
fn contact_laws_serialise_with_their_model() {
    let j = |l: ContactLaw| serde_json::to_string(&l).unwrap();
    assert_eq!(j(ContactLaw::md(1.5)), r#"{"model":"md","lambda":1.5}"#);
    assert_eq!(
        j(ContactLaw::solid_and_meniscus(1.0, 0.2, 5.0)),
        r#"{"model":"solid_and_meniscus","lambda":1.0,"stress_ratio":0.2,"range_ratio":5.0}"#
    );
    assert_eq!(j(ContactLaw::Jkr), r#"{"model":"jkr"}"#);
    for law in laws() {
        assert_eq!(law.model(), law.law().model());
    }
}

/// The energy release rate at the contact's edge equals w (Griffith's condition, the one every
/// adhesive law's contact states satisfy), from each law's states and a formula of its own:
/// Maugis-Dugdale's J-integral through the Dugdale zone (`physics::fields`, the gap at C over
/// h0), the two-zone profile's J over the total w at the law's radii (the sum of each zone's
/// stress times its gap at its edge), JKR's stress intensity `(A^3 - Pbar) / (2 A sqrt(pi A))`
/// with `G/w = (2 pi / 3) K^2` (a tip's JKR-type law with its `Qbar(A)` for `A^3`: the flat
/// punch's load `(3/2) A (Fbar(A) - Dbar)`); Hertz, Sneddon's punch and DMT have no crack (K = 0).
#[test]
fn the_energy_release_rate_at_the_edge_is_w() {
    use tabor::physics::fields::MdGeometry;
    use tabor::profile::two_zone::two_zone_profile;
    for law in laws() {
        let (_, t0, t1) = *law.pieces(3.0).last().unwrap();
        for k in 1..10 {
            let t = t0 + (t1 - t0) * k as f64 / 10.0;
            let s = law.state(Piece::Contact, t);
            let at = format!("{law:?} at A = {}", s.a);
            let g = match law {
                ContactLaw::Md(md) => MdGeometry {
                    lambda: md.lambda,
                    a: s.a,
                    mu: (-t).exp(),
                }
                .energy_release_over_w(),
                // The J-integral through the zone, s0 times the gap at C over w: the gap from
                // its Abel form in T by double-exponential quadrature (not the law's rule in phi).
                ContactLaw::Tip(tip) => {
                    let (a, c) = (s.a, tip.at_radius(s.a).c);
                    let fa = tip.shape.abel(a).0;
                    // T = C - (C - A) v^2 takes the 1/sqrt(C - T) out of the integrand; a
                    // capped cone's joint (Fbar'' singular there) splits the range.
                    let v_of = |x: f64| ((c - x) / (c - a)).sqrt();
                    let mut cuts = vec![0.0, 1.0];
                    if let Shape::CappedCone { rho, half_angle } = tip.shape {
                        let b = rho * half_angle.cos();
                        if a < b && b < c {
                            cuts.insert(1, v_of(b));
                        }
                    }
                    let profile: f64 = cuts
                        .windows(2)
                        .map(|w| {
                            quadrature::double_exponential::integrate(
                                |v: f64| {
                                    let x = c - (c - a) * v * v;
                                    (tip.shape.abel(x).0 - fa) * 2.0 * (c - a).sqrt()
                                        / (c + x).sqrt()
                                },
                                w[0],
                                w[1],
                                1e-14,
                            )
                            .integral
                        })
                        .sum();
                    let m = c / a;
                    let mu = (m * m - 1.0).sqrt();
                    let l = tip.lambda;
                    l * profile + 4.0 / 3.0 * l * l * a * (mu * mu.atan() - m + 1.0)
                }
                ContactLaw::SolidAndMeniscus(z) => {
                    let p = two_zone_profile(
                        z.lambda,
                        z.stress_ratio,
                        z.range_ratio,
                        tabor::Given::Radius(s.a),
                        16,
                    )
                    .unwrap();
                    assert!(
                        (p.models[0].load - s.load).abs() <= 1e-8 * s.load.abs().max(1.0),
                        "{at}: profile load {} against {}",
                        p.models[0].load,
                        s.load
                    );
                    p.energy_release_rate_over_w
                }
                _ => {
                    let adhesion = if law.model() == ContactModel::Dmt {
                        2.0
                    } else {
                        0.0
                    };
                    // A tip's closed forms: its adhesion-free load Qbar(A) for the sphere's A^3.
                    let q = match law {
                        ContactLaw::TipClosed(c) => c.shape.load(s.a).0,
                        _ => s.a.powi(3),
                    };
                    let k_i =
                        (q - s.load - adhesion) / (2.0 * s.a * (std::f64::consts::PI * s.a).sqrt());
                    let g = 2.0 * std::f64::consts::PI / 3.0 * k_i * k_i;
                    if law.model() != ContactModel::Jkr {
                        assert!(g <= 1e-20, "{at}: {g}");
                        continue;
                    }
                    g
                }
            };
            assert!((g - 1.0).abs() <= 1e-8, "{at}: G/w = {g}");
        }
    }
}

/// One physics, two codes: the follower (`law::follow::DrivenPath`, the fits' and the cycles')
/// at infinite stiffness follows rigid grips, as the stretches of `law::stretch` (the DEM law's
/// and the cycle loop's) do, each found its own way (nodes and a secant on the slope; probes and
/// bisection). On the approach from apart to an overlap of 4 and the retract back, both give the
/// same load at every overlap away from the jumps (1e-6 of a stretch's end), within 1e-11 of
/// 1 + |load|, for every law.
#[test]
fn the_follower_at_infinite_stiffness_follows_the_stretches() {
    use tabor::law::follow::{Direction, DrivenPath};
    use tabor::law::stretch::Stretches;
    let top = 4.0;
    let mut checked = 0;
    let mut worst = 0.0f64;
    for law in laws() {
        let Ok(st) = Stretches::of(&law, top) else {
            continue;
        };
        let sp = DrivenPath::of(law, f64::INFINITY, top);
        let marks = st.marks();
        let lo = st.lowest().min(st.entry()) - 0.5;
        let n = 600;
        let grid: Vec<f64> = (0..=n)
            .map(|i| lo + (top - lo) * i as f64 / n as f64)
            .collect();
        let away = |d: f64| marks.iter().all(|m| (d - m).abs() > 1e-6 * (1.0 + m.abs()));
        let mut k = 0;
        let mut compare = |k: usize, d: f64, dir: Direction| {
            if !away(d) {
                return;
            }
            let a = st.exact(&law, k, d).unwrap();
            let b = sp.at(d, dir).load;
            let e = (a - b).abs() / (1.0 + a.abs());
            worst = worst.max(e);
            assert!(
                e <= 1e-11,
                "{law:?}, {dir:?} at overlap {d}: stretches {a}, follower {b}"
            );
        };
        for &d in &grid {
            k = st.next(k, d);
            compare(k, d, Direction::Approach);
        }
        for &d in grid.iter().rev() {
            k = st.next(k, d);
            compare(k, d, Direction::Retract);
        }
        checked += 1;
    }
    // 22 laws, largest difference 5.5e-14 (2026-11-29).
    println!("{checked} laws: largest load difference {worst:e} (relative to 1 + |load|)");
    assert_eq!(checked, laws().len(), "every law has rigid-grip stretches");
}
