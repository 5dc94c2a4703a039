//! The checked-in header `include/rfisst.h` is what cbindgen generates from this crate now. Run with
//! `RFISST_BLESS=1` to rewrite it after changing the C interface.

use std::path::Path;

#[test]
fn checked_in_header_matches_the_rust_interface() {
    let crate_dir = Path::new(env!("CARGO_MANIFEST_DIR"));
    let config = cbindgen::Config::from_file(crate_dir.join("cbindgen.toml")).expect("cbindgen.toml");
    let bindings = cbindgen::Builder::new()
        .with_crate(crate_dir)
        .with_config(config)
        .generate()
        .expect("cbindgen generates the header");
    let mut generated = Vec::new();
    bindings.write(&mut generated);
    let generated = String::from_utf8(generated).expect("UTF-8 header");
    let path = crate_dir.join("include/rfisst.h");
    if std::env::var_os("RFISST_BLESS").is_some() {
        std::fs::write(&path, &generated).expect("write include/rfisst.h");
    }
    let checked_in = std::fs::read_to_string(&path).unwrap_or_default();
    assert!(
        checked_in == generated,
        "bindings/c/include/rfisst.h is stale: regenerate it with \
         `RFISST_BLESS=1 cargo test -p rfisst-c --test header` and commit it"
    );
}
