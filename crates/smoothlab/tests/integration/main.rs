//! The crate's integration tests, one binary (the tests of each concern in a module).

mod common;
mod fuzz_regressions;
mod io_bad;
mod io_formats;
mod io_livesu;
mod io_mesquite;
mod io_roundtrip;
mod limits;
mod never_worse;
mod smooth_papers;
mod smooth_properties;
mod solid_properties;
mod stretch_target;
mod surface_corners;
mod surface_properties;
mod surface_tangled;
mod volume_properties;
mod volume_roundtrip;
