"""prism, a spectral path tracer, from Python.

Spectra (`Spectrum`), colour conversions (`xyz_to_rgb`, `rgb_to_xyz`), RGB upsampling
(`upsample`, `upsample_spectrum`) and renders (`load`, `render`, `Render`) as numpy
arrays. Errors are `ValueError` for bad arguments and `SceneError` for scenes that cannot
be loaded or rendered.
"""

from ._prism import (
    Render,
    Scene,
    SceneError,
    Spectrum,
    load,
    render,
    rgb_to_xyz,
    spaces,
    upsample,
    upsample_spectrum,
    xyz_to_rgb,
)

__all__ = [
    "Render",
    "Scene",
    "SceneError",
    "Spectrum",
    "load",
    "render",
    "rgb_to_xyz",
    "spaces",
    "upsample",
    "upsample_spectrum",
    "xyz_to_rgb",
]
