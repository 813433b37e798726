//! `prism trade`: the speed-accuracy trade of a scene measured, not guessed. The scene is
//! rendered under sweeps of settings (wavelengths per path, wavelength sampler, RGB
//! upsampling) at a ladder of sample counts; each run's time and relative MSE against a
//! reference go to a CSV, log-log plots (SVG) and a markdown summary.

use std::collections::HashMap;
use std::path::{Path, PathBuf};
use std::time::Instant;

use clap::Args;
use prism_integrator::{
    ChannelImage, ExrMetadata, LambdaSampler, RenderSettings, compare_images, decode_exr,
    encode_exr, render,
};
use prism_scene::load::Upsampling;
use prism_scene::world::{Scene, SceneOptions};
use prism_spectrum::color::RgbSpaceId;

use crate::output::write_atomically;
use crate::svg_plot::{Curve, log_log};

#[derive(Debug, Args)]
#[command(
    after_help = "Examples:\n  prism trade scenes/cornell-box.gltf -o trade/box\n  prism trade scenes/cornell-bunny.gltf --budget 300 --spp 4,16,64,256 -o trade/bunny\n  prism trade --report -o trade/box    (redraw plots and summary, with DIR/peer.csv if present)\n\nWrites DIR/runs.csv, DIR/<sweep>.svg, DIR/summary.md and DIR/reference.exr."
)]
pub struct TradeArgs {
    /// The scene (.gltf, .glb or a TOML overlay); not needed with --report.
    pub scene: Option<PathBuf>,
    /// The output directory.
    #[arg(short = 'o', long = "output")]
    pub dir: PathBuf,
    /// A reference image (EXR, same size, linear sRGB); default: rendered at
    /// --reference-spp with prism's defaults and a different seed.
    #[arg(long)]
    pub reference: Option<PathBuf>,
    /// Samples per pixel of the rendered reference.
    #[arg(long, default_value_t = 2048)]
    pub reference_spp: u64,
    /// Stop starting runs, and repeats of a run, after this many seconds (the reference
    /// included; every run keeps one render); runs are ordered by samples per pixel, so a
    /// budget cuts the most expensive ones.
    #[arg(long, default_value_t = 900.0, allow_negative_numbers = true)]
    pub budget: f64,
    /// The samples-per-pixel ladder of every sweep.
    #[arg(long, default_value = "4,16,64")]
    pub spp: String,
    /// Image width.
    #[arg(long, default_value_t = 128)]
    pub width: u32,
    /// Image height.
    #[arg(long, default_value_t = 128)]
    pub height: u32,
    /// Longest path in bounces (default: unbounded).
    #[arg(long)]
    pub max_depth: Option<u32>,
    /// Worker threads (default: one per core; at most 1024).
    #[arg(long, default_value_t = 0)]
    pub threads: usize,
    /// Render every run this many times (seeds 1, 2, ...) and record the medians of its
    /// time and error: shared machines are noisy, and so is one seed's error.
    #[arg(long, default_value_t = 1)]
    pub repeat: u32,
    /// Only redraw the plots and summary from DIR/runs.csv (and DIR/peer.csv).
    #[arg(long)]
    pub report: bool,
}

/// One measured run.
#[derive(Debug, Clone, PartialEq)]
struct Run {
    scene: String,
    sweep: String,
    setting: String,
    spp: u64,
    seconds: f64,
    setup_seconds: f64,
    relmse: f64,
    /// How many renders the time and error are medians of.
    repeats: u32,
}

const CSV_HEADER: &str = "scene,sweep,setting,spp,seconds,setup_seconds,relmse,repeats";

/// The median of `values` (the mean of the middle two for an even count).
fn median(mut values: Vec<f64>) -> f64 {
    values.sort_by(f64::total_cmp);
    let n = values.len();
    if n == 0 {
        return f64::NAN;
    }
    if n % 2 == 1 {
        values[n / 2]
    } else {
        0.5 * (values[n / 2 - 1] + values[n / 2])
    }
}

/// What one run varies.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
struct Knobs {
    wavelengths: usize,
    sampler: LambdaSampler,
    upsampling: Upsampling,
    spp: u64,
}

const DEFAULT_KNOBS: Knobs = Knobs {
    wavelengths: 4,
    sampler: LambdaSampler::Visible,
    upsampling: Upsampling::Exact,
    spp: 0,
};

fn sampler_name(s: LambdaSampler) -> &'static str {
    match s {
        LambdaSampler::Uniform => "uniform",
        LambdaSampler::Visible => "visible",
        LambdaSampler::Response => "response",
        LambdaSampler::Spd => "spd",
    }
}

/// The sweeps: (sweep, setting, knobs without spp).
fn sweeps() -> Vec<(&'static str, String, Knobs)> {
    let mut out = Vec::new();
    for c in [1, 2, 4, 8, 16] {
        out.push((
            "wavelengths",
            format!("C={c}"),
            Knobs {
                wavelengths: c,
                ..DEFAULT_KNOBS
            },
        ));
    }
    for s in [
        LambdaSampler::Uniform,
        LambdaSampler::Visible,
        LambdaSampler::Response,
        LambdaSampler::Spd,
    ] {
        out.push((
            "sampler",
            sampler_name(s).into(),
            Knobs {
                sampler: s,
                ..DEFAULT_KNOBS
            },
        ));
    }
    for u in [
        Upsampling::Table(16),
        Upsampling::Table(32),
        Upsampling::Table(64),
        Upsampling::Refined(64),
        Upsampling::Exact,
    ] {
        out.push((
            "upsampling",
            u.name(),
            Knobs {
                upsampling: u,
                ..DEFAULT_KNOBS
            },
        ));
    }
    out
}

fn linear_srgb(film: &prism_integrator::Film, width: u32, height: u32) -> ChannelImage {
    let rgb = film.to_rgb(RgbSpaceId::Srgb.space());
    let channel = |k: usize| rgb.iter().map(|p| p[k]).collect::<Vec<f32>>();
    ChannelImage {
        width: width as usize,
        height: height as usize,
        channels: vec![
            ("B".into(), channel(2)),
            ("G".into(), channel(1)),
            ("R".into(), channel(0)),
        ],
    }
}

fn parse_ladder(text: &str) -> Result<Vec<u64>, String> {
    let mut ladder: Vec<u64> = text
        .split(',')
        .map(|s| {
            s.trim()
                .parse::<u64>()
                .ok()
                .filter(|&n| n > 0)
                .ok_or_else(|| {
                    format!("--spp '{text}': expected positive integers, comma separated")
                })
        })
        .collect::<Result<_, _>>()?;
    ladder.sort_unstable();
    ladder.dedup();
    Ok(ladder)
}

/// The scene loaded per upsampling mode, with the seconds loading took.
type Scenes = HashMap<Upsampling, (Scene, f64)>;

/// Loads the scene with `mode` unless already loaded.
fn load_once(scenes: &mut Scenes, path: &Path, mode: Upsampling) -> Result<(), String> {
    if let std::collections::hash_map::Entry::Vacant(slot) = scenes.entry(mode) {
        let t = Instant::now();
        let loaded = crate::scene_file::load_with(path, None, mode)?;
        let scene = Scene::from_loaded(loaded, &SceneOptions::default())
            .map_err(|e| format!("'{}': {e}", path.display()))?;
        slot.insert((scene, t.elapsed().as_secs_f64()));
    }
    Ok(())
}

pub fn run(args: &TradeArgs) -> Result<(), String> {
    if !args.report {
        measure(args)?;
    }
    report(&args.dir)
}

fn measure(args: &TradeArgs) -> Result<(), String> {
    let scene_path = args
        .scene
        .as_ref()
        .ok_or("prism trade needs a SCENE (or --report to redraw from an earlier run)")?;
    if args.repeat == 0 {
        return Err("--repeat must be at least 1".into());
    }
    if !(args.budget.is_finite() && args.budget > 0.0) {
        return Err(format!(
            "--budget {} must be finite and > 0 seconds",
            args.budget
        ));
    }
    let ladder = parse_ladder(&args.spp)?;
    std::fs::create_dir_all(&args.dir)
        .map_err(|e| format!("cannot create '{}': {e}", args.dir.display()))?;
    let name = scene_path
        .file_stem()
        .map_or("scene".into(), |s| s.to_string_lossy().to_string());
    let started = Instant::now();
    let mut scenes: Scenes = HashMap::new();
    load_once(&mut scenes, scene_path, Upsampling::Exact)?;
    let settings_for = |k: Knobs, seed: u64| {
        RenderSettings::default()
            .width(args.width)
            .height(args.height)
            .samples(0..k.spp)
            .seed(seed)
            .max_depth(args.max_depth)
            .wavelengths(k.wavelengths)
            .lambda_sampler(k.sampler)
            .threads(args.threads)
    };
    let reference = match &args.reference {
        Some(path) => {
            let bytes = crate::output::read_file(path)?;
            let mut image = decode_exr(&bytes).map_err(|e| format!("'{}': {e}", path.display()))?;
            image
                .channels
                .retain(|(n, _)| n == "R" || n == "G" || n == "B");
            image
        }
        None => {
            eprintln!("prism trade: reference at {} spp", args.reference_spp);
            let settings = settings_for(
                Knobs {
                    spp: args.reference_spp,
                    ..DEFAULT_KNOBS
                },
                0x7e7e_7e7e,
            );
            let scene = &scenes[&Upsampling::Exact].0;
            let (film, _) = render(scene, &settings).map_err(|e| e.to_string())?;
            let bytes = encode_exr(
                &film,
                RgbSpaceId::Srgb.space(),
                &ExrMetadata::default()
                    .spp(film.samples())
                    .strings(vec![("trade_reference".into(), name.clone())]),
            )
            .map_err(|e| e.to_string())?;
            write_atomically(&args.dir.join("reference.exr"), &bytes)?;
            linear_srgb(&film, args.width, args.height)
        }
    };
    let mut measured: HashMap<Knobs, (f64, f64, f64, u32)> = HashMap::new();
    let mut runs = Vec::new();
    let mut skipped = 0;
    for &spp in &ladder {
        for (sweep, setting, knobs) in sweeps() {
            let knobs = Knobs { spp, ..knobs };
            if let std::collections::hash_map::Entry::Vacant(slot) = measured.entry(knobs) {
                if started.elapsed().as_secs_f64() > args.budget {
                    skipped += 1;
                    continue;
                }
                load_once(&mut scenes, scene_path, knobs.upsampling)?;
                let (scene, setup) = &scenes[&knobs.upsampling];
                let (mut times, mut errors) = (Vec::new(), Vec::new());
                for seed in 1..=u64::from(args.repeat) {
                    // The budget cuts repeats as it cuts runs: --repeat 1000000000 would
                    // otherwise never end. Every run keeps at least one render.
                    if seed > 1 && started.elapsed().as_secs_f64() > args.budget {
                        break;
                    }
                    let t = Instant::now();
                    let (film, _) =
                        render(scene, &settings_for(knobs, seed)).map_err(|e| e.to_string())?;
                    times.push(t.elapsed().as_secs_f64());
                    let image = linear_srgb(&film, args.width, args.height);
                    errors.push(
                        compare_images(&image, &reference)
                            .map_err(|e| format!("comparing with the reference: {e}"))?
                            .relmse,
                    );
                }
                let repeats = times.len() as u32;
                let (seconds, relmse) = (median(times), median(errors));
                eprintln!(
                    "prism trade: {sweep} {setting} {spp} spp: {seconds:.2} s, relMSE {relmse:.3e}"
                );
                slot.insert((seconds, *setup, relmse, repeats));
            }
            let (seconds, setup_seconds, relmse, repeats) = measured[&knobs];
            runs.push(Run {
                scene: name.clone(),
                sweep: sweep.into(),
                setting,
                spp,
                seconds,
                setup_seconds,
                relmse,
                repeats,
            });
        }
    }
    if skipped > 0 {
        eprintln!(
            "prism trade: the budget of {} s left {skipped} runs out",
            args.budget
        );
    }
    let mut csv = String::from(CSV_HEADER);
    csv.push('\n');
    for r in &runs {
        csv.push_str(&format!(
            "{},{},{},{},{:.6},{:.6},{:.6e},{}\n",
            r.scene, r.sweep, r.setting, r.spp, r.seconds, r.setup_seconds, r.relmse, r.repeats
        ));
    }
    write_atomically(&args.dir.join("runs.csv"), csv.as_bytes())
}

fn read_runs(path: &Path) -> Result<Vec<Run>, String> {
    let text = crate::output::read_text(path)?;
    let mut runs = Vec::new();
    for (i, line) in text.lines().enumerate().skip(1) {
        let f: Vec<&str> = line.split(',').collect();
        let bad = || format!("'{}' line {}: expected {CSV_HEADER}", path.display(), i + 1);
        // The repeats column is optional (1 when absent).
        if f.len() != 7 && f.len() != 8 {
            return Err(bad());
        }
        let number = |s: &str| s.trim().parse::<f64>().map_err(|_| bad());
        runs.push(Run {
            scene: f[0].into(),
            sweep: f[1].into(),
            setting: f[2].into(),
            spp: f[3].trim().parse().map_err(|_| bad())?,
            seconds: number(f[4])?,
            setup_seconds: number(f[5])?,
            relmse: number(f[6])?,
            repeats: match f.get(7) {
                Some(r) => r.trim().parse().map_err(|_| bad())?,
                None => 1,
            },
        });
    }
    Ok(runs)
}

/// Monte Carlo efficiency: 1 / (error x time); higher is better.
fn efficiency(r: &Run) -> f64 {
    1.0 / (r.relmse * (r.seconds + r.setup_seconds)).max(1e-300)
}

fn report(dir: &Path) -> Result<(), String> {
    let mut runs = read_runs(&dir.join("runs.csv"))?;
    let peer = dir.join("peer.csv");
    if peer.exists() {
        runs.extend(read_runs(&peer)?);
    }
    let scene = runs.first().map_or("scene".into(), |r| r.scene.clone());
    let mut summary = format!(
        "# prism trade: {scene}\n\nRelative MSE (mean of (x - ref)^2 / (ref^2 + 0.01) over linear sRGB) against the reference, and wall time, per run. Efficiency is 1 / (relMSE x seconds): higher is better, and independent of the sample count for an unbiased estimator. Setup time (loading, upsampling) counts in the efficiency.\n\n"
    );
    let mut sweeps: Vec<String> = Vec::new();
    for r in &runs {
        if r.sweep != "peer" && !sweeps.contains(&r.sweep) {
            sweeps.push(r.sweep.clone());
        }
    }
    let peer_runs: Vec<&Run> = runs.iter().filter(|r| r.sweep == "peer").collect();
    for sweep in &sweeps {
        let mut settings: Vec<String> = Vec::new();
        for r in runs.iter().filter(|r| &r.sweep == sweep) {
            if !settings.contains(&r.setting) {
                settings.push(r.setting.clone());
            }
        }
        let mut curves: Vec<Curve> = settings
            .iter()
            .map(|s| Curve {
                label: s.clone(),
                points: runs
                    .iter()
                    .filter(|r| &r.sweep == sweep && &r.setting == s)
                    .map(|r| (r.seconds + r.setup_seconds, r.relmse))
                    .collect(),
            })
            .collect();
        if !peer_runs.is_empty() {
            let mut labels: Vec<String> = Vec::new();
            for r in &peer_runs {
                if !labels.contains(&r.setting) {
                    labels.push(r.setting.clone());
                }
            }
            for label in labels {
                curves.push(Curve {
                    label: label.clone(),
                    points: peer_runs
                        .iter()
                        .filter(|r| r.setting == label)
                        .map(|r| (r.seconds + r.setup_seconds, r.relmse))
                        .collect(),
                });
            }
        }
        let svg = log_log(
            &format!("{scene}: {sweep}"),
            "seconds",
            "relative MSE",
            &curves,
        );
        write_atomically(&dir.join(format!("{sweep}.svg")), svg.as_bytes())?;
        summary.push_str(&format!(
            "## {sweep}\n\n![{sweep}]({sweep}.svg)\n\n| setting | spp | seconds | relMSE | efficiency | medians of |\n| --- | --- | --- | --- | --- | --- |\n"
        ));
        let mut rows: Vec<&Run> = runs
            .iter()
            .filter(|r| &r.sweep == sweep || r.sweep == "peer")
            .collect();
        // By sample count, then in the sweep's own order (C=2 before C=16), peers last.
        let order = |r: &Run| {
            settings
                .iter()
                .position(|s| *s == r.setting)
                .unwrap_or(usize::MAX)
        };
        rows.sort_by_key(|r| (r.spp, order(r)));
        for r in &rows {
            summary.push_str(&format!(
                "| {} | {} | {:.3} | {:.3e} | {:.3e} | {} |\n",
                r.setting,
                r.spp,
                r.seconds + r.setup_seconds,
                r.relmse,
                efficiency(r),
                r.repeats
            ));
        }
        // The most efficient setting at the largest sample count measured for all.
        let top = rows.iter().map(|r| r.spp).max().unwrap_or(0);
        if let Some(best) = rows
            .iter()
            .filter(|r| r.spp == top && r.sweep != "peer")
            .max_by(|a, b| efficiency(a).total_cmp(&efficiency(b)))
        {
            summary.push_str(&format!(
                "\nMost efficient at {top} spp: **{}** ({:.3e}).\n\n",
                best.setting,
                efficiency(best)
            ));
        }
    }
    write_atomically(&dir.join("summary.md"), summary.as_bytes())?;
    eprintln!(
        "prism trade: wrote {} runs, {} plots and summary.md to {}",
        runs.len(),
        sweeps.len(),
        dir.display()
    );
    Ok(())
}
