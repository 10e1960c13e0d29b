#![no_main]
//! Fuzz target `medit`: see `Target::Medit` in `src/harness.rs`.

use libfuzzer_sys::fuzz_target;
use smoothlab_fuzz::harness::{run, Target};

fuzz_target!(|data: &[u8]| {
    run(Target::Medit, data);
});
