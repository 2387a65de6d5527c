fn main() {
    // Mesa's Vulkan loader probes Wayland and complains on stderr when XDG_RUNTIME_DIR is unset
    // (headless machines, CI); point it at the temp dir before any thread starts.
    if std::env::var_os("XDG_RUNTIME_DIR").is_none() {
        std::env::set_var("XDG_RUNTIME_DIR", std::env::temp_dir());
    }
    if let Err(e) = tabor::cli::run() {
        eprintln!("error: {e}");
        for cause in e.chain().skip(1) {
            eprintln!("  caused by: {cause}");
        }
        std::process::exit(1);
    }
}
