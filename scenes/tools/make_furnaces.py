"""Writes the furnaces the estimator matrix renders (integrator/tests/estimators.rs and
cli/tests/estimators.rs): scenes whose every pixel has a known expectation in every
output, so that any combination of settings can be judged against a closed form.

- scenes/assets/medium-furnace.gltf: a sphere (radius 0.5) of a medium that scatters and
  does not absorb (sigma_s falling from 8/m at 400 nm to 2/m at 700 nm, Henyey-Greenstein
  g 0.6) behind an `interface` boundary, seen by a perspective camera 2.2 away (yfov 0.5).
  Under a uniform environment (`--environment 0.5`) it is invisible: every pixel sees the
  environment at every wavelength.

Run from the repository root: python3 scenes/tools/make_furnaces.py
"""

from gltf_build import Document, sphere


def main():
    doc = Document("scenes/tools/make_furnaces.py")
    medium = doc.material(
        "scattering medium",
        extensions={"PRISM_spectral": {"type": "interface", "medium": {
            "sigma_a": 0.0,
            "sigma_s": [[400, 8.0], [700, 2.0]],
            "g": 0.6,
        }}},
    )
    positions, normals, indices = sphere((0.0, 0.0, 0.0), 0.5, rings=24, segments=48)
    doc.mesh("sphere", positions, medium, normals=normals, indices=indices)
    doc.camera("camera", (0.0, 0.0, 2.2), (0.0, 0.0, 0.0), {"yfov": 0.5, "znear": 0.01, "aspectRatio": 1.0})
    doc.write("scenes/assets/medium-furnace.gltf")


if __name__ == "__main__":
    main()
