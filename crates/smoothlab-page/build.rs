//! Builds into the crate the part of `docs/reproduction.md` that the tour quotes: its
//! headings and tables (`src/lab/tour/tables_only.rs`), not its prose, which the page's
//! module need not carry.

use std::path::Path;

include!("src/lab/tour/tables_only.rs");

fn main() {
    let out_dir = std::env::var("OUT_DIR").expect("cargo sets OUT_DIR");
    let src = "../../docs/reproduction.md";
    println!("cargo:rerun-if-changed={src}");
    println!("cargo:rerun-if-changed=src/lab/tour/tables_only.rs");
    let doc = std::fs::read_to_string(src).unwrap_or_else(|e| panic!("cannot read {src}: {e}"));
    let path = Path::new(&out_dir).join("reproduction-tables.md");
    std::fs::write(&path, tables_only(&doc)).unwrap_or_else(|e| panic!("cannot write {}: {e}", path.display()));
}
