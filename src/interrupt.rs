//! Cooperative interruption of long library work. A front end that stays responsive while the
//! library works (the Python binding, on Ctrl-C) runs the work under a [`Token`] and may
//! [`Token::interrupt`] it; the long loops (rough cycles and maps, ensembles, adhesion maps) call
//! [`checkpoint`], which then unwinds with an [`Interrupted`] payload. The unwind skips the
//! panic hook (nothing is printed) and the caller catches it (`catch_unwind`) and drops the
//! work. The request is process-wide while the interrupted work runs: library work on other
//! threads meanwhile ends the same way, never with numbers from a cut-short loop. The command
//! line never interrupts (Ctrl-C ends its process), so [`checkpoint`] costs it one atomic load.

use std::sync::atomic::{AtomicIsize, AtomicU8, Ordering};
use std::sync::Arc;

/// The number of interrupted works still running (transiently negative in a race, harmless).
static STOPPING: AtomicIsize = AtomicIsize::new(0);

const RUNNING: u8 = 0;
const INTERRUPTED: u8 = 1;
const DONE: u8 = 2;

/// The payload of the unwind of an interrupted work.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Interrupted;

/// One work that may be interrupted, shared by the thread that runs it and the one that waits.
#[derive(Clone, Debug, Default)]
pub struct Token(Arc<AtomicU8>);

impl Token {
    /// A token for a work not yet interrupted.
    pub fn new() -> Token {
        Token::default()
    }

    /// Runs `f` (the work) and marks the token done, so that a late interrupt changes nothing.
    pub fn run<T>(&self, f: impl FnOnce() -> T) -> T {
        struct Done<'a>(&'a AtomicU8);
        impl Drop for Done<'_> {
            fn drop(&mut self) {
                if self.0.swap(DONE, Ordering::SeqCst) == INTERRUPTED {
                    STOPPING.fetch_sub(1, Ordering::SeqCst);
                }
            }
        }
        let _done = Done(&self.0);
        f()
    }

    /// Asks the work to stop at its next [`checkpoint`]; nothing once it is done.
    pub fn interrupt(&self) {
        if self
            .0
            .compare_exchange(RUNNING, INTERRUPTED, Ordering::SeqCst, Ordering::SeqCst)
            .is_ok()
        {
            STOPPING.fetch_add(1, Ordering::SeqCst);
        }
    }
}

/// Whether an interrupted work is still running.
pub fn requested() -> bool {
    STOPPING.load(Ordering::Relaxed) > 0
}

/// Unwinds with [`Interrupted`] where an interrupt was requested; else nothing.
pub fn checkpoint() {
    if requested() {
        std::panic::resume_unwind(Box::new(Interrupted));
    }
}
