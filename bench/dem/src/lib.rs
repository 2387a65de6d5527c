//! Benchmarks of tabor's DEM force-overlap law (`cargo bench -p tabor-dem-bench`): the pairs of
//! materials of a given lambda and the streams of contacts that `benches/eval.rs` times.
//!
//! A stream is what a particle code hands the law in one time step: an array of contacts, each
//! with its overlap and its own history, in no particular order. Every contact's history is one
//! that its overlap keeps (`DemLaw::next_history(h, overlap) == h`), so a stream is the same in
//! every pass of a benchmark and its branches are as mixed in the last pass as in the first.

use tabor::dem::{DemLaw, History, Pair};
use tabor::physics::params::{effective_radius, reduced_modulus, Body, Contact, ForceRange};
use tabor_dem::TaborDemPair;

/// The largest overlap of every table here (approach units): `tabor dem-law`'s default.
pub const OVERLAP_MAX: f64 = 10.0;
/// The largest overlap of a stream (approach units): a few, well inside the table.
pub const STREAM_MAX: f64 = 5.0;
/// Contacts per stream.
pub const CONTACTS: usize = 4096;

/// The overlaps and histories of a stream; `si` turns the overlaps into metres.
#[derive(Clone, Debug)]
pub struct Stream {
    /// Overlaps (approach units).
    pub overlap: Vec<f64>,
    /// Each contact's history.
    pub history: Vec<History>,
}

impl Stream {
    /// The overlaps in metres (`length_scale` metres per approach unit).
    pub fn overlap_m(&self, length_scale: f64) -> Vec<f64> {
        self.overlap.iter().map(|d| d * length_scale).collect()
    }

    /// The histories as the C ABI's bytes.
    pub fn history_bytes(&self) -> Vec<u8> {
        self.history.iter().map(|h| h.code()).collect()
    }

    /// How many contacts are on each kind of branch (free, non-contact, contact).
    pub fn counts(&self, law: &DemLaw) -> [usize; 3] {
        let mut n = [0; 3];
        for h in &self.history {
            n[law.branch(*h) as usize] += 1;
        }
        n
    }
}

/// A fixed-seed generator (splitmix64): the same streams in every run.
struct Rng(u64);

impl Rng {
    fn next(&mut self) -> u64 {
        self.0 = self.0.wrapping_add(0x9e37_79b9_7f4a_7c15);
        let mut z = self.0;
        z = (z ^ (z >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
        z = (z ^ (z >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
        z ^ (z >> 31)
    }

    /// Uniform in [lo, hi).
    fn uniform(&mut self, lo: f64, hi: f64) -> f64 {
        lo + (hi - lo) * (self.next() >> 11) as f64 * (1.0 / (1u64 << 53) as f64)
    }
}

/// The law of `lambda`, tabulated up to [`OVERLAP_MAX`].
pub fn law(lambda: f64) -> DemLaw {
    DemLaw::new(lambda, OVERLAP_MAX).expect("the law builds")
}

/// The wet law of a solid of lambda 1 and a meniscus of half its stress over three times its
/// range (`tabor dem-law --lambda 1 --stress-ratio 0.5 --range-ratio 3`: two non-contact
/// stretches, the retract caught by the meniscus), tabulated up to [`OVERLAP_MAX`].
pub fn wet_law() -> DemLaw {
    DemLaw::of_law(
        tabor::law::ContactLaw::solid_and_meniscus(1.0, 0.5, 3.0),
        OVERLAP_MAX,
    )
    .expect("the wet law builds")
}

/// Contacts on the contact branch: overlaps uniform from the jump-out (the contact branch's
/// fold) to [`STREAM_MAX`], every history `Contact`.
pub fn contact_stream(law: &DemLaw, seed: u64) -> Stream {
    let mut rng = Rng(seed);
    let overlap: Vec<f64> = (0..CONTACTS)
        .map(|_| rng.uniform(law.delta_out, STREAM_MAX))
        .collect();
    let contact = law
        .history(law.stretch_count() as u8 - 1)
        .expect("the contact stretch");
    let history = vec![contact; CONTACTS];
    check(law, &overlap, &history);
    Stream { overlap, history }
}

/// Contacts on every stretch the law has: each contact's stretch drawn with equal chances among
/// free (a gap beyond the attraction's reach, down to one approach unit below any force),
/// non-contact (where lambda has that branch) and contact, then its overlap uniform over that
/// stretch's range up to [`STREAM_MAX`]; the order is random, as in a neighbour list.
pub fn mixed_stream(law: &DemLaw, seed: u64) -> Stream {
    let mut rng = Rng(seed);
    let lo = law.lowest_overlap() - 1.0;
    let branches: Vec<History> = (0..law.stretch_count() as u8)
        .filter_map(|c| law.history(c))
        .collect();
    let mut overlap = Vec::with_capacity(CONTACTS);
    let mut history = Vec::with_capacity(CONTACTS);
    while overlap.len() < CONTACTS {
        let b = branches[(rng.next() % branches.len() as u64) as usize];
        // Rejection: an overlap that this history keeps.
        loop {
            let d = rng.uniform(lo, STREAM_MAX);
            if law.next_history(b, d) == b {
                overlap.push(d);
                history.push(b);
                break;
            }
        }
    }
    check(law, &overlap, &history);
    Stream { overlap, history }
}

/// Every contact keeps its history: the stream is stationary.
fn check(law: &DemLaw, overlap: &[f64], history: &[History]) {
    for (&d, &b) in overlap.iter().zip(history) {
        let mut h = b;
        let e = law.eval(d, &mut h);
        assert_eq!(h, b, "overlap {d} leaves its history {b:?}");
        assert!(e.load.is_finite() && !e.beyond_table);
    }
}

/// The bodies of the C ABI's tests: two polymer spheres (E = 3 GPa, nu = 0.35, R = 10 um each),
/// w = 0.1 J/m^2, the Dugdale stress chosen to give `lambda`, the table up to [`OVERLAP_MAX`]
/// approach units.
pub fn c_pair(lambda: f64) -> TaborDemPair {
    let body = Body {
        youngs_modulus_pa: 3e9,
        poisson_ratio: 0.35,
        radius_m: Some(10e-6),
    };
    let contact = contact(
        reduced_modulus(&body, &body).expect("modulus"),
        effective_radius(&body, &body).expect("radius"),
        lambda,
    );
    TaborDemPair {
        youngs_modulus1_pa: 3e9,
        poisson_ratio1: 0.35,
        radius1_m: 10e-6,
        youngs_modulus2_pa: 3e9,
        poisson_ratio2: 0.35,
        radius2_m: 10e-6,
        work_of_adhesion_j_m2: contact.work,
        dugdale_stress_pa: contact.s0,
        lj_range_m: 0.0,
        overlap_max_m: OVERLAP_MAX * contact.approach_scale(),
        relative_humidity: 0.0,
        contact_angle_deg: 0.0,
    }
}

/// The same pair as a [`Contact`] (for [`Pair::new`]).
pub fn pair_contact(lambda: f64) -> Contact {
    let p = c_pair(lambda);
    let body = |e, nu, r| Body {
        youngs_modulus_pa: e,
        poisson_ratio: nu,
        radius_m: Some(r),
    };
    let b1 = body(p.youngs_modulus1_pa, p.poisson_ratio1, p.radius1_m);
    let b2 = body(p.youngs_modulus2_pa, p.poisson_ratio2, p.radius2_m);
    Contact::new(
        effective_radius(&b1, &b2).expect("radius"),
        reduced_modulus(&b1, &b2).expect("modulus"),
        p.work_of_adhesion_j_m2,
        ForceRange::DugdaleStress(p.dugdale_stress_pa),
    )
    .expect("contact")
}

/// The pair of `lambda` in SI units, tabulated up to [`OVERLAP_MAX`] approach units.
pub fn pair(lambda: f64) -> Pair {
    let c = pair_contact(lambda);
    Pair::new(c, OVERLAP_MAX * c.approach_scale()).expect("the pair builds")
}

/// A contact of modulus `e_star`, radius `radius` and w = 0.1 J/m^2 whose Dugdale stress gives
/// `lambda` (lambda is proportional to s0).
fn contact(e_star: f64, radius: f64, lambda: f64) -> Contact {
    let work = 0.1;
    let unit = Contact::new(radius, e_star, work, ForceRange::DugdaleStress(1e6))
        .expect("contact")
        .lambda();
    Contact::new(
        radius,
        e_star,
        work,
        ForceRange::DugdaleStress(1e6 * lambda / unit),
    )
    .expect("contact")
}
