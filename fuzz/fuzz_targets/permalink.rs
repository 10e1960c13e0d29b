#![no_main]
//! Fuzz target `permalink`: see `Target::Permalink` in `src/harness.rs`.

use libfuzzer_sys::fuzz_target;
use smoothlab_fuzz::harness::{run, Target};

fuzz_target!(|data: &[u8]| {
    run(Target::Permalink, data);
});
