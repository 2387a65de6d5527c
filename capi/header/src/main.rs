//! Writes capi/include/tabor_dem.h, the C header of capi/src/lib.rs (cbindgen, configured by
//! capi/cbindgen.toml): `cargo run -p tabor-capi-header`.

fn main() {
    let path = tabor_capi_header::header_path();
    std::fs::write(&path, tabor_capi_header::generate()).expect("capi/include is writable");
    println!("wrote {}", path.display());
}
