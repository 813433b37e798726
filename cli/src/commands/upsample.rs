//! `prism upsample`: RGB to sigmoid-polynomial coefficients.

use std::io::{BufRead, Write};

use clap::Args;
use prism_spectrum::colorimetry::{Lab, Observer, ciede2000, reflectance_xyz};
use prism_upsample::{CoefficientTable, FitContext, RgbKind, RgbSpectrum, SigmoidPolynomial};
use serde_json::json;

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism upsample 0.8 0.2 0.1\n  prism upsample --space rec2020 0.1 0.6 0.2 --json\n  \
prism upsample --table srgb-64.bin 0.8 0.2 0.1\n  printf '0.8 0.2 0.1\\n0.5 0.5 0.5\\n' | prism upsample --stdin"
)]
pub struct UpsampleArgs {
    /// Linear RGB components in [0, 1] (omit with --stdin).
    #[arg(num_args = 0..=3, allow_negative_numbers = true)]
    pub rgb: Vec<f64>,
    /// The RGB colour space: a name (srgb, display-p3, rec2020, acescg, aces2065-1,
    /// prophoto, adobe-rgb, dci-p3, rec709) or primaries 'XR,YR,XG,YG,XB,YB@ILLUMINANT'
    /// (ILLUMINANT a named spectrum such as illuminant:D50; default illuminant:D65).
    #[arg(long, default_value = "srgb")]
    pub space: String,
    /// Fit each colour exactly (the default without --table).
    #[arg(long, conflicts_with = "table")]
    pub exact: bool,
    /// Look colours up in a coefficient table made by `prism table fit`, or `auto` for the
    /// space's default table (fitted on first use, then cached; see PRISM_CACHE_DIR).
    #[arg(long)]
    pub table: Option<std::path::PathBuf>,
    /// With --table: refine the interpolated coefficients with one solver step.
    #[arg(long, requires = "table")]
    pub refine: bool,
    /// Read lines `r g b` from stdin and write `c0 c1 c2` per line (l in nm), nothing else.
    #[arg(long)]
    pub stdin: bool,
    /// Print one JSON object. Coefficients are numbers, or the strings "inf" and "-inf"
    /// where the spectrum is exactly 1 or 0 (white and black), which JSON numbers cannot
    /// hold.
    #[arg(long, conflicts_with = "stdin")]
    pub json: bool,
}

/// How colours become coefficients.
enum Method {
    Exact,
    Table {
        table: CoefficientTable,
        refine: bool,
    },
}

pub fn run(args: &UpsampleArgs) -> Result<(), String> {
    let choice = crate::space_arg::parse_space(&args.space)?;
    let context =
        FitContext::new(&choice.space, choice.illuminant.as_ref()).map_err(|e| e.to_string())?;
    let method = match &args.table {
        None => Method::Exact,
        Some(path) if path.as_os_str() == "auto" => Method::Table {
            table: match choice.id {
                Some(id) => crate::table_cache::default_table(id, &context)?,
                None => {
                    return Err(
                        "--table auto: default tables exist for named spaces only; fit one \
                         for these primaries with `prism table fit --space ...`"
                            .into(),
                    );
                }
            },
            refine: args.refine,
        },
        Some(path) => {
            let bytes = crate::output::read_file(path)?;
            let table = CoefficientTable::from_bytes(&bytes)
                .map_err(|e| format!("'{}': {e}", path.display()))?;
            if !table.space().matches(&context) {
                let [r, g, b] = table.space().primaries;
                return Err(format!(
                    "'{}' is a table for '{}' (primaries {r:?} {g:?} {b:?}), not for --space {}",
                    path.display(),
                    table.space().name,
                    args.space
                ));
            }
            Method::Table {
                table,
                refine: args.refine,
            }
        }
    };
    if args.stdin {
        if !args.rgb.is_empty() {
            return Err("give RGB on the command line or with --stdin, not both".into());
        }
        return stream(&context, &method);
    }
    let rgb: [f64; 3] = args
        .rgb
        .clone()
        .try_into()
        .map_err(|_| format!("expected three components R G B, got {}", args.rgb.len()))?;
    let (spectrum, clamped) = upsample(&context, &method, rgb)?;
    let c = spectrum.map_or([0.0, 0.0, f64::NEG_INFINITY], |s| s.coefficients);
    let (round_trip, de) = round_trip(&context, choice.illuminant.as_ref(), rgb, spectrum)?;
    if args.json {
        // JSON has no infinity: the sigmoid's limits (exactly 0 or 1) are strings.
        let coefficient = |v: f64| match v {
            f64::INFINITY => json!("inf"),
            f64::NEG_INFINITY => json!("-inf"),
            v => json!(v),
        };
        outln!(
            "{}",
            json!({
                "space": choice.name,
                "rgb": rgb,
                "coefficients": c.map(coefficient),
                "black": spectrum.is_none(),
                "clamped": clamped,
                "round_trip_rgb": round_trip,
                "delta_e_2000": de,
            })
        );
    } else {
        outln!("space         {}", choice.name);
        if spectrum.is_none() {
            outln!("spectrum      black (exactly zero)");
        } else {
            outln!(
                "coefficients  {:e} {:e} {:e}  (f(l) = S(c0 l^2 + c1 l + c2), l in nm)",
                c[0],
                c[1],
                c[2]
            );
        }
        if clamped {
            outln!("warning       the input was outside [0, 1] and was clamped");
        }
        outln!(
            "round trip    {:.6} {:.6} {:.6}",
            round_trip[0],
            round_trip[1],
            round_trip[2]
        );
        outln!("dE2000        {de:.2e}");
    }
    Ok(())
}

/// The spectrum for one colour (None for black) and whether the input was clamped.
fn upsample(
    context: &FitContext,
    method: &Method,
    rgb: [f64; 3],
) -> Result<(Option<SigmoidPolynomial>, bool), String> {
    // The policies (black, greys, clamping) are RgbSpectrum's; only the shape of other
    // colours comes from the fitter or the table.
    let spectrum = match method {
        Method::Exact => RgbSpectrum::fit(context, rgb, RgbKind::Albedo, None),
        Method::Table { table, refine } => RgbSpectrum::from_table(
            table,
            context,
            rgb,
            RgbKind::Albedo,
            None,
            u32::from(*refine),
        ),
    }
    .map_err(|e| e.to_string())?;
    Ok((spectrum.shape(), spectrum.clamped()))
}

fn round_trip(
    context: &FitContext,
    illuminant: &dyn prism_spectrum::Spectrum,
    rgb: [f64; 3],
    spectrum: Option<SigmoidPolynomial>,
) -> Result<([f64; 3], f64), String> {
    let xyz = match spectrum {
        Some(s) => reflectance_xyz(&s, illuminant, Observer::Cie1931).map_err(|e| e.to_string())?,
        None => prism_spectrum::colorimetry::Xyz::default(),
    };
    let back = context.space().xyz_to_rgb(xyz);
    let white = context.white();
    let target = context.rgb_xyz(rgb.map(|c| c.clamp(0.0, 1.0)));
    Ok((
        back,
        ciede2000(Lab::from_xyz(xyz, white), Lab::from_xyz(target, white)),
    ))
}

/// `--stdin`: one `c0 c1 c2` line per `r g b` line, in order.
fn stream(context: &FitContext, method: &Method) -> Result<(), String> {
    let stdin = std::io::stdin();
    let mut out = std::io::BufWriter::new(std::io::stdout().lock());
    for (index, line) in stdin.lock().lines().enumerate() {
        let line = line.map_err(|e| format!("reading stdin: {e}"))?;
        let fields: Vec<f64> = line
            .split_whitespace()
            .map(str::parse)
            .collect::<Result<_, _>>()
            .map_err(|_| {
                format!(
                    "stdin line {}: expected three numbers 'r g b', got '{line}'",
                    index + 1
                )
            })?;
        let rgb: [f64; 3] = fields.try_into().map_err(|_| {
            format!(
                "stdin line {}: expected three numbers 'r g b', got '{line}'",
                index + 1
            )
        })?;
        let (spectrum, _) =
            upsample(context, method, rgb).map_err(|e| format!("stdin line {}: {e}", index + 1))?;
        let c = spectrum.map_or([0.0, 0.0, f64::NEG_INFINITY], |s| s.coefficients);
        let written = writeln!(out, "{:e} {:e} {:e}", c[0], c[1], c[2]);
        if !wants_more(written)? {
            return Ok(());
        }
    }
    wants_more(out.flush()).map(|_| ())
}

/// Whether the reader of stdout still reads after a write: not once it has closed the pipe
/// (`... | head`), which ends the stream quietly; any other failure is an error.
fn wants_more(written: std::io::Result<()>) -> Result<bool, String> {
    match written {
        Ok(()) => Ok(true),
        Err(e) if e.kind() == std::io::ErrorKind::BrokenPipe => Ok(false),
        Err(e) => Err(format!("writing stdout: {e}")),
    }
}
