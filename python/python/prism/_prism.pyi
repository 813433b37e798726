"""Type stubs of prism's native module (re-exported by `prism`)."""

from os import PathLike
from typing import Any, Callable, Optional, Protocol, Tuple, Union

import numpy as np
import numpy.typing as npt

ArrayLike = npt.ArrayLike

class _Distribution(Protocol):
    wavelengths: Any
    values: Any

SpectrumLike = Union["Spectrum", str, _Distribution]

class SceneError(Exception):
    """A scene that cannot be loaded or rendered (the message names the file and the reason)."""

class Spectrum:
    """A spectrum: values per wavelength in nanometres."""

    def __init__(self, value: SpectrumLike) -> None:
        """A named spectrum's string, a Spectrum, or anything with .wavelengths and .values."""
    @staticmethod
    def named(name: str) -> "Spectrum":
        """A named spectrum of the scene format: blackbody:T, illuminant:NAME, daylight:CCT, ..."""
    @staticmethod
    def from_samples(wavelengths: ArrayLike, values: ArrayLike) -> "Spectrum":
        """A piecewise-linear spectrum through the samples (nm, increasing), zero outside them."""
    @staticmethod
    def from_colour(distribution: _Distribution) -> "Spectrum":
        """A spectrum from a colour-science SpectralDistribution."""
    def __call__(self, wavelengths: ArrayLike) -> npt.NDArray[np.float64]:
        """The values at wavelengths (nm), an array of their shape."""
    def to_xyz(self, observer: str = "cie1931") -> Tuple[float, float, float]:
        """CIE XYZ of the spectrum as an emission under observer (cie1931 or cie1964)."""
    def to_colour(self) -> Any:
        """A colour-science SpectralDistribution, 360-830 nm in 1 nm steps."""

def xyz_to_rgb(xyz: ArrayLike, space: str = "srgb") -> npt.NDArray[np.float64]:
    """CIE XYZ to linear RGB in space, over arrays of shape (..., 3)."""

def rgb_to_xyz(rgb: ArrayLike, space: str = "srgb") -> npt.NDArray[np.float64]:
    """Linear RGB in space to CIE XYZ, over arrays of shape (..., 3)."""

def spaces() -> list[str]:
    """The names of the RGB spaces."""

def upsample(
    rgb: ArrayLike, space: str = "srgb", kind: str = "reflectance", method: str = "exact"
) -> npt.NDArray[np.float64]:
    """Sigmoid-polynomial coefficients (..., 3) for linear RGB colours (..., 3); (..., 4) with the scale for kind unbounded or illuminant."""

def upsample_spectrum(
    rgb: ArrayLike, space: str = "srgb", kind: str = "reflectance", method: str = "exact"
) -> Spectrum:
    """One linear RGB colour as a Spectrum."""

class Scene:
    """A loaded scene."""

    @property
    def cameras(self) -> list[str]:
        """The names of the scene's cameras."""
    @property
    def materials(self) -> list[str]:
        """The names of the scene's materials."""
    @property
    def lights(self) -> list[str]:
        """A short description of each light."""
    @property
    def path(self) -> str:
        """The file the scene was read from."""
    def set_material(self, name: str, description: dict[str, Any]) -> None:
        """Replaces material name's PRISM_spectral description (spectra may be Spectrum objects); raises SceneError and changes nothing on a bad one."""
    def set_light(self, name: str, description: dict[str, Any]) -> None:
        """Replaces punctual light name's PRISM_spectral description."""
    def set_environment(self, environment: Any) -> None:
        """Replaces the environment: a spectrum, a number or {"image": ..., "rotation": ...}."""

__version__: str

def load(path: Union[str, PathLike[str]], scene: Optional[int] = None, **parameters: Any) -> Scene:
    """Loads a .gltf, .glb, .toml overlay or Mitsuba 3 .xml (keywords: its parameters, as mi.load_file's); raises SceneError naming the file."""

def load_mitsuba_xml(text: str, directory: Union[str, PathLike[str]], **parameters: Any) -> Scene:
    """Loads a Mitsuba 3 scene's XML text; files it names resolve relative to directory."""

class Render:
    """A finished render."""

    @property
    def rgb(self) -> npt.NDArray[np.float32]:
        """Linear RGB in the render's space, (H, W, 3); denoised with denoise=True."""
    @property
    def noisy(self) -> npt.NDArray[np.float32]:
        """The film's RGB before any denoising, (H, W, 3)."""
    @property
    def aovs(self) -> list[str]:
        """The AOVs recorded (aov="albedo,normal", denoise=True)."""
    def aov(self, name: str) -> npt.NDArray[np.float32]:
        """An AOV: (H, W, 3) for albedo, normal, position, variance; (H, W) for depth, material_id."""
    @property
    def alpha(self) -> npt.NDArray[np.float32]:
        """Coverage, (H, W)."""
    @property
    def xyz(self) -> npt.NDArray[np.float64]:
        """CIE 1931 XYZ, (H, W, 3)."""
    @property
    def spectral(self) -> Optional[npt.NDArray[np.float64]]:
        """Spectral radiance per band with bands=N, (H, W, N)."""
    @property
    def wavelengths(self) -> Optional[list[float]]:
        """The bands' centres, nm."""
    @property
    def stats(self) -> dict[str, Any]:
        """The statistics prism render --stats prints."""
    def save(self, path: Union[str, PathLike[str]]) -> None:
        """Writes .exr or .png as prism render -o writes it."""
    def to_colour(self) -> Any:
        """The bands as a colour-science MultiSpectralDistributions (one column per pixel)."""

def render(
    scene: Scene,
    spp: Optional[int] = None,
    width: Optional[int] = None,
    height: Optional[int] = None,
    seed: int = 0,
    threads: Optional[int] = None,
    progress: Union[bool, Callable[[int, int], Any], None] = None,
    **settings: Any,
) -> Render:
    """Renders scene with prism render's settings as keywords (max_depth=8, bands=16, ...); a Mitsuba scene's film and sampler give the size and spp the call does not, other scenes render 64 x 64 at 16 spp; progress=True shows the progress line, a callable gets (done, total) samples per pixel."""
