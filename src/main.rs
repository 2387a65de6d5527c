fn main() {
    tabor::io::output::install_signal_cleanup();
    if let Err(e) = tabor::cli::run() {
        // `tabor ... | head`: the reader has what it wanted.
        if tabor::io::output::is_broken_pipe(&e) {
            std::process::exit(0);
        }
        // One line: the context, then each cause after a colon.
        // A closed stderr ends quietly, as a closed stdout does.
        use std::io::Write as _;
        let _ = writeln!(std::io::stderr(), "error: {e:#}");
        std::process::exit(1);
    }
}
