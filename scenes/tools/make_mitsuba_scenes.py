#!/usr/bin/env python3
"""Writes scenes/mitsuba/*.xml: Mitsuba 3 scene files that prism's XML loader is tested on.

cornell-box.xml is Mitsuba's own `mi.cornell_box()` (the dictionary its Python package
returns; the box scenes/cornell-box.gltf reproduces) written as XML, with the film and
sampler the shared peer scripts use (box filter). The script then loads the XML back with
Mitsuba and checks that it renders the dictionary's image, so the file is Mitsuba's scene,
not a transcription of it.

  python3 -m venv /tmp/venv && /tmp/venv/bin/pip install mitsuba numpy
  /tmp/venv/bin/python scenes/tools/make_mitsuba_scenes.py
"""

import os
import sys

import mitsuba as mi
import numpy as np

mi.set_variant("scalar_spectral")

CLASSES = {
    "rectangle": "shape", "cube": "shape", "sphere": "shape", "disk": "shape", "obj": "shape",
    "ply": "shape", "diffuse": "bsdf", "dielectric": "bsdf", "conductor": "bsdf",
    "area": "emitter", "constant": "emitter", "point": "emitter", "perspective": "sensor",
    "hdrfilm": "film", "independent": "sampler", "box": "rfilter", "path": "integrator",
}



def number(v):
    return repr(float(v)) if isinstance(v, float) else str(v)


def value(name, v, indent):
    pad = " " * indent
    if isinstance(v, bool):
        return f'{pad}<boolean name="{name}" value="{str(v).lower()}"/>'
    if isinstance(v, int):
        return f'{pad}<integer name="{name}" value="{v}"/>'
    if isinstance(v, float):
        return f'{pad}<float name="{name}" value="{number(v)}"/>'
    if isinstance(v, str):
        return f'{pad}<string name="{name}" value="{v}"/>'
    if isinstance(v, mi.ScalarTransform4f):
        m = np.array(v.matrix).reshape(4, 4)
        values = " ".join(f"{x:.9g}" for x in m.flatten())
        return f'{pad}<transform name="{name}">\n{pad}    <matrix value="{values}"/>\n{pad}</transform>'
    if isinstance(v, dict):
        return obj(v, indent, name=name)
    raise TypeError(f"{name}: {type(v)}")


def obj(d, indent, name=None, id=None):
    pad = " " * indent
    kind = d["type"]
    if kind == "ref":
        attrs = f' name="{name}"' if name else ""
        return f'{pad}<ref{attrs} id="{d["id"]}"/>'
    if kind == "rgb":
        return f'{pad}<rgb name="{name}" value="{", ".join(number(float(x)) for x in d["value"])}"/>'
    tag = CLASSES[kind]
    attrs = f' type="{kind}"' + (f' id="{id}"' if id else "") + (
        f' name="{name}"' if name and tag == "texture" else "")
    lines = [f"{pad}<{tag}{attrs}>"]
    for k, v in d.items():
        if k == "type":
            continue
        lines.append(value(k, v, indent + 4))
    lines.append(f"{pad}</{tag}>")
    return "\n".join(lines)


def scene_xml(d):
    lines = ['<scene version="3.0.0">']
    # Referenced objects first, as Mitsuba's own files define them.
    items = [(k, v) for k, v in d.items() if k != "type"]
    items.sort(key=lambda kv: CLASSES.get(kv[1]["type"], "") != "bsdf")
    for key, v in items:
        lines.append(obj(v, 4, id=key))
    lines.append("</scene>")
    return "\n".join(lines) + "\n"


def cornell_box():
    d = mi.cornell_box()
    d["sensor"]["film"]["rfilter"] = {"type": "box"}
    return d


def main():
    out = os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "mitsuba")
    os.makedirs(out, exist_ok=True)
    d = cornell_box()
    path = os.path.join(out, "cornell-box.xml")
    with open(path, "w") as f:
        f.write("<!-- Mitsuba 3's mi.cornell_box(), written by scenes/tools/make_mitsuba_scenes.py -->\n")
        f.write(scene_xml(d))
    # The file is Mitsuba's scene: it renders the dictionary's image, sample for sample
    # (within float32 rounding: its transforms' inverses are computed from the matrices).
    a = np.array(mi.render(mi.load_dict(d), spp=16, seed=3))
    b = np.array(mi.render(mi.load_file(path), spp=16, seed=3))
    worst = float(np.abs(a - b).max() / np.abs(a).max())
    if worst > 1e-5:
        sys.exit(f"{path}: Mitsuba renders it differently from mi.cornell_box() ({worst:.2e})")
    print(f"wrote {path} (Mitsuba renders it as mi.cornell_box(), within {worst:.1e})")
    reference(path, "cornell-box", size=32, spp=16384)


def reference(path, name, size, spp):
    """Mitsuba's render of the scene at `path`, `size` pixels square: the reference
    cli/tests/mitsuba.rs compares prism's render of the same file with."""
    text = open(path).read()
    for axis in ("width", "height"):
        text = text.replace(f'name="{axis}" value="256"', f'name="{axis}" value="{size}"')
    image = mi.render(mi.load_string(text), spp=spp, seed=7)
    out = os.path.join(os.path.dirname(path), "references", f"{name}-{size}.exr")
    os.makedirs(os.path.dirname(out), exist_ok=True)
    mi.Bitmap(image).write(out)
    print(f"wrote {out} (Mitsuba {mi.__version__} scalar_spectral, {spp} spp)")


if __name__ == "__main__":
    main()
