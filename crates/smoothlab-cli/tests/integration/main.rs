//! The crate's integration tests, one binary (the tests of each concern in a module).

mod common;
mod cli_stats;
mod front_door;
mod generate;
mod hardening;
mod io_plane;
mod render_cli;
mod smooth_cli;
mod surface_cli;
mod volume_generate;
mod volume_io;
mod volume_mesquite;
mod volume_slide;
