//! tabor::interrupt, in a test binary of its own and one test: an interrupt request is
//! process-wide while the interrupted work runs, and would stop the work of tests beside it.

use tabor::interrupt::{checkpoint, requested, Interrupted, Token};

/// Runs `f` under a token interrupted before it starts; returns the unwind's payload.
fn interrupted<T>(f: impl FnOnce() -> T) -> Box<dyn std::any::Any + Send> {
    let t = Token::new();
    let r = std::panic::catch_unwind(std::panic::AssertUnwindSafe(|| {
        t.run(|| {
            t.interrupt();
            f()
        })
    }));
    let payload = r.err().expect("the work stops at its first checkpoint");
    assert!(!requested(), "the request ends with the work");
    payload
}

#[test]
fn interrupted_work_unwinds_at_its_checkpoints_and_finished_work_is_left_alone() {
    let p = interrupted(checkpoint);
    assert_eq!(p.downcast_ref::<Interrupted>(), Some(&Interrupted));
    // The library's long loops stop instead of returning numbers: a rough cycle (its rayon
    // workers' unwind reaches the caller), a rough map, an adhesion map.
    let p =
        interrupted(|| tabor::rough::Rough::new(1.0, 0.63).and_then(|r| r.cycle(-1.89, None, 100)));
    assert!(p.downcast_ref::<Interrupted>().is_some());
    let spec = tabor::rough::map::RoughMapSpec {
        lambda_min: 0.1,
        lambda_max: 10.0,
        nx: 4,
        sigma_min: 0.1,
        sigma_max: 1.0,
        ny: 4,
        tolerance: 0.05,
        press_sigmas: 3.0,
    };
    let p = interrupted(|| tabor::rough::map::compute(&spec, 0));
    assert!(p.downcast_ref::<Interrupted>().is_some());
    // Done work is left alone: a late interrupt changes nothing.
    let t = Token::new();
    assert_eq!(t.run(|| 2), 2);
    t.interrupt();
    assert!(!requested());
    checkpoint();
}
