"""Writes scenes/lens-chart.gltf: a chart of small white lights, for comparing real lenses
(docs/guide/cameras.md, "Real lenses"): through an uncorrected singlet each light is a sharp core in a
coloured halo (the F and C lines focus before and behind the d line) and the chart's
edges show colour fringes; through a cemented achromat the lights stay white and sharp.

- A 9 x 6 grid of 8 mm square lights (daylight, 6500 K) and two thin white bars at the
  frame's sides, on a black card 3 m in front of the camera.
- The camera mounts scenes/lenses/singlet.dat (a 97 mm BK7 singlet) on a full-frame film,
  at f/5.6, focused at 3 m; `prism render --lens scenes/lenses/achromat.dat` swaps the lens.

Units are metres; y is up. Run from the repository root:
python3 scenes/tools/make_lens_chart.py
"""

from gltf_build import Document, facing, quad


def main():
    doc = Document("scenes/tools/make_lens_chart.py")
    card = doc.material(
        "card", pbrMetallicRoughness={"baseColorFactor": [0.02, 0.02, 0.02, 1.0], "metallicFactor": 0.0, "roughnessFactor": 1.0}
    )
    z = -3.0
    doc.mesh("card", facing(quad((-2, -2, z - 0.01), (2, -2, z - 0.01), (2, 2, z - 0.01), (-2, 2, z - 0.01)), lambda p: [0, 0, 1]), card)
    white = doc.material(
        "white light",
        extensions={"PRISM_spectral": {"type": "diffuse", "reflectance": 0.0, "emission": {"spectrum": "daylight:6500", "scale": 0.0006}}},
    )
    positions = []
    h = 0.004
    for j in range(6):
        for i in range(9):
            x = -0.48 + 0.12 * i
            y = -0.30 + 0.12 * j
            positions += facing(quad((x - h, y - h, z), (x + h, y - h, z), (x + h, y + h, z), (x - h, y + h, z)), lambda p: [0, 0, 1])
    for x in (-0.53, 0.53):
        positions += facing(quad((x - 0.002, -0.34, z), (x + 0.002, -0.34, z), (x + 0.002, 0.34, z), (x - 0.002, 0.34, z)), lambda p: [0, 0, 1])
    doc.mesh("lights", positions, white)
    doc.camera("camera", (0.0, 0.0, 0.0), (0.0, 0.0, z), {"yfov": 0.25, "aspectRatio": 1.5, "znear": 0.01})
    doc.cameras[-1]["extensions"] = {"PRISM_spectral": {"lens": "lenses/singlet.dat", "aperture": {"f_number": 5.6}, "focus_distance": 3.0}}
    doc.write("scenes/lens-chart.gltf")


if __name__ == "__main__":
    main()
