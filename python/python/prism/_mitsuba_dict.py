"""Mitsuba 3's dict form of a scene (what `mi.load_dict` takes) written as Mitsuba's XML,
which prism's Mitsuba loader reads: `prism.load_dict` is that loader behind this writer.

The dict form is Mitsuba's "Scene format: Python dictionary" (mitsuba.readthedocs.io,
key_topics/scene_format.html): each object a dict with a `type` (the plugin), its other
keys the plugin's parameters or nested objects; at the top level a key is the object's
id. Values are booleans, integers, floats, strings, three numbers (points and vectors),
`{"type": "rgb", "value": ...}`, `{"type": "spectrum", "value": ...}` (a number or
`[(nm, value), ...]`), `{"type": "ref", "id": ...}`, and transforms: anything with a
4 x 4 `.matrix` (Mitsuba's `ScalarTransform4f`), or a 4 x 4 nested list.
"""

from xml.sax.saxutils import quoteattr

# Each Mitsuba 3 plugin's object class (its XML tag), from the plugin reference.
_CLASSES = {
    "shape": "obj ply serialized rectangle cube sphere disk cylinder shapegroup instance "
             "bsplinecurve linearcurve sdfgrid ellipsoids ellipsoidsmesh",
    "bsdf": "diffuse dielectric thindielectric roughdielectric conductor roughconductor hair "
            "plastic roughplastic pplastic bumpmap normalmap blendbsdf mask twosided principled "
            "principledthin null polarizer retarder circular measured measured_polarized",
    "emitter": "area point constant envmap spot projector directional directionalarea sunsky",
    "sensor": "perspective thinlens orthographic radiancemeter irradiancemeter distant batch",
    "film": "hdrfilm specfilm",
    "rfilter": "box tent gaussian mitchell catmullrom lanczos",
    "sampler": "independent stratified multijitter orthogonal ldsampler",
    "integrator": "path volpath volpathmis direct ptracer moment aov depth prb prbvolpath "
                  "stokes",
    "texture": "bitmap checkerboard mesh_attribute volume",
    "medium": "homogeneous heterogeneous",
    "phase": "isotropic hg rayleigh blendphase sggx tabphase",
    "volume": "gridvolume constvolume",
    "spectrum": "blackbody d65 regular irregular srgb uniform",
}
CLASS_OF = {plugin: tag for tag, names in _CLASSES.items() for plugin in names.split()}


def _number(x):
    if isinstance(x, bool):
        raise TypeError("a boolean where a number is meant")
    return repr(float(x)) if isinstance(x, float) else str(x)


def _matrix(value):
    """A 4 x 4 matrix's 16 numbers, row by row, or None when `value` is not one."""
    matrix = getattr(value, "matrix", value)
    try:
        rows = [[float(matrix[i][j]) for j in range(4)] for i in range(4)]
    except (TypeError, IndexError, KeyError, ValueError):
        return None
    try:
        len(matrix[4])
        return None  # more than four rows
    except (TypeError, IndexError, KeyError):
        pass
    return [x for row in rows for x in row]


def _triple(value):
    try:
        items = list(value)
    except TypeError:
        return None
    if len(items) == 3 and all(isinstance(x, (int, float)) and not isinstance(x, bool)
                               for x in items):
        return items
    return None


class _Writer:
    def __init__(self):
        self.lines = []

    def put(self, depth, text):
        self.lines.append("    " * depth + text)

    def value(self, depth, name, value, where):
        attr = f"name={quoteattr(name)}"
        if isinstance(value, bool):
            self.put(depth, f'<boolean {attr} value="{str(value).lower()}"/>')
        elif isinstance(value, int):
            self.put(depth, f'<integer {attr} value="{value}"/>')
        elif isinstance(value, float):
            self.put(depth, f'<float {attr} value="{_number(value)}"/>')
        elif isinstance(value, str):
            self.put(depth, f"<string {attr} value={quoteattr(value)}/>")
        elif isinstance(value, dict):
            self.object(depth, value, f"{where}[{name!r}]", name=name)
        elif _matrix(value) is not None:
            numbers = " ".join(_number(x) for x in _matrix(value))
            self.put(depth, f"<transform {attr}><matrix value=\"{numbers}\"/></transform>")
        elif _triple(value) is not None:
            x, y, z = (_number(v) for v in _triple(value))
            self.put(depth, f'<point {attr} value="{x}, {y}, {z}"/>')
        else:
            raise ValueError(f"{where}[{name!r}]: {type(value).__name__} is not a value "
                             "Mitsuba's dict form has")

    def object(self, depth, d, where, name=None, id=None):
        kind = d.get("type")
        if not isinstance(kind, str):
            raise ValueError(f"{where}: an object needs a 'type' string")
        id = d.get("id", id)
        named = f" name={quoteattr(name)}" if name is not None else ""
        if kind == "ref":
            if "id" not in d:
                raise ValueError(f"{where}: a reference needs an 'id'")
            self.put(depth, f"<ref{named} id={quoteattr(str(d['id']))}/>")
            return
        if kind in ("rgb", "spectrum") and "value" in d:
            value = d["value"]
            if kind == "rgb":
                triple = _triple(value) if not isinstance(value, (int, float)) else None
                text = (", ".join(_number(v) for v in triple) if triple is not None
                        else _number(value))
            elif isinstance(value, (int, float)) and not isinstance(value, bool):
                text = _number(value)
            else:
                text = ", ".join(f"{_number(nm)}:{_number(v)}" for nm, v in value)
            self.put(depth, f"<{kind}{named} value=\"{text}\"/>")
            return
        if kind == "spectrum" and "filename" in d:
            self.put(depth, f"<spectrum{named} filename={quoteattr(str(d['filename']))}/>")
            return
        tag = CLASS_OF.get(kind)
        if tag is None:
            raise ValueError(f"{where}: '{kind}' is not a Mitsuba 3 plugin prism knows")
        attrs = f"type={quoteattr(kind)}" + (f" id={quoteattr(str(id))}" if id else "") + named
        self.put(depth, f"<{tag} {attrs}>")
        for key, value in d.items():
            if key in ("type", "id"):
                continue
            if not isinstance(key, str):
                raise ValueError(f"{where}: key {key!r} is not a string")
            self.value(depth + 1, key, value, where)
        self.put(depth, f"</{tag}>")


def to_xml(scene):
    """Mitsuba's XML for the dict form `scene` ({"type": "scene", ...})."""
    if not isinstance(scene, dict) or scene.get("type") != "scene":
        raise ValueError("load_dict takes a scene: a dict whose 'type' is 'scene'")
    writer = _Writer()
    writer.put(0, '<scene version="3.0.0">')
    for key, value in scene.items():
        if key == "type":
            continue
        if not isinstance(value, dict):
            raise ValueError(f"scene[{key!r}]: a scene holds objects (dicts with a 'type')")
        writer.object(1, value, f"scene[{key!r}]", id=key)
    writer.put(0, "</scene>")
    return "\n".join(writer.lines) + "\n"
