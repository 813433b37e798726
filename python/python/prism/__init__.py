"""prism, a spectral path tracer, from Python.

Spectra (`Spectrum`), colour conversions (`xyz_to_rgb`, `rgb_to_xyz`), RGB upsampling
(`upsample`, `upsample_spectrum`) and renders (`load`, `load_dict`, `render`, `Render`)
as numpy arrays. glTF scenes and Mitsuba 3 scenes load alike: `prism.load("scene.xml",
spp=64)` as `mi.load_file`, `prism.load_dict({...})` as `mi.load_dict`. Errors are
`ValueError` for bad arguments, `TypeError` for unknown keywords, and `SceneError` for
scenes that cannot be loaded or rendered.
"""

import os as _os

from ._prism import (
    Render,
    Scene,
    SceneError,
    Spectrum,
    __version__,
    load,
    load_mitsuba_xml as _load_mitsuba_xml,
    render,
    rgb_to_xyz,
    spaces,
    upsample,
    upsample_spectrum,
    xyz_to_rgb,
)
from ._mitsuba_dict import to_xml as _to_xml


def load_dict(scene, **parameters):
    """Loads a Mitsuba 3 scene given in Mitsuba's dict form, as `mi.load_dict` does
    (`{"type": "scene", "sensor": {"type": "perspective", ...}, ...}`); files it names
    resolve relative to the working directory. A dict that is not a scene raises
    `ValueError`; a scene prism cannot load raises `SceneError`."""
    return _load_mitsuba_xml(_to_xml(scene), _os.getcwd(), **parameters)


__all__ = [
    "Render",
    "Scene",
    "SceneError",
    "Spectrum",
    "__version__",
    "load",
    "load_dict",
    "render",
    "rgb_to_xyz",
    "spaces",
    "upsample",
    "upsample_spectrum",
    "xyz_to_rgb",
]
