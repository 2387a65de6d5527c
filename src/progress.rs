//! Progress of long work on a terminal: an `indicatif` bar that appears only after the work has
//! run for two seconds and only when stderr is a terminal, so short runs, scripts and CI logs stay
//! clean. Without the `cli` feature (a library user, the Python package) it draws nothing.

#[cfg(feature = "cli")]
pub use bar::Progress;
#[cfg(not(feature = "cli"))]
pub use silent::Progress;

#[cfg(not(feature = "cli"))]
mod silent {
    /// Draws nothing; the same calls as the terminal bar.
    pub struct Progress;

    // The same calls as the bar; some are made only by the command line.
    #[allow(dead_code)]
    impl Progress {
        /// A bar of `len` units.
        pub fn new(_what: &str, _len: u64, _unit: &str) -> Progress {
            Progress
        }
        /// A spinner of unknown length.
        pub fn spinner(_what: &str) -> Progress {
            Progress
        }
        /// A line on stderr.
        pub fn println(&self, line: &str) {
            use std::io::Write;
            let _ = writeln!(std::io::stderr(), "{line}");
        }
        /// Advances by `n`.
        pub fn inc(&mut self, _n: u64) {}
        /// Sets the position.
        pub fn set(&mut self, _pos: u64) {}
        /// Ends the bar.
        pub fn finish(self) {}
    }
}

#[cfg(feature = "cli")]
mod bar {
    use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};
    use std::time::{Duration, Instant};

    const DELAY: Duration = Duration::from_secs(2);

    /// A progress bar on stderr, shown only on a terminal and only after two seconds.
    pub struct Progress {
        bar: ProgressBar,
        start: Instant,
        shown: bool,
    }

    impl Progress {
        /// A bar counting `unit` (for example "points", or "bytes" for a file read in chunks) up to
        /// `len`.
        pub fn new(what: &str, len: u64, unit: &str) -> Progress {
            let bar = ProgressBar::with_draw_target(Some(len), ProgressDrawTarget::hidden());
            let template = if unit == "bytes" {
                "{msg} [{bar:40}] {binary_bytes}/{binary_total_bytes}, {eta} left"
            } else {
                "{msg} [{bar:40}] {human_pos}/{human_len} {prefix}, {eta} left"
            };
            if let Ok(style) = ProgressStyle::with_template(template) {
                bar.set_style(style.progress_chars("=> "));
            }
            bar.set_message(what.to_string());
            bar.set_prefix(unit.to_string());
            Progress {
                bar,
                start: Instant::now(),
                shown: false,
            }
        }

        /// For work of unknown length that always takes long (bench, atlas): a spinner with the
        /// count of finished steps, drawn at once (where stderr is a terminal).
        pub fn spinner(what: &str) -> Progress {
            let bar = ProgressBar::with_draw_target(None, ProgressDrawTarget::stderr());
            if let Ok(style) =
                ProgressStyle::with_template("{spinner} {msg}: {pos} done, {elapsed}")
            {
                bar.set_style(style);
            }
            bar.set_message(what.to_string());
            bar.enable_steady_tick(Duration::from_millis(200));
            Progress {
                bar,
                start: Instant::now(),
                shown: true,
            }
        }

        /// Prints a line above the bar (or plainly where there is no bar).
        pub fn println(&self, line: &str) {
            if self.bar.is_hidden() {
                eprintln!("{line}");
            } else {
                self.bar.println(line);
            }
        }

        fn reveal(&mut self) {
            if !self.shown && self.start.elapsed() >= DELAY {
                self.shown = true;
                // Drawn only where stderr is a terminal.
                self.bar.set_draw_target(ProgressDrawTarget::stderr());
            }
        }

        /// Advances by `n`.
        pub fn inc(&mut self, n: u64) {
            self.bar.inc(n);
            self.reveal();
        }

        /// Sets the position.
        pub fn set(&mut self, pos: u64) {
            self.bar.set_position(pos);
            self.reveal();
        }

        /// Removes the bar (the command prints its own summary).
        pub fn finish(self) {
            self.bar.finish_and_clear();
        }
    }
}
