fn main() {
    tabor::io::output::install_signal_cleanup();
    if let Err(e) = tabor::cli::run() {
        // `tabor ... | head`: the reader has what it wanted.
        if tabor::io::output::is_broken_pipe(&e) {
            std::process::exit(0);
        }
        // One line: the context, then each cause after a colon.
        eprintln!("error: {e:#}");
        std::process::exit(1);
    }
}
