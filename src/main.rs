fn main() {
    tabor::io::output::install_signal_cleanup();
    if tabor::io::output::stdout_was_closed() {
        // Results and tables go to stdout: with it closed they would vanish under exit status 0.
        eprintln!("error: stdout is closed (>&-): tabor writes its results there; redirect it to a file (or to /dev/null to discard them)");
        std::process::exit(1);
    }
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
