"""Writes the lamp scenes of docs/trade-offs.md ("When the choice follows the
wavelengths"): the Cornell box (scenes/cornell-box.gltf) with KHR punctual lamps added.

    python3 docs/trade-offs/light-choice/make_scenes.py OUT_DIR

OUT_DIR receives the .gltf files and a copy of cornell-box.bin. Scenes:
- rgb3: three lamps of pure RGB colours (upsampled illuminant spectra), 20 cd each;
- led30, led40: three lamps of Gaussian bands at 460/540/620 nm, 30 or 40 nm wide, 40 cd;
- led20x12: twelve lamps, Gaussian bands 20 nm wide in those three colours, 5-40 cd;
- rgb12: twelve lamps of three desaturated RGB colours at 5-40 cd.
"""
import json
import shutil
import sys
from pathlib import Path

ROOT = Path(__file__).resolve().parents[3]


def box():
    return json.loads((ROOT / "scenes" / "cornell-box.gltf").read_text())


def with_lamps(lamps):
    """lamps: (light description, position) pairs."""
    g = box()
    g["extensionsUsed"] = g.get("extensionsUsed", []) + ["KHR_lights_punctual", "PRISM_spectral"]
    lights = []
    for k, (light, position) in enumerate(lamps):
        lights.append(dict(light, name=f"lamp{k}"))
        g["nodes"].append({"name": f"lamp{k}", "translation": position,
                           "extensions": {"KHR_lights_punctual": {"light": k}}})
        g["scenes"][0]["nodes"].append(len(g["nodes"]) - 1)
    g.setdefault("extensions", {})["KHR_lights_punctual"] = {"lights": lights}
    return g


def band(centre, width, intensity):
    return {"type": "point", "intensity": intensity,
            "extensions": {"PRISM_spectral": {"spectrum": f"gaussian:{centre}:{width}"}}}


def rgb(colour, intensity):
    return {"type": "point", "color": colour, "intensity": intensity}


def row(k):
    return [-0.5 + 0.5 * k, 0.6, 0.0]


def grid(ci, j):
    return [-0.8 + 0.5 * j, 0.7, -0.6 + 0.6 * ci]


CENTRES = [460, 540, 620]
SCENES = {
    "rgb3": with_lamps([(rgb(c, 20.0), row(k)) for k, c in enumerate([[1, 0, 0], [0, 1, 0], [0, 0, 1]])]),
    "led30": with_lamps([(band(c, 30, 40.0), row(k)) for k, c in enumerate(CENTRES)]),
    "led40": with_lamps([(band(c, 40, 40.0), row(k)) for k, c in enumerate(CENTRES)]),
    "led20x12": with_lamps([(band(c, 20, i), grid(ci, j)) for ci, c in enumerate(CENTRES)
                            for j, i in enumerate([5.0, 10.0, 20.0, 40.0])]),
    "rgb12": with_lamps([(rgb(c, i), grid(ci, j))
                         for ci, c in enumerate([[1, 0.15, 0.1], [0.1, 1, 0.2], [0.15, 0.2, 1]])
                         for j, i in enumerate([5.0, 10.0, 20.0, 40.0])]),
}

if __name__ == "__main__":
    out = Path(sys.argv[1])
    out.mkdir(parents=True, exist_ok=True)
    shutil.copy(ROOT / "scenes" / "cornell-box.bin", out / "cornell-box.bin")
    for name, scene in SCENES.items():
        (out / f"{name}.gltf").write_text(json.dumps(scene))
