#![no_main]
//! Fuzz target `vtk`: see `Target::Vtk` in `src/harness.rs`.

use libfuzzer_sys::fuzz_target;
use smoothlab_fuzz::harness::{run, Target};

fuzz_target!(|data: &[u8]| {
    run(Target::Vtk, data);
});
