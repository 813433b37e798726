//! The resolved tree a Mitsuba scene file reads into: plugin objects ([`Object`]) with
//! typed properties ([`Value`]) and child objects, references already replaced by the
//! object they name (shared through an [`Arc`]).

use std::fmt;
use std::sync::Arc;
use std::sync::atomic::{AtomicBool, Ordering};

/// Where something is: the file (as the caller named it, or as an include joined it) and
/// its 1-based line.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Location {
    /// The file name.
    pub file: String,
    /// The line, counted from 1.
    pub line: u32,
}

impl fmt::Display for Location {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(f, "{}:{}", self.file, self.line)
    }
}

/// A plugin's class: the XML tag that made it.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Class {
    /// `<scene>`, the root.
    Scene,
    /// `<shape>`.
    Shape,
    /// `<bsdf>`.
    Bsdf,
    /// `<emitter>`.
    Emitter,
    /// `<sensor>`.
    Sensor,
    /// `<film>`.
    Film,
    /// `<sampler>`.
    Sampler,
    /// `<integrator>`.
    Integrator,
    /// `<texture>`.
    Texture,
    /// `<medium>`.
    Medium,
    /// `<phase>`.
    Phase,
    /// `<rfilter>`.
    Rfilter,
    /// `<volume>`.
    Volume,
    /// A `<spectrum type="...">` plugin object (blackbody, d65, irregular, regular...);
    /// a `<spectrum>` without `type` is a [`Value::Spectrum`] property.
    Spectrum,
    /// An `<rgb type="...">` plugin object; a plain `<rgb>` is a [`Value::Rgb`] property.
    Rgb,
}

impl Class {
    /// The class an object tag names, `None` for a tag that is not an object's.
    /// `spectrum` and `rgb` are objects only with a `type` attribute; the caller decides.
    pub fn from_tag(tag: &str) -> Option<Class> {
        Some(match tag {
            "scene" => Class::Scene,
            "shape" => Class::Shape,
            "bsdf" => Class::Bsdf,
            "emitter" => Class::Emitter,
            "sensor" => Class::Sensor,
            "film" => Class::Film,
            "sampler" => Class::Sampler,
            "integrator" => Class::Integrator,
            "texture" => Class::Texture,
            "medium" => Class::Medium,
            "phase" => Class::Phase,
            "rfilter" => Class::Rfilter,
            "volume" => Class::Volume,
            "spectrum" => Class::Spectrum,
            "rgb" => Class::Rgb,
            _ => return None,
        })
    }

    /// The XML tag of this class.
    pub fn tag(self) -> &'static str {
        match self {
            Class::Scene => "scene",
            Class::Shape => "shape",
            Class::Bsdf => "bsdf",
            Class::Emitter => "emitter",
            Class::Sensor => "sensor",
            Class::Film => "film",
            Class::Sampler => "sampler",
            Class::Integrator => "integrator",
            Class::Texture => "texture",
            Class::Medium => "medium",
            Class::Phase => "phase",
            Class::Rfilter => "rfilter",
            Class::Volume => "volume",
            Class::Spectrum => "spectrum",
            Class::Rgb => "rgb",
        }
    }
}

/// One plugin instance: `<bsdf type="diffuse" id="white">`.
#[derive(Debug, Clone)]
pub struct Object {
    /// The class (the tag).
    pub class: Class,
    /// The plugin: the `type` attribute ("scene" for the root).
    pub kind: String,
    /// The `id` attribute.
    pub id: Option<String>,
    /// The properties, in file order.
    pub properties: Vec<Property>,
    /// Nested objects and resolved references, in file order.
    pub children: Vec<Child>,
    /// Where the object's tag is.
    pub at: Location,
}

impl Object {
    /// The first property of that name, marked as read ([`Object::unread`]).
    pub fn property(&self, name: &str) -> Option<&Property> {
        let found = self.properties.iter().find(|p| p.name == name);
        if let Some(p) = found {
            p.read.0.store(true, Ordering::Relaxed);
        }
        found
    }

    /// The properties no reader has asked for by name ([`Object::property`]).
    pub fn unread(&self) -> impl Iterator<Item = &Property> {
        self.properties
            .iter()
            .filter(|p| !p.read.0.load(Ordering::Relaxed))
    }

    /// The first child of that name.
    pub fn child(&self, name: &str) -> Option<&Child> {
        self.children
            .iter()
            .find(|c| c.name.as_deref() == Some(name))
    }

    /// The children of a class, named or not, in file order.
    pub fn children_of(&self, class: Class) -> impl Iterator<Item = &Child> {
        self.children
            .iter()
            .filter(move |c| c.object.class == class)
    }
}

/// A named, typed value of an object: `<float name="radius" value="2"/>`.
#[derive(Debug, Clone)]
pub struct Property {
    /// The `name` attribute.
    pub name: String,
    /// The value.
    pub value: Value,
    /// Where the property's tag is.
    pub at: Location,
    /// Whether a reader has asked for it, so that what prism ignores can be said.
    pub read: Read,
}

/// Whether a property has been read: set through a shared reference, because the tree
/// is read through `Arc`s.
#[derive(Debug, Default)]
pub struct Read(AtomicBool);

impl Clone for Read {
    fn clone(&self) -> Self {
        Read(AtomicBool::new(self.0.load(Ordering::Relaxed)))
    }
}

/// A nested object or a resolved `<ref>`.
#[derive(Debug, Clone)]
pub struct Child {
    /// The `name` attribute (e.g. "reflectance", "interior"); a `<ref name=".." id="..">`
    /// keeps its name. `None` when the file gives none.
    pub name: Option<String>,
    /// The object, shared with every other reference to it.
    pub object: Arc<Object>,
}

/// A property's value.
#[derive(Debug, Clone, PartialEq)]
pub enum Value {
    /// `<float>`.
    Float(f64),
    /// `<integer>`.
    Integer(i64),
    /// `<boolean>`.
    Boolean(bool),
    /// `<string>`.
    String(String),
    /// `<point>`.
    Point([f64; 3]),
    /// `<vector>`.
    Vector([f64; 3]),
    /// `<rgb>` (one value means grey).
    Rgb([f64; 3]),
    /// `<spectrum>` without `type`.
    Spectrum(SpectrumValue),
    /// `<transform>`: row-major 4x4, the composition of its operations in document order,
    /// each one multiplying from the left (`M = op_n * ... * op_1`), as Mitsuba composes
    /// them. Points transform as `M * (x, y, z, 1)`.
    Transform([[f64; 4]; 4]),
}

/// The value of a `<spectrum>` property.
#[derive(Debug, Clone, PartialEq)]
pub enum SpectrumValue {
    /// `<spectrum name="x" value="0.5"/>`.
    Constant(f64),
    /// (wavelength in nm, value) pairs in increasing wavelength: `value="400:0.1, 500:0.2"`,
    /// or a `filename=` `.spd` file (lines "lambda value", `#` comments).
    Samples(Vec<(f64, f64)>),
}
