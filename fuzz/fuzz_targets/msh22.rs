#![no_main]
//! Fuzz target `msh22`: see `Target::Msh22` in `src/harness.rs`.

use libfuzzer_sys::fuzz_target;
use smoothlab_fuzz::harness::{run, Target};

fuzz_target!(|data: &[u8]| {
    run(Target::Msh22, data);
});
