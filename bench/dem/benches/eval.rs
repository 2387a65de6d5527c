//! The DEM force-overlap law's cost, on one thread: per contact evaluation on streams of 4096
//! contacts (each with its own history), through the Rust API and through the C ABI, and the
//! one-off build of a law per pair of materials.
//!
//! `cargo bench -p tabor-dem-bench -- --warm-up-time 1 --measurement-time 3`. The `eval` groups
//! report elements (evaluations) per second; the time per evaluation is the time per iteration
//! divided by 4096.

use std::hint::black_box;

use criterion::{criterion_group, criterion_main, BenchmarkId, Criterion, Throughput};
use tabor::dem::{DemLaw, History, Pair};
use tabor_dem::{tabor_dem_law_eval, tabor_dem_law_free, tabor_dem_law_new, TaborDemLaw};
use tabor_dem_bench::{
    c_pair, contact_stream, law, mixed_stream, pair, pair_contact, wet_law, Stream, CONTACTS,
    OVERLAP_MAX,
};

/// The C ABI's evaluation, as a C caller sees it: a call through a pointer, never inlined.
type EvalFn = unsafe extern "C" fn(*const TaborDemLaw, f64, *mut u8, *mut f64, *mut f64) -> i32;

/// One pass of the stream through the normalised law: each contact's load and stiffness into
/// `out`, its history updated.
#[inline(never)]
fn pass_law(law: &DemLaw, overlap: &[f64], history: &mut [History], out: &mut [[f64; 2]]) {
    for ((&d, h), o) in overlap.iter().zip(history.iter_mut()).zip(out.iter_mut()) {
        let e = law.eval(d, h);
        *o = [e.load, e.stiffness];
    }
}

/// The same through the SI pair (metres in, newtons out).
#[inline(never)]
fn pass_pair(pair: &Pair, overlap_m: &[f64], history: &mut [History], out: &mut [[f64; 2]]) {
    for ((&d, h), o) in overlap_m.iter().zip(history.iter_mut()).zip(out.iter_mut()) {
        let e = pair.eval(d, h);
        *o = [e.force_n, e.stiffness_n_m];
    }
}

/// The same through the C ABI; returns the return codes or'ed (a caller checks them).
#[inline(never)]
fn pass_c(
    eval: EvalFn,
    law: *const TaborDemLaw,
    overlap_m: &[f64],
    history: &mut [u8],
    out: &mut [[f64; 2]],
) -> i32 {
    let mut rc = 0;
    for ((&d, h), o) in overlap_m.iter().zip(history.iter_mut()).zip(out.iter_mut()) {
        let [f, k] = o;
        // SAFETY: a live law and valid pointers.
        rc |= unsafe { eval(law, d, h, f, k) };
    }
    rc
}

/// The streams' lambdas: with a non-contact branch, near lambda_D (the finest table: 6457
/// nodes, 206 kB), and DMT-like.
const LAMBDAS: [f64; 3] = [0.5, 0.94, 10.0];

/// The laws of `lambdas` by name, and with `wet` the wet law.
fn laws(lambdas: &[f64], wet: bool) -> Vec<(String, DemLaw)> {
    let mut v: Vec<(String, DemLaw)> = lambdas.iter().map(|&l| (l.to_string(), law(l))).collect();
    if wet {
        v.push(("wet".into(), wet_law()));
    }
    v
}

fn bench_law(
    c: &mut Criterion,
    group: &str,
    laws: Vec<(String, DemLaw)>,
    stream: fn(&DemLaw, u64) -> Stream,
) {
    let mut g = c.benchmark_group(group);
    g.throughput(Throughput::Elements(CONTACTS as u64));
    for (name, law) in laws {
        let s = stream(&law, 1);
        eprintln!(
            "{group}/{name}: {} contacts free, non-contact, contact: {:?}; table {} nodes",
            CONTACTS,
            s.counts(&law),
            law.nodes
        );
        let mut history = s.history.clone();
        let mut out = vec![[0.0; 2]; CONTACTS];
        g.bench_with_input(
            BenchmarkId::from_parameter(name),
            &s.overlap,
            |b, overlap| {
                b.iter(|| {
                    pass_law(
                        black_box(&law),
                        black_box(overlap),
                        black_box(&mut history),
                        &mut out,
                    );
                    black_box(&mut out);
                })
            },
        );
    }
    g.finish();
}

fn eval_contact(c: &mut Criterion) {
    bench_law(c, "eval/contact", laws(&LAMBDAS, true), contact_stream);
}

fn eval_mixed(c: &mut Criterion) {
    bench_law(c, "eval/mixed", laws(&[0.5, 10.0], true), mixed_stream);
}

fn eval_pair(c: &mut Criterion) {
    let mut g = c.benchmark_group("eval/pair_si");
    g.throughput(Throughput::Elements(CONTACTS as u64));
    for lambda in [0.5, 10.0] {
        let pair = pair(lambda);
        let s = contact_stream(&pair.law, 1);
        let overlap_m = s.overlap_m(pair.length_scale);
        let mut history = s.history.clone();
        let mut out = vec![[0.0; 2]; CONTACTS];
        g.bench_with_input(
            BenchmarkId::from_parameter(lambda),
            &overlap_m,
            |b, overlap_m| {
                b.iter(|| {
                    pass_pair(
                        black_box(&pair),
                        black_box(overlap_m),
                        black_box(&mut history),
                        &mut out,
                    );
                    black_box(&mut out);
                })
            },
        );
    }
    g.finish();
}

fn eval_c_abi(c: &mut Criterion) {
    let mut g = c.benchmark_group("eval/c_abi");
    g.throughput(Throughput::Elements(CONTACTS as u64));
    for (name, lambda, stream) in [
        (
            "contact/0.5",
            0.5,
            contact_stream as fn(&DemLaw, u64) -> Stream,
        ),
        ("contact/10", 10.0, contact_stream),
        ("mixed/0.5", 0.5, mixed_stream),
        ("mixed/10", 10.0, mixed_stream),
    ] {
        let p = c_pair(lambda);
        // SAFETY: a valid pair, no message buffer.
        let law = unsafe { tabor_dem_law_new(&p, std::ptr::null_mut(), 0) };
        assert!(!law.is_null());
        // The same stream as the Rust benchmarks', in metres.
        let rust = pair(lambda);
        let s = stream(&rust.law, 1);
        let overlap_m = s.overlap_m(rust.length_scale);
        let mut history = s.history_bytes();
        let mut out = vec![[0.0; 2]; CONTACTS];
        let eval: EvalFn = tabor_dem_law_eval;
        g.bench_with_input(
            BenchmarkId::from_parameter(name),
            &overlap_m,
            |b, overlap_m| {
                b.iter(|| {
                    let rc = pass_c(
                        black_box(eval),
                        black_box(law),
                        black_box(overlap_m),
                        black_box(&mut history),
                        &mut out,
                    );
                    black_box(rc);
                    black_box(&mut out);
                })
            },
        );
        assert_eq!(
            history,
            s.history_bytes(),
            "the histories are stationary through the C ABI too"
        );
        // SAFETY: from tabor_dem_law_new, freed once.
        unsafe { tabor_dem_law_free(law) };
    }
    g.finish();
}

fn build(c: &mut Criterion) {
    let mut g = c.benchmark_group("build");
    g.sample_size(10);
    for lambda in LAMBDAS {
        g.bench_with_input(BenchmarkId::new("law", lambda), &lambda, |b, &lambda| {
            b.iter(|| DemLaw::new(black_box(lambda), black_box(OVERLAP_MAX)).expect("law"))
        });
    }
    for lambda in LAMBDAS {
        let contact = pair_contact(lambda);
        let max = OVERLAP_MAX * contact.approach_scale();
        g.bench_with_input(BenchmarkId::new("pair", lambda), &contact, |b, &contact| {
            b.iter(|| Pair::new(black_box(contact), black_box(max)).expect("pair"))
        });
    }
    // The C ABI's build adds the loop energy (a quadrature over the exact branches) for its info.
    for lambda in LAMBDAS {
        let p = c_pair(lambda);
        g.bench_with_input(BenchmarkId::new("c_abi", lambda), &p, |b, p| {
            b.iter(|| {
                // SAFETY: a valid pair, no message buffer; the law freed once.
                unsafe {
                    let law = tabor_dem_law_new(black_box(p), std::ptr::null_mut(), 0);
                    assert!(!law.is_null());
                    tabor_dem_law_free(black_box(law));
                }
            })
        });
    }
    g.finish();
}

criterion_group!(
    benches,
    eval_contact,
    eval_mixed,
    eval_pair,
    eval_c_abi,
    build
);
criterion_main!(benches);
