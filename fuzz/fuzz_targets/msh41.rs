#![no_main]
//! Fuzz target `msh41`: see `Target::Msh41` in `src/harness.rs`.

use libfuzzer_sys::fuzz_target;
use smoothlab_fuzz::harness::{run, Target};

fuzz_target!(|data: &[u8]| {
    run(Target::Msh41, data);
});
