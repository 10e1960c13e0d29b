//! `smoothlab`: the command-line face of the core — generate, stats, convert, smooth,
//! render. Each subcommand lives in its own file and only parses arguments, calls the
//! core and prints; errors go to stderr with a non-zero exit code.

use clap::{Parser, Subcommand};

mod args;
mod files;
mod generate;
mod render;
mod smooth;
mod stats;

#[derive(Parser)]
#[command(name = "smoothlab", version, about = "A mesh-smoothing laboratory: metrics, smoothers and pictures")]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Subcommand)]
enum Command {
    /// Write a sample mesh (planar, surface or volume) or perturb one.
    Generate(generate::GenerateArgs),
    /// Print the quality statistics of a mesh.
    Stats(stats::StatsArgs),
    /// Convert a mesh between formats (by the file extensions).
    Convert(files::ConvertArgs),
    /// Smooth a mesh: Laplacian, smart, optimization, Freitag's C1/C2/C3 or Chen's rules.
    Smooth(smooth::SmoothArgs),
    /// Draw a mesh, level sets, convergence histories or angle histograms to PNG.
    Render(render::RenderArgs),
}

fn main() {
    let cli = Cli::parse();
    let result = match cli.command {
        Command::Generate(a) => generate::run(a),
        Command::Stats(a) => stats::run(a),
        Command::Convert(a) => files::convert(a),
        Command::Smooth(a) => smooth::run(a),
        Command::Render(a) => render::run(a),
    };
    if let Err(e) = result {
        eprintln!("smoothlab: {e}");
        std::process::exit(1);
    }
}
