"""Which Mitsuba 3 script renders which comparison scene: the shared Cornell box and bunny box
(../shared/scenes/peer/mitsuba_peer.py), the scene kinds (specular, glossy, caustic, textured, plastic:
mitsuba_kinds.py), the repository's volume scene (mitsuba_media.py) and any Mitsuba scene file
(mitsuba_xml.py, the file as it stands). Both take VARIANT SCENE SPP [--depth D] [--width W] [--seed S] [--out F].
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.environ.get("PRISM_SHARED", os.path.join(os.path.dirname(ROOT), "shared"))

# prism's scene file for each comparison scene, under scenes/.
SCENES = {"box": "cornell-box.gltf", "bunny": "cornell-bunny.gltf", "specular": "cornell-specular.gltf",
          "glossy": "cornell-glossy.gltf", "caustic": "cornell-caustic.gltf", "media": "cornell-medium.gltf",
          "textured": "textured-sky.gltf", "plastic": "cornell-plastic.gltf"}
KINDS = ("specular", "glossy", "caustic", "textured", "plastic")


def is_xml(scene):
    """Whether `scene` is a Mitsuba scene file, which both renderers read as it stands."""
    return scene.lower().endswith(".xml")


def scene_path(scene):
    """prism's file for `scene`: a comparison scene's under scenes/, or the XML file itself."""
    return os.path.abspath(scene) if is_xml(scene) else os.path.join(ROOT, "scenes", SCENES[scene])


def scene_name(scene):
    """A name for file names: the comparison scene's, or the XML file's stem."""
    return os.path.splitext(os.path.basename(scene))[0] if is_xml(scene) else scene


def check_scene(scene):
    """argparse's type for a SCENE: a comparison scene's name or a Mitsuba .xml file."""
    if scene in SCENES or (is_xml(scene) and os.path.exists(scene)):
        return scene
    import argparse
    raise argparse.ArgumentTypeError(f"{scene!r}: one of {', '.join(SCENES)}, or a Mitsuba scene file (.xml)")


def script(scene, narrow=False):
    """The Mitsuba script that renders `scene` (narrow: as on a host without AVX-512)."""
    if is_xml(scene):
        if narrow:
            raise SystemExit("--narrow-peers has no XML scenes")
        return os.path.join(ROOT, "benches", "peer", "mitsuba_xml.py")
    if narrow:
        if scene == "media" or scene in KINDS:
            raise SystemExit(f"--narrow-peers has no {scene} scene")
        return os.path.join(ROOT, "benches", "peer", "narrow_peer.py")
    if scene == "media":
        return os.path.join(ROOT, "benches", "peer", "mitsuba_media.py")
    if scene in KINDS:
        return os.path.join(ROOT, "benches", "peer", "mitsuba_kinds.py")
    return os.path.join(SHARED, "scenes", "peer", "mitsuba_peer.py")
