//! `prism`: the command-line front end of the prism spectral renderer.
//!
//! The binary is thin by design (see ARCHITECTURE.md): it parses arguments, reads files,
//! and composes the library crates. Every failure is one line on stderr and a non-zero exit
//! code: 2 for a malformed command line, 1 for anything else.

use std::process::ExitCode;

use prism_cli::{commands, cpu, stdout};

use clap::{Parser, Subcommand};

/// prism: a spectral path tracer.
#[derive(Debug, Parser)]
#[command(name = "prism", version, about, long_about = None)]
struct Cli {
    #[command(subcommand)]
    command: Command,
}

#[derive(Debug, Subcommand)]
enum Command {
    /// Print the colorimetry of one spectrum: XYZ, chromaticity, RGB and CCT.
    Color(commands::color::ColorArgs),
    /// Turn RGB colours into sigmoid-polynomial spectra (Jakob and Hanika 2019).
    Upsample(commands::upsample::UpsampleArgs),
    /// Render a glTF scene (or the embedded effects stage) to EXR and PNG images.
    Render(Box<commands::render::RenderArgs>),
    /// Merge accumulation files of sample ranges (prism render --sample-range) into an image.
    Merge(commands::merge::MergeArgs),
    /// Compare an image with a reference: RMSE, relative MSE, PSNR, mean ratios.
    Compare(commands::compare::CompareArgs),
    /// Denoise a render that has albedo and normal AOVs (Intel Open Image Denoise).
    Denoise(commands::denoise::DenoiseArgs),
    /// Describe a glTF scene: geometry, materials, lights, cameras, memory.
    Info(commands::info::InfoArgs),
    /// A lens prescription's focal length, back focal distance, pupil and f-number per
    /// wavelength, and its longitudinal chromatic aberration.
    Lens(commands::lens::LensArgs),
    /// Measure the speed-accuracy trade of a scene: error against time per setting.
    Trade(commands::trade::TradeArgs),
    /// Fit and inspect RGB-to-spectrum coefficient tables.
    #[command(subcommand)]
    Table(commands::table::TableCommand),
}

fn main() -> ExitCode {
    let missing = cpu::missing_features();
    if !missing.is_empty() {
        eprintln!("prism: error: {}", cpu::unsupported(&missing));
        return ExitCode::from(1);
    }
    let cli = match Cli::try_parse() {
        Ok(cli) => cli,
        Err(error) => return usage_error(error),
    };
    let result = match cli.command {
        Command::Color(args) => commands::color::run(&args),
        Command::Upsample(args) => commands::upsample::run(&args),
        Command::Info(args) => commands::info::run(&args),
        Command::Render(args) => commands::render::run(&args),
        Command::Merge(args) => commands::merge::run(&args),
        Command::Compare(args) => commands::compare::run(&args),
        Command::Denoise(args) => commands::denoise::run(&args),
        Command::Table(command) => commands::table::run(&command),
        Command::Trade(args) => commands::trade::run(&args),
        Command::Lens(args) => commands::lens::run(&args),
    };
    match result {
        // What could not be written was named on stderr when it failed.
        Ok(()) if stdout::failed() => ExitCode::from(1),
        Ok(()) => ExitCode::SUCCESS,
        Err(message) => {
            eprintln!("prism: error: {}", one_line(&message));
            ExitCode::from(1)
        }
    }
}

/// An error on one line whatever the input put into it: line and paragraph separators
/// become spaces, other control characters are written escaped.
fn one_line(message: &str) -> String {
    message
        .chars()
        .map(|c| match c {
            '\n' | '\r' | '\u{2028}' | '\u{2029}' => " ".to_string(),
            c if c.is_control() => c.escape_unicode().to_string(),
            c => c.to_string(),
        })
        .collect()
}

/// Help and version go to stdout with success; real usage errors become one line.
fn usage_error(error: clap::Error) -> ExitCode {
    use clap::error::ErrorKind;
    match error.kind() {
        ErrorKind::DisplayHelp
        | ErrorKind::DisplayVersion
        | ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand => {
            // Printing help can only fail if stdout is closed; nothing useful remains to do.
            let _ = error.print();
            if error.kind() == ErrorKind::DisplayHelpOnMissingArgumentOrSubcommand {
                ExitCode::from(2)
            } else {
                ExitCode::SUCCESS
            }
        }
        _ => {
            // clap's message may continue on indented lines (for example the names of the
            // missing arguments) before its usage block: join them into one line.
            let rendered = error.render().to_string();
            let message = rendered
                .lines()
                .take_while(|l| !l.starts_with("Usage:") && !l.starts_with("For more information"))
                .map(str::trim)
                .filter(|l| !l.is_empty())
                .collect::<Vec<_>>()
                .join(" ");
            let message = message.trim_start_matches("error: ");
            let message = if message.is_empty() {
                "invalid arguments"
            } else {
                message
            };
            eprintln!("prism: error: {message} (see 'prism --help')");
            ExitCode::from(2)
        }
    }
}
