//! `prism table`: fit and inspect coefficient tables.

use std::io::IsTerminal;
use std::path::PathBuf;
use std::time::Instant;

use clap::Subcommand;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_upsample::{CoefficientTable, FitContext};

#[derive(Debug, Subcommand)]
pub enum TableCommand {
    /// Fit a table for a colour space and write it to a file.
    #[command(
        after_help = "Examples:\n  prism table fit --space srgb --res 64 -o srgb-64.bin\n  \
prism table fit --space '0.7,0.3,0.2,0.75,0.12,0.05@illuminant:D50' --res 32 -o mine.bin"
    )]
    Fit {
        /// The colour space: a name (srgb, display-p3, rec2020, acescg, aces2065-1,
        /// prophoto, adobe-rgb, dci-p3, rec709) or primaries 'XR,YR,XG,YG,XB,YB@ILLUMINANT'
        /// (ILLUMINANT a named spectrum such as illuminant:D50; default illuminant:D65).
        #[arg(long, default_value = "srgb")]
        space: String,
        /// Nodes per axis (2-256; 64 is the usual trade).
        #[arg(long, default_value_t = 64)]
        res: usize,
        /// Output file.
        #[arg(short, long)]
        output: PathBuf,
    },
    /// Describe a table file.
    #[command(
        after_help = "Example:\n  prism table fit --space srgb --res 64 -o srgb.table\n  prism table info srgb.table"
    )]
    Info {
        /// The table file.
        file: PathBuf,
    },
}

pub fn run(command: &TableCommand) -> Result<(), String> {
    match command {
        TableCommand::Fit { space, res, output } => fit(space, *res, output),
        TableCommand::Info { file } => info(file),
    }
}

fn fit(space: &str, res: usize, output: &std::path::Path) -> Result<(), String> {
    let choice = crate::space_arg::parse_space(space)?;
    let context =
        FitContext::new(&choice.space, choice.illuminant.as_ref()).map_err(|e| e.to_string())?;
    crate::output::check_writable(output)?;
    let rows = 3 * res;
    let start = Instant::now();
    // A progress line only on a terminal; scripts and logs get the summary alone.
    let terminal = std::io::stderr().is_terminal();
    let progress = |done: usize| {
        let step = |d: usize| d * 20 / rows.max(1);
        if terminal && (step(done) != step(done - 1) || done == rows) {
            eprint!(
                "\rfitting {} {res}^3: {:3}%",
                choice.name,
                done * 100 / rows.max(1)
            );
        }
    };
    let (table, stats) =
        CoefficientTable::fit(&context, res, &progress).map_err(|e| e.to_string())?;
    let seconds = start.elapsed().as_secs_f64();
    if terminal {
        eprintln!();
    }
    let bytes = table.to_bytes();
    crate::output::write_atomically(output, &bytes)?;
    let (mean, p99, max) = accuracy(&context, choice.illuminant.as_ref(), &table);
    outln!("wrote {} ({} bytes)", output.display(), bytes.len());
    outln!(
        "fit: {seconds:.2} s wall, {} nodes, {:.2} iterations per node",
        stats.nodes,
        stats.iterations as f64 / stats.nodes as f64
    );
    outln!(
        "reachable nodes: {:.4}% ({} of {} beyond 1e-3 Lab: beyond the reach of sigmoid-polynomial reflectances), largest residual {:.2e}",
        100.0 * (1.0 - stats.unreachable as f64 / stats.nodes as f64),
        stats.unreachable,
        stats.nodes,
        stats.max_residual
    );
    outln!(
        "trilinear lookup, 2000 random colours, dE2000: mean {mean:.4}, p99 {p99:.4}, max {max:.4}"
    );
    Ok(())
}

/// dE2000 statistics of trilinear lookups of 2000 pseudo-random colours of the cube.
fn accuracy(
    context: &FitContext,
    illuminant: &dyn prism_spectrum::Spectrum,
    table: &CoefficientTable,
) -> (f64, f64, f64) {
    let white = context.white();
    let mut x = 0x853c_49e6_748f_ea9bu64;
    let mut errors: Vec<f64> = (0..2000)
        .filter_map(|_| {
            let rgb: [f64; 3] = std::array::from_fn(|_| {
                x ^= x << 13;
                x ^= x >> 7;
                x ^= x << 17;
                (x >> 11) as f64 / (1u64 << 53) as f64
            });
            let xyz = reflectance_xyz(&table.lookup(rgb), illuminant, Observer::Cie1931).ok()?;
            Some(ciede2000(
                Lab::from_xyz(xyz, white),
                Lab::from_xyz(context.rgb_xyz(rgb), white),
            ))
        })
        .collect();
    errors.sort_by(f64::total_cmp);
    let n = errors.len().max(1);
    (
        errors.iter().sum::<f64>() / n as f64,
        errors[n * 99 / 100],
        errors[n - 1],
    )
}

fn info(file: &std::path::Path) -> Result<(), String> {
    let bytes = crate::output::read_file(file)?;
    let table =
        CoefficientTable::from_bytes(&bytes).map_err(|e| format!("'{}': {e}", file.display()))?;
    let s = table.space();
    outln!("file          {} ({} bytes)", file.display(), bytes.len());
    outln!(
        "format        prism coefficient table, version {}",
        prism_upsample::FORMAT_VERSION
    );
    outln!("colour space  {}", s.name);
    outln!(
        "primaries     r ({}, {})  g ({}, {})  b ({}, {})",
        s.primaries[0][0],
        s.primaries[0][1],
        s.primaries[1][0],
        s.primaries[1][1],
        s.primaries[2][0],
        s.primaries[2][1]
    );
    outln!("white         ({:.6}, {:.6})", s.white[0], s.white[1]);
    outln!("observer      CIE 1931 2 degree");
    outln!(
        "resolution    {0} ({0}^3 nodes per largest channel)",
        table.resolution()
    );
    Ok(())
}
