"""The Python package against its own promises, colour-science and the command line.

Run after `pip install ./python` (with pytest and colour-science): `python -m pytest python/tests`.
PRISM_BIN names a `prism` binary of the same source for the comparisons with the command
line (.ci/run sets it).
"""

import json
import os
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest

import prism

ROOT = Path(__file__).resolve().parents[2]
SCENES = ROOT / "scenes"

with warnings.catch_warnings():
    warnings.simplefilter("ignore")
    import colour


def prism_bin():
    path = os.environ.get("PRISM_BIN")
    if not path:
        pytest.fail("PRISM_BIN must name the prism binary built from this source")
    return path


# Spectra


def test_named_spectra_equal_colour_science():
    d65 = prism.Spectrum.named("illuminant:D65")
    nm = np.arange(360.0, 831.0)
    reference = colour.SDS_ILLUMINANTS["D65"]
    np.testing.assert_allclose(d65(nm)[nm <= 780], reference[nm[nm <= 780]], rtol=1e-6)
    a = prism.Spectrum.named("illuminant:A")
    np.testing.assert_allclose(a(nm[nm <= 780]), colour.SDS_ILLUMINANTS["A"][nm[nm <= 780]], rtol=1e-6)


def test_xyz_equals_colour_science_integration():
    for name, observer, cmfs in [
        ("illuminant:D65", "cie1931", "CIE 1931 2 Degree Standard Observer"),
        ("blackbody:3000", "cie1964", "CIE 1964 10 Degree Standard Observer"),
    ]:
        s = prism.Spectrum.named(name)
        expected = colour.sd_to_XYZ(s.to_colour(), cmfs=colour.MSDS_CMFS[cmfs], k=1, method="Integration")
        np.testing.assert_allclose(s.to_xyz(observer), expected, rtol=1e-6)


def test_spectra_evaluate_arrays_of_any_shape_dtype_and_strides():
    s = prism.Spectrum.from_samples([400, 500, 600], [0.0, 1.0, 0.5])
    assert s(450.0).shape == ()
    assert float(s(450.0)) == pytest.approx(0.5)
    grid = np.arange(380, 620, dtype=np.int32).reshape(4, 60)
    values = s(grid)
    assert values.shape == (4, 60) and values.dtype == np.float64
    strided = np.linspace(380.0, 700.0, 40)[::3]
    np.testing.assert_allclose(s(strided), np.interp(strided, [400, 500, 600], [0, 1, 0.5], left=0, right=0))
    transposed = np.arange(400.0, 600.0).reshape(20, 10).T
    np.testing.assert_allclose(s(transposed), s(np.ascontiguousarray(transposed)))
    assert s(np.array([], dtype=float)).shape == (0,)


def test_colour_distributions_are_spectra():
    sd = colour.SDS_ILLUMINANTS["D50"]
    s = prism.Spectrum(sd)
    np.testing.assert_allclose(s([450.0, 555.0]), sd[[450.0, 555.0]], rtol=1e-9)
    assert prism.Spectrum("blackbody:5000")(500.0) > 0
    back = prism.Spectrum.from_colour(s.to_colour())
    np.testing.assert_allclose(back([500.0, 600.5]), s([500.0, 600.5]), rtol=1e-6)


def test_bad_spectra_are_value_errors():
    with pytest.raises(ValueError, match="illuminant"):
        prism.Spectrum.named("illuminant:nope")
    with pytest.raises(ValueError):
        prism.Spectrum.from_samples([500, 400], [1, 2])
    with pytest.raises(ValueError):
        prism.Spectrum.from_samples([400, 500], [1, float("nan")])
    with pytest.raises(ValueError):
        prism.Spectrum(42)
    with pytest.raises(ValueError):
        prism.Spectrum.named("blackbody:300").to_xyz("cie2000")


# Colour


def derived(space):
    cs = colour.RGB_COLOURSPACES[space].copy()
    cs.use_derived_transformation_matrices(True)
    return cs


@pytest.mark.parametrize("ours,theirs", [("srgb", "sRGB"), ("acescg", "ACEScg"), ("rec2020", "ITU-R BT.2020"), ("display-p3", "Display P3")])
def test_colour_conversions_equal_colour_science(ours, theirs):
    xyz = np.random.default_rng(1).random((5, 4, 3))
    expected = colour.XYZ_to_RGB(xyz, derived(theirs), apply_cctf_encoding=False, chromatic_adaptation_transform=None)
    rgb = prism.xyz_to_rgb(xyz, space=ours)
    assert rgb.shape == (5, 4, 3)
    np.testing.assert_allclose(rgb, expected, atol=1e-6)
    np.testing.assert_allclose(prism.rgb_to_xyz(rgb, space=ours), xyz, atol=1e-9)


def test_colour_conversion_shapes_and_errors():
    assert prism.xyz_to_rgb([0.2, 0.3, 0.4]).shape == (3,)
    assert prism.rgb_to_xyz(np.zeros((0, 3))).shape == (0, 3)
    with pytest.raises(ValueError, match=r"\(\.\.\., 3\)"):
        prism.xyz_to_rgb(np.zeros((4, 2)))
    with pytest.raises(ValueError, match="srgb"):
        prism.xyz_to_rgb([0.2, 0.3, 0.4], space="nope")
    assert "srgb" in prism.spaces() and "acescg" in prism.spaces()


# Upsampling


def test_upsampled_reflectances_reproduce_their_colour():
    rgb = np.array([[0.8, 0.2, 0.1], [0.1, 0.6, 0.3], [0.2, 0.3, 0.9]])
    coefficients = prism.upsample(rgb)
    assert coefficients.shape == (3, 3)
    d65 = colour.SDS_ILLUMINANTS["D65"]
    cmfs = colour.MSDS_CMFS["CIE 1931 2 Degree Standard Observer"]
    for c, colour_rgb in zip(coefficients, rgb):
        nm = np.arange(360.0, 831.0)
        x = nm
        values = 0.5 + (c[0] * x * x + c[1] * x + c[2]) / (2 * np.sqrt(1 + (c[0] * x * x + c[1] * x + c[2]) ** 2))
        assert values.min() >= 0 and values.max() <= 1
        spectrum = prism.upsample_spectrum(colour_rgb)
        np.testing.assert_allclose(spectrum(nm), values, atol=1e-9)
        sd = colour.SpectralDistribution(values, nm)
        xyz = colour.sd_to_XYZ(sd, cmfs=cmfs, illuminant=d65) / 100
        np.testing.assert_allclose(prism.xyz_to_rgb(xyz), colour_rgb, atol=2e-3)


def test_upsample_shapes_kinds_and_methods():
    rgb = np.random.default_rng(2).random((6, 5, 3))[:, ::2]  # non-contiguous
    assert prism.upsample(rgb).shape == (6, 3, 3)
    assert prism.upsample(rgb, kind="unbounded").shape == (6, 3, 4)
    exact = prism.upsample(rgb.reshape(-1, 3))
    table = prism.upsample(rgb.reshape(-1, 3), method="table")
    assert np.abs(exact - table).max() < 5.0  # same kind of coefficients, looked up
    black = prism.upsample([0.0, 0.0, 0.0])
    assert black[2] == -np.inf
    with pytest.raises(ValueError, match="rgb"):
        prism.upsample([[0.5, np.nan, 0.5]])
    with pytest.raises(ValueError, match="table"):
        prism.upsample([0.5, 0.5, 0.5], space="rec2020", method="table")
    with pytest.raises(ValueError, match="kind"):
        prism.upsample([0.5, 0.5, 0.5], kind="paint")
    emission = prism.upsample_spectrum([1.0, 1.0, 1.0], kind="illuminant")
    assert emission(560.0) > 0


# Scenes and renders


def test_load_lists_cameras_materials_lights():
    scene = prism.load(SCENES / "cornell-box.gltf")
    assert "white" in scene.materials
    assert len(scene.lights) >= 1 and "area light" in scene.lights[0]
    assert len(scene.cameras) >= 1
    with pytest.raises(prism.SceneError, match="nope.gltf"):
        prism.load(SCENES / "nope.gltf")


def test_render_arrays_and_stats():
    scene = prism.load(SCENES / "cornell-box.gltf")
    image = prism.render(scene, spp=2, width=12, height=10, seed=3)
    assert image.rgb.shape == (10, 12, 3) and image.rgb.dtype == np.float32
    assert image.alpha.shape == (10, 12)
    assert image.xyz.shape == (10, 12, 3)
    assert image.spectral is None and image.wavelengths is None
    assert image.stats["spp"] == 2 and image.stats["width"] == 12
    total = image.stats["total_seconds"]
    time.sleep(0.05)
    assert image.stats["total_seconds"] == total  # taken when the render ended
    # The estimators the render used, each with why: 2 spp is too few for adaptive sampling.
    estimators = image.stats["estimators"]
    assert estimators["tracer"] == "paths" and estimators["adaptive"] is False
    assert "16" in estimators["adaptive_why"] and estimators["reuse"] == image.stats["reuse"]
    assert np.isfinite(image.rgb).all() and image.rgb.mean() > 0
    np.testing.assert_allclose(prism.xyz_to_rgb(image.xyz), image.rgb, rtol=1e-4, atol=1e-6)
    again = prism.render(scene, spp=2, width=12, height=10, seed=3, threads=1)
    assert np.array_equal(image.rgb, again.rgb)


def test_spectral_bands_and_colour_science():
    scene = prism.load(SCENES / "cornell-box.gltf")
    image = prism.render(scene, spp=2, width=8, height=6, bands=10, band_range="400:700")
    assert image.spectral.shape == (6, 8, 10)
    np.testing.assert_allclose(image.wavelengths, np.arange(415.0, 700.0, 30.0))
    msds = image.to_colour()
    assert msds.shape.start == 415.0 and len(msds.labels) == 48


def test_images_equal_the_command_lines(tmp_path):
    scene_path = SCENES / "cornell-box.gltf"
    image = prism.render(prism.load(scene_path), spp=3, width=16, height=12, seed=5, max_depth=4, wavelengths=4)
    ours = tmp_path / "python.exr"
    image.save(ours)
    image.save(tmp_path / "python.png")
    theirs = tmp_path / "cli.exr"
    subprocess.run(
        [prism_bin(), "render", str(scene_path), "--spp", "3", "--width", "16", "--height", "12", "--seed", "5",
         "--max-depth", "4", "--wavelengths", "4", "-o", str(theirs), "-o", str(tmp_path / "cli.png"), "--quiet"],
        check=True,
    )
    assert ours.read_bytes() == theirs.read_bytes()
    assert (tmp_path / "python.png").read_bytes() == (tmp_path / "cli.png").read_bytes()


def test_aovs_are_arrays_and_equal_the_command_lines(tmp_path):
    scene_path = SCENES / "cornell-box.gltf"
    image = prism.render(prism.load(scene_path), spp=2, width=16, height=12, aov="albedo,depth,material_id")
    assert image.aovs == ["albedo", "depth", "material_id"]
    assert image.aov("albedo").shape == (12, 16, 3) and image.aov("depth").shape == (12, 16)
    ids = image.aov("material_id")
    assert ids.min() >= 0 and ids.max() <= len(prism.load(scene_path).materials) and (ids == np.round(ids)).all()
    with pytest.raises(KeyError, match="normal"):
        image.aov("normal")
    assert np.array_equal(image.rgb, image.noisy)
    ours, theirs = tmp_path / "python.exr", tmp_path / "cli.exr"
    image.save(ours)
    subprocess.run(
        [prism_bin(), "render", str(scene_path), "--spp", "2", "--width", "16", "--height", "12",
         "--aov", "albedo,depth,material_id", "-o", str(theirs), "--quiet"],
        check=True,
    )
    assert ours.read_bytes() == theirs.read_bytes()


def oidn_required():
    """Whether this run must denoise (CI sets PRISM_REQUIRE_OIDN and PRISM_OIDN)."""
    return bool(os.environ.get("PRISM_REQUIRE_OIDN"))


def test_denoised_renders(tmp_path):
    if not os.environ.get("PRISM_OIDN") and not oidn_required():
        pytest.skip("set PRISM_OIDN to libOpenImageDenoise (pip install pyoidn)")
    scene_path = SCENES / "cornell-box.gltf"
    image = prism.render(prism.load(scene_path), spp=4, width=64, height=48, denoise=True)
    assert image.aovs == ["albedo", "normal"]
    assert not np.array_equal(image.rgb, image.noisy)
    # Denoising smooths: neighbouring pixels differ less.
    roughness = lambda a: float(np.abs(np.diff(a, axis=1)).mean())
    assert roughness(image.rgb) < 0.7 * roughness(image.noisy)
    ours, theirs = tmp_path / "python.exr", tmp_path / "cli.exr"
    image.save(ours)
    subprocess.run(
        [prism_bin(), "render", str(scene_path), "--spp", "4", "--width", "64", "--height", "48", "--denoise",
         "-o", str(theirs), "--quiet"],
        check=True,
    )
    assert ours.read_bytes() == theirs.read_bytes()


def test_edited_materials_equal_an_overlay_file(tmp_path):
    scene = prism.load(SCENES / "cornell-box.gltf")
    before = prism.render(scene, spp=2, width=12, height=12)
    scene.set_material("white-emitter", {"emission": {"spectrum": "illuminant:A", "scale": 17.0}})
    scene.set_material("green", {"type": "diffuse", "reflectance": prism.Spectrum.from_samples([400, 550, 700], [0.1, 0.8, 0.1])})
    after = prism.render(scene, spp=2, width=12, height=12)
    assert not np.array_equal(before.rgb, after.rgb)
    after.save(tmp_path / "python.exr")
    table = ", ".join(f"[{nm}, {v!r}]" for nm, v in zip(range(300, 1001), prism.Spectrum.from_samples([400, 550, 700], [0.1, 0.8, 0.1])(np.arange(300.0, 1001.0))))
    overlay = tmp_path / "edited.toml"
    overlay.write_text(
        f'gltf = "{SCENES / "cornell-box.gltf"}"\n'
        '[materials.white-emitter]\nemission = { spectrum = "illuminant:A", scale = 17.0 }\n'
        f'[materials.green]\ntype = "diffuse"\nreflectance = [{table}]\n'
    )
    subprocess.run([prism_bin(), "render", str(overlay), "--spp", "2", "--width", "12", "--height", "12",
                    "-o", str(tmp_path / "cli.exr"), "--quiet"], check=True)
    assert (tmp_path / "python.exr").read_bytes() == (tmp_path / "cli.exr").read_bytes()
    with pytest.raises(prism.SceneError, match="nope"):
        scene.set_material("nope", {"reflectance": 0.5})
    with pytest.raises(prism.SceneError):
        scene.set_material("red", {"type": "diffuse", "reflectance": -1.0})
    assert np.array_equal(prism.render(scene, spp=2, width=12, height=12).rgb, after.rgb)
    scene.set_environment(0.0)


def test_progress_callbacks_and_stopping():
    scene = prism.load(SCENES / "cornell-box.gltf")
    calls = []
    prism.render(scene, spp=6, width=8, height=8, progress=lambda done, total: calls.append((done, total)))
    assert calls and calls[-1] == (6, 6) and all(t == 6 for _, t in calls)
    assert [d for d, _ in calls] == sorted(d for d, _ in calls)

    class Stop(Exception):
        pass

    def stop(done, total):
        raise Stop()

    with pytest.raises(Stop):
        prism.render(scene, spp=2000, width=64, height=64, progress=stop)


def test_ctrl_c_stops_a_render_and_keeps_it():
    import signal

    scene = prism.load(SCENES / "cornell-box.gltf")

    # Ctrl-C once a pass is done (a timer could fire before the first on a busy host).
    def ctrl_c(done, total):
        if done >= 1:
            os.kill(os.getpid(), signal.SIGINT)

    with pytest.raises(KeyboardInterrupt) as stopped:
        prism.render(scene, spp=100000, width=64, height=64, progress=ctrl_c)
    partial = stopped.value.args[1]
    assert isinstance(partial, prism.Render)
    assert 0 < partial.stats["spp"] < 100000
    assert partial.stats["ending"] == "Interrupted"
    assert np.isfinite(partial.rgb).all() and partial.rgb.mean() > 0


def test_bad_settings_are_value_errors():
    scene = prism.load(SCENES / "cornell-box.gltf")
    with pytest.raises(ValueError, match="spp"):
        prism.render(scene, spp=-1)
    # An unknown keyword is Python's TypeError, in Python's words, not a command line tip.
    with pytest.raises(TypeError, match="unexpected keyword argument 'no_such_setting'") as e:
        prism.render(scene, spp=1, no_such_setting=3)
    assert "tip" not in str(e.value) and "--" not in str(e.value)
    with pytest.raises(ValueError, match="output"):
        prism.render(scene, spp=1, output="x.png")
    # A bad value of a known setting is a ValueError, the scene being fine.
    with pytest.raises(ValueError, match="wavelengths") as e:
        prism.render(scene, spp=1, width=4, height=4, wavelengths=3)
    assert not isinstance(e.value, prism.SceneError)


def test_version_is_the_packages():
    import importlib.metadata

    assert prism.__version__ == importlib.metadata.version("prism-spectral")


MITSUBA_BOX = SCENES / "mitsuba" / "cornell-box.xml"


def test_a_mitsuba_scene_loads_with_parameters_and_renders_as_the_command_line(tmp_path):
    # The file's film (256 x 256) and sampler count stand where the call is silent.
    scene = prism.load(MITSUBA_BOX)
    assert "Scene(" in repr(scene) and scene.lights
    image = prism.render(scene, spp=2, width=16, height=16, seed=3)
    ours = tmp_path / "python.exr"
    image.save(ours)
    theirs = tmp_path / "cli.exr"
    subprocess.run([prism_bin(), "render", str(MITSUBA_BOX), "--spp", "2", "--width", "16",
                    "--height", "16", "--seed", "3", "-o", str(theirs), "--quiet"], check=True)
    assert ours.read_bytes() == theirs.read_bytes()
    # Keywords are the file's parameters, as mi.load_file's are; a glTF has none.
    xml = tmp_path / "param.xml"
    xml.write_text(MITSUBA_BOX.read_text().replace('value="256"', 'value="$res"').replace(
        '<scene version="3.0.0">', '<scene version="3.0.0"><default name="res" value="256"/>'))
    small = prism.render(prism.load(xml, res=8), spp=1)
    assert small.rgb.shape == (8, 8, 3)
    with pytest.raises(TypeError, match="'res'"):
        prism.load(SCENES / "cornell-box.gltf", res=8)
    with pytest.raises(prism.SceneError, match="set_material"):
        scene.set_material("x", {"reflectance": 0.5})


def test_load_dict_reads_mitsubas_dict_form():
    # The same scene as a dict, as a Mitsuba user's script writes it: renders the XML's image.
    d = {
        "type": "scene",
        "integrator": {"type": "path", "max_depth": 4},
        "sensor": {
            "type": "perspective",
            "fov": 45.0,
            "to_world": [[-1, 0, 0, 0], [0, 1, 0, 0], [0, 0, -1, 4], [0, 0, 0, 1]],
            "film": {"type": "hdrfilm", "width": 12, "height": 10, "rfilter": {"type": "box"}},
            "sampler": {"type": "independent", "sample_count": 3},
        },
        "grey": {"type": "diffuse", "reflectance": {"type": "rgb", "value": [0.5, 0.4, 0.3]}},
        "floor": {"type": "rectangle", "bsdf": {"type": "ref", "id": "grey"}},
        "light": {
            "type": "rectangle",
            "to_world": [[0.2, 0, 0, 0], [0, 0.2, 0, 0], [0, 0, -1, 2], [0, 0, 0, 1]],
            "emitter": {"type": "area", "radiance": {"type": "spectrum", "value": [(400, 5.0), (700, 10.0)]}},
        },
    }
    scene = prism.load_dict(d)
    image = prism.render(scene, seed=1)
    assert image.rgb.shape == (10, 12, 3) and image.stats["spp"] == 3
    assert np.isfinite(image.rgb).all() and image.rgb.mean() > 0
    with pytest.raises(ValueError, match="scene"):
        prism.load_dict({"type": "diffuse"})
    with pytest.raises(ValueError, match="'teapot'"):
        prism.load_dict({"type": "scene", "x": {"type": "teapot"}})
    with pytest.raises(prism.SceneError):
        prism.load_dict({"type": "scene", "s": {"type": "obj", "filename": "nope.obj"}})


# The documents' Python snippets run as written, from a directory where scenes/ is the
# repository's.


def python_blocks(path):
    blocks, inside, lines = [], False, []
    for line in path.read_text().splitlines():
        if line.strip() == "```python":
            inside, lines = True, []
        elif inside and line.strip() == "```":
            inside = False
            blocks.append("\n".join(lines))
        elif inside:
            lines.append(line)
    return blocks


@pytest.mark.parametrize("document", ["README.md", "docs/guide/python.md", "docs/guide/denoising.md",
                                      "docs/guide/from-mitsuba.md"])
def test_documented_snippets_run(document, tmp_path, monkeypatch):
    blocks = python_blocks(ROOT / document)
    assert blocks, f"{document} has no python block"
    (tmp_path / "scenes").symlink_to(SCENES)
    monkeypatch.chdir(tmp_path)
    for block in blocks:
        exec(compile(block, document, "exec"), {})


def test_the_example_runs(tmp_path, monkeypatch):
    (tmp_path / "scenes").symlink_to(SCENES)
    monkeypatch.chdir(tmp_path)
    subprocess.run([sys.executable, str(ROOT / "python/examples/illuminants.py")], check=True)
    assert (tmp_path / "cornell-python.png").exists()
