//! Denoising with Intel Open Image Denoise (OIDN 2.x): its "RT" filter for HDR images,
//! guided by the albedo and normal feature buffers, on the RGB image the spectral film
//! made (never on spectral bands: the network is trained on RGB renders).
//!
//! The auxiliary buffers are denoised first and the image filtered with `cleanAux`, OIDN's
//! "prefiltering" mode (its documentation, "RT filter"; Cycles' "Accurate" prefilter):
//! prism's albedo is one BSDF sample per camera sample and its normals are averaged over
//! the pixel, so at the sample counts denoising is for both carry noise that the network
//! would otherwise keep as detail.
//!
//! The library is found at run time ([`find_library`]): `pip install pyoidn` is the one
//! install step (its wheel ships the official OIDN 2.5 libraries).

mod oidn;

use std::path::{Path, PathBuf};
use std::process::Command;

use prism_spectrum::color::{Mat3, RgbColorSpace, RgbSpaceId};

pub use oidn::Image;
use oidn::{LIBRARY, Oidn};

/// What to install, said where the library is missing.
pub const INSTALL: &str = "pip install pyoidn (Intel Open Image Denoise 2.x), or set PRISM_OIDN to its libOpenImageDenoise library";

/// A loaded denoiser.
pub struct Denoiser {
    oidn: Oidn,
}

impl Denoiser {
    /// Finds and loads Open Image Denoise; the error is one line saying what to install.
    pub fn load() -> Result<Self, String> {
        let path = find_library()?;
        Ok(Self {
            oidn: Oidn::load(&path)?,
        })
    }

    /// Where the library was loaded from.
    pub fn path(&self) -> &Path {
        &self.oidn.path
    }

    /// The denoised `color` (linear RGB in `space`, HDR) of a `width` x `height` image,
    /// guided by its `albedo` (RGB in `space`, [0, 1]) and `normal` (any length, [-1, 1])
    /// buffers, each first denoised alone.
    ///
    /// The filter works in ACES2065-1 (AP0 primaries), whose gamut holds every colour
    /// light can have: OIDN's HDR mode takes non-negative light, and the spectral colours
    /// of a dispersed or fluorescent render lie outside sRGB's (negative components),
    /// which clipping would grey. Measured on a prism's spectrum on a wall
    /// (benches/denoise/measure.py), denoising in sRGB took its most saturated pixels
    /// further from the converged image than the noise had, while denoising in AP0
    /// brought them closer and cut the relative MSE more (docs/trade-offs.md,
    /// "Denoising").
    pub fn denoise(
        &self,
        width: usize,
        height: usize,
        space: &RgbColorSpace,
        color: &[[f32; 3]],
        albedo: &[[f32; 3]],
        normal: &[[f32; 3]],
    ) -> Result<Image, String> {
        let working = RgbSpaceId::Aces2065_1.space();
        let to_working = working.xyz_to_rgb_matrix().mul(&space.rgb_to_xyz_matrix());
        let back = to_working
            .inverse()
            .ok_or("a colour space without an inverse")?;
        let convert = |m: &Mat3, image: &[[f32; 3]]| -> Image {
            image
                .iter()
                .map(|p| m.apply(p.map(f64::from)).map(|v| v as f32))
                .collect()
        };
        let color = convert(&to_working, color);
        let albedo = convert(&to_working, albedo);
        let denoised = self.denoise_working(width, height, &color, &albedo, normal)?;
        Ok(convert(&back, &denoised))
    }

    /// [`Denoiser::denoise`] in the working space: non-finite values and what rounding
    /// leaves negative are 0 in the filter's inputs, albedo at most 1.
    fn denoise_working(
        &self,
        width: usize,
        height: usize,
        color: &[[f32; 3]],
        albedo: &[[f32; 3]],
        normal: &[[f32; 3]],
    ) -> Result<Image, String> {
        let clean = |image: &[[f32; 3]], lo: f32, hi: f32| -> Image {
            image
                .iter()
                .map(|p| p.map(|v| if v.is_finite() { v.clamp(lo, hi) } else { 0.0 }))
                .collect()
        };
        let color = clean(color, 0.0, f32::MAX);
        let albedo = clean(albedo, 0.0, 1.0);
        let normal = clean(normal, -1.0, 1.0);
        let fail = |e: String| format!("denoising failed: {e}");
        let albedo = self
            .oidn
            .filter(width, height, &[("albedo", &albedo)], &[])
            .map_err(fail)?;
        let normal = self
            .oidn
            .filter(width, height, &[("normal", &normal)], &[])
            .map_err(fail)?;
        let inputs = [("color", &color), ("albedo", &albedo), ("normal", &normal)];
        self.oidn
            .filter(width, height, &inputs, &[("hdr", true), ("cleanAux", true)])
            .map_err(fail)
    }
}

/// Where Open Image Denoise is, in this order: `PRISM_OIDN` (the library, or its
/// folder), `OIDN_DIR`'s `lib/`, the system's library path, then the `pyoidn` package of
/// the `python3` on `PATH` (or `PRISM_PYTHON`). One line saying what to install where none
/// has it.
pub fn find_library() -> Result<PathBuf, String> {
    let in_folder = |dir: PathBuf| dir.join(LIBRARY);
    if let Some(given) = std::env::var_os("PRISM_OIDN") {
        let given = PathBuf::from(given);
        let path = if given.is_dir() {
            in_folder(given)
        } else {
            given
        };
        return if path.exists() {
            Ok(path)
        } else {
            Err(format!(
                "PRISM_OIDN names '{}', which does not exist; {INSTALL}",
                path.display()
            ))
        };
    }
    if let Some(dir) = std::env::var_os("OIDN_DIR") {
        let path = in_folder(PathBuf::from(dir).join("lib"));
        if path.exists() {
            return Ok(path);
        }
    }
    if Oidn::loadable(Path::new(LIBRARY)) {
        return Ok(PathBuf::from(LIBRARY));
    }
    if let Some(dir) = pyoidn_folder() {
        let path = in_folder(dir);
        if path.exists() {
            return Ok(path);
        }
    }
    Err(format!(
        "--denoise needs Intel Open Image Denoise, which was not found: {INSTALL}"
    ))
}

/// The folder of the libraries the `pyoidn` wheel ships, asked of Python.
fn pyoidn_folder() -> Option<PathBuf> {
    let python = std::env::var_os("PRISM_PYTHON").unwrap_or_else(|| "python3".into());
    let script =
        "import os, pyoidn; print(os.path.join(os.path.dirname(pyoidn.__file__), 'oidn', 'lib'))";
    let out = Command::new(python).args(["-c", script]).output().ok()?;
    if !out.status.success() {
        return None;
    }
    let text = String::from_utf8(out.stdout).ok()?;
    Some(PathBuf::from(text.trim()))
}
