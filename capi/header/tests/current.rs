//! The committed header is the one cbindgen generates from the ABI now.

#[test]
fn the_committed_header_is_the_generated_one() {
    let committed = std::fs::read(tabor_capi_header::header_path()).unwrap();
    assert!(
        committed == tabor_capi_header::generate(),
        "capi/include/tabor_dem.h differs from what capi/src/lib.rs generates: run `cargo run -p tabor-capi-header`"
    );
}
