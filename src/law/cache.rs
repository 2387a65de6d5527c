//! The per-thread cache of the laws' costly values: a radius's parameter on the contact piece,
//! the states at a piece's nodes, a law's ends (two zones' non-contact ends, a tip's). A fit at fixed lambda asks for
//! the same ones again; a cached value is the value computed, bit for bit.

use super::{LawKey, Piece, Pt};
use std::rc::Rc;

#[derive(Clone, Copy, PartialEq, Eq)]
enum Key {
    Radius(LawKey, u64),
    Nodes(LawKey, Piece, u64, u64),
    Ends(LawKey),
}

#[derive(Clone)]
enum Cached {
    X(f64),
    Nodes(Rc<Vec<(f64, Pt)>>),
    Ends((f64, f64)),
}

/// Entries kept per thread: a fit at fixed lambda needs a handful (the radii of the doubling
/// and the two pieces' nodes); a free fit, whose lambda moves at every step, only cycles them,
/// as does every fit of the two-zone law (its zones' ratios move with E* and w).
const CACHE: usize = 16;

thread_local! {
    static PATH_CACHE: std::cell::RefCell<(usize, Vec<(Key, Cached)>)> =
        const { std::cell::RefCell::new((0, Vec::new())) };
}

/// The cached value of `key`, computed by `f` on a miss.
fn cached(key: Key, f: impl FnOnce() -> Cached) -> Cached {
    if let Some(v) = PATH_CACHE.with(|c| {
        c.borrow()
            .1
            .iter()
            .find(|(k, _)| *k == key)
            .map(|(_, v)| v.clone())
    }) {
        return v;
    }
    let v = f();
    PATH_CACHE.with(|c| {
        let mut c = c.borrow_mut();
        let (next, entries) = &mut *c;
        if entries.len() < CACHE {
            entries.push((key, v.clone()));
        } else {
            entries[*next] = (key, v.clone());
            *next = (*next + 1) % CACHE;
        }
    });
    v
}

/// The contact piece's parameter at radius `a` of the law `law`.
pub(crate) fn radius(law: LawKey, a: f64, f: impl FnOnce() -> f64) -> f64 {
    match cached(Key::Radius(law, a.to_bits()), || Cached::X(f())) {
        Cached::X(x) => x,
        _ => unreachable!("a radius key holds a parameter"),
    }
}

/// The states at the nodes of a piece between t0 and t1.
pub(crate) fn nodes(
    law: LawKey,
    piece: Piece,
    t0: f64,
    t1: f64,
    f: impl FnOnce() -> Vec<(f64, Pt)>,
) -> Rc<Vec<(f64, Pt)>> {
    match cached(Key::Nodes(law, piece, t0.to_bits(), t1.to_bits()), || {
        Cached::Nodes(Rc::new(f()))
    }) {
        Cached::Nodes(n) => n,
        _ => unreachable!("a node key holds nodes"),
    }
}

/// A law's pair of costly ends: two zones' non-contact ends, a tip's zone end and the start of
/// its contact piece's part stable under rigid grips.
pub(crate) fn ends(law: LawKey, f: impl FnOnce() -> (f64, f64)) -> (f64, f64) {
    match cached(Key::Ends(law), || Cached::Ends(f())) {
        Cached::Ends(e) => e,
        _ => unreachable!("an ends key holds ends"),
    }
}
