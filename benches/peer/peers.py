"""Which Mitsuba 3 script renders which comparison scene: the shared Cornell box and bunny box
(../shared/scenes/peer/mitsuba_peer.py), the scene kinds (specular, glossy, caustic, textured, plastic:
mitsuba_kinds.py) and the repository's volume scene (mitsuba_media.py). Both take VARIANT SCENE SPP [--depth D] [--width W] [--seed S] [--out F].
"""
import os

ROOT = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
SHARED = os.environ.get("PRISM_SHARED", os.path.join(os.path.dirname(ROOT), "shared"))

# prism's scene file for each comparison scene, under scenes/.
SCENES = {"box": "cornell-box.gltf", "bunny": "cornell-bunny.gltf", "specular": "cornell-specular.gltf",
          "glossy": "cornell-glossy.gltf", "caustic": "cornell-caustic.gltf", "media": "cornell-medium.gltf",
          "textured": "textured-sky.gltf", "plastic": "cornell-plastic.gltf"}
KINDS = ("specular", "glossy", "caustic", "textured", "plastic")


def script(scene, narrow=False):
    """The Mitsuba script that renders `scene` (narrow: as on a host without AVX-512)."""
    if narrow:
        if scene == "media" or scene in KINDS:
            raise SystemExit(f"--narrow-peers has no {scene} scene")
        return os.path.join(ROOT, "benches", "peer", "narrow_peer.py")
    if scene == "media":
        return os.path.join(ROOT, "benches", "peer", "mitsuba_media.py")
    if scene in KINDS:
        return os.path.join(ROOT, "benches", "peer", "mitsuba_kinds.py")
    return os.path.join(SHARED, "scenes", "peer", "mitsuba_peer.py")
