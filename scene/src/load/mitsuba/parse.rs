//! Reading the XML: one pass over the elements of the file (and of the files it
//! includes) that substitutes `$name` parameters, reads every property's value, composes
//! transforms and collects the objects into a flat list, references kept as ids. The ids
//! are resolved afterwards ([`super::resolve`]), so that a `<ref>` may name an object
//! defined anywhere in the scene, as in Mitsuba, which instantiates after parsing.

use std::collections::HashMap;

use roxmltree::{Document, Node, NodeType};

use super::paths;
use super::resolve::{Arena, RawChild, RawObject, Target};
use super::tree::{Class, Location, Property, Value};
use super::values;
use super::{ParseOptions, Parsed};
use crate::LoadError;

/// How deep `<include>`s may nest.
pub const MAX_INCLUDE_DEPTH: usize = 16;
/// How deep elements may nest, counted across included files (the parser recurses).
const MAX_ELEMENT_DEPTH: usize = 200;

/// The error of a parse at a place.
pub fn error(at: &Location, reason: impl Into<String>) -> LoadError {
    LoadError::Mitsuba {
        at: at.to_string(),
        reason: one_line(reason.into()),
    }
}

/// The message on one line: a line break becomes a space, and any other control
/// character the input put into it is written escaped (`\u{b}`), so that no terminal or
/// log reads it as a second line.
fn one_line(text: String) -> String {
    let breaks = |c: char| c.is_control() || c == '\u{2028}' || c == '\u{2029}';
    if !text.chars().any(breaks) {
        return text;
    }
    text.chars()
        .map(|c| match c {
            '\n' | '\r' | '\u{2028}' | '\u{2029}' => " ".to_string(),
            c if c.is_control() => c.escape_unicode().to_string(),
            c => c.to_string(),
        })
        .collect()
}

/// Parses a Mitsuba scene (see the module's documentation).
pub fn parse(text: &str, file: &str, options: &ParseOptions) -> Result<Parsed, LoadError> {
    let mut reader = Reader {
        resolve: options.resolve,
        params: options.defines.to_vec(),
        arena: Arena::default(),
        search: Vec::new(),
        includes: vec![file.to_string()],
        warnings: Vec::new(),
    };
    let doc = xml(text, file)?;
    let root = doc.root_element();
    let src = Source { file, doc: &doc };
    let at = src.at(root);
    let attrs = reader.attributes(&src, root)?;
    if root.tag_name().name() != "scene" {
        return Err(error(
            &at,
            format!(
                "the root element must be <scene>, not <{}>",
                root.tag_name().name()
            ),
        ));
    }
    attrs.check(&["version", "id"], "scene", &at)?;
    match attrs.get("version") {
        None => {
            return Err(error(
                &at,
                "missing version attribute in root element <scene>",
            ));
        }
        Some(v) => reader.version(v, &at)?,
    }
    let mut scene = RawObject::new(Class::Scene, "scene".into(), None, at);
    if let Some(id) = attrs.get("id") {
        reader.define_id(id, &scene.at)?;
        scene.id = Some(id.to_string());
    }
    for child in root.children() {
        reader.element(&src, child, Parent::Object(&mut scene), 1, true)?;
    }
    let scene = reader.arena.finish(scene)?;
    // Mitsuba's file resolver holds the scene file's directory behind the `<path>`s
    // (`load_file` prepends it first): files named in an included file are found there.
    let mut search = reader.search;
    search.push(paths::directory(file).to_string());
    Ok(Parsed {
        scene,
        warnings: reader.warnings,
        search,
    })
}

fn xml<'a>(text: &'a str, file: &str) -> Result<Document<'a>, LoadError> {
    Document::parse(text).map_err(|e| {
        let at = Location {
            file: file.to_string(),
            line: e.pos().row,
        };
        error(&at, format!("malformed XML: {e}"))
    })
}

/// One file being read.
struct Source<'a, 'input> {
    file: &'a str,
    doc: &'a Document<'input>,
}

impl Source<'_, '_> {
    fn at(&self, node: Node) -> Location {
        Location {
            file: self.file.to_string(),
            line: self.doc.text_pos_at(node.range().start).row,
        }
    }
}

/// Where an element's content goes.
enum Parent<'p> {
    Object(&'p mut RawObject),
    Transform(&'p mut values::Matrix),
}

/// An element's attributes after `$name` substitution.
struct Attributes(Vec<(String, String)>);

impl Attributes {
    fn get(&self, name: &str) -> Option<&str> {
        self.0
            .iter()
            .find(|(n, _)| n == name)
            .map(|(_, v)| v.as_str())
    }

    fn need(&self, name: &str, tag: &str, at: &Location) -> Result<&str, LoadError> {
        self.get(name).ok_or_else(|| {
            error(
                at,
                format!("missing attribute \"{name}\" in element <{tag}>"),
            )
        })
    }

    fn check(&self, allowed: &[&str], tag: &str, at: &Location) -> Result<(), LoadError> {
        match self.0.iter().find(|(n, _)| !allowed.contains(&n.as_str())) {
            Some((n, _)) => Err(error(
                at,
                format!("unexpected attribute \"{n}\" in element <{tag}>"),
            )),
            None => Ok(()),
        }
    }

    /// `value="x, y, z"` (or one number for all three) or `x`, `y`, `z` each defaulting
    /// to `default`.
    fn xyz(&self, default: f64, tag: &str, at: &Location) -> Result<[f64; 3], LoadError> {
        let parts = [self.get("x"), self.get("y"), self.get("z")];
        if let Some(value) = self.get("value") {
            if parts.iter().any(Option::is_some) {
                return Err(error(
                    at,
                    format!("<{tag}>: can't mix \"value\" and \"x\"/\"y\"/\"z\" attributes"),
                ));
            }
            return values::one_or_three(value).map_err(|e| error(at, format!("<{tag}>: {e}")));
        }
        let mut out = [default; 3];
        for (o, p) in out.iter_mut().zip(parts) {
            if let Some(p) = p {
                *o = values::float(p).map_err(|e| error(at, format!("<{tag}>: {e}")))?;
            }
        }
        Ok(out)
    }
}

struct Reader<'o> {
    resolve: &'o dyn Fn(&str) -> std::io::Result<Vec<u8>>,
    /// `-D` definitions first, then `<default>`s in the order met.
    params: Vec<(String, String)>,
    arena: Arena,
    /// `<path>` directories, the latest first.
    search: Vec<String>,
    /// The file being read and the files that include it, outermost first.
    includes: Vec<String>,
    warnings: Vec<String>,
}

impl Reader<'_> {
    fn warn(&mut self, at: &Location, text: impl std::fmt::Display) {
        self.warnings.push(format!("{at}: {text}"));
    }

    fn version(&mut self, text: &str, at: &Location) -> Result<(), LoadError> {
        let parts: Vec<&str> = text.split(['.', ' ']).filter(|p| !p.is_empty()).collect();
        let numbers: Option<Vec<u32>> = parts.iter().map(|p| p.parse().ok()).collect();
        match numbers.as_deref() {
            Some([major, _, _]) => {
                if *major < 2 {
                    self.warn(
                        at,
                        format!(
                            "scene version {text} is older than 2.0.0: parameter names \
                             (camelCase in 0.x) are read as written, not upgraded"
                        ),
                    );
                }
                Ok(())
            }
            _ => Err(error(
                at,
                format!("could not parse version number \"{text}\" (expected major.minor.patch)"),
            )),
        }
    }

    fn define_id(&mut self, id: &str, at: &Location) -> Result<(), LoadError> {
        if id.starts_with('_') {
            return Err(error(
                at,
                format!("invalid id \"{id}\": leading underscores are reserved"),
            ));
        }
        self.arena.declare(id, at).map_err(|previous| {
            error(
                at,
                format!("duplicate id \"{id}\" (previous was at {previous})"),
            )
        })
    }

    /// The attributes of an element, `$name` replaced.
    fn attributes(&self, src: &Source, node: Node) -> Result<Attributes, LoadError> {
        let mut out = Vec::new();
        for a in node.attributes() {
            let value = if a.value().contains('$') {
                self.substitute(a.value())
                    .map_err(|e| error(&src.at(node), e))?
            } else {
                a.value().to_string()
            };
            out.push((a.name().to_string(), value));
        }
        Ok(Attributes(out))
    }

    /// Replaces every `$name` by its parameter, the longest name that matches first.
    fn substitute(&self, text: &str) -> Result<String, String> {
        let mut out = String::with_capacity(text.len());
        let mut rest = text;
        while let Some(i) = rest.find('$') {
            out.push_str(&rest[..i]);
            let after = &rest[i + 1..];
            let best = self
                .params
                .iter()
                .filter(|(name, _)| !name.is_empty() && after.starts_with(name.as_str()))
                .max_by_key(|(name, _)| name.len());
            match best {
                Some((name, value)) => {
                    out.push_str(value);
                    rest = &after[name.len()..];
                }
                None => {
                    let name: String = after
                        .chars()
                        .take_while(|c| c.is_alphanumeric() || *c == '_')
                        .collect();
                    return Err(format!(
                        "undefined parameter \"${name}\" in \"{text}\" (no <default> and no definition)"
                    ));
                }
            }
        }
        out.push_str(rest);
        Ok(out)
    }

    /// Reads one node into its parent. `top`: the parent is the scene (for `<path>`).
    fn element(
        &mut self,
        src: &Source,
        node: Node,
        parent: Parent,
        depth: usize,
        top: bool,
    ) -> Result<(), LoadError> {
        match node.node_type() {
            NodeType::Comment | NodeType::PI => return Ok(()),
            NodeType::Text => {
                return match node.text() {
                    Some(t) if !t.trim().is_empty() => {
                        Err(error(&src.at(node), "unexpected text content"))
                    }
                    _ => Ok(()),
                };
            }
            NodeType::Root | NodeType::Element => {}
        }
        let at = src.at(node);
        if depth > MAX_ELEMENT_DEPTH {
            return Err(error(
                &at,
                format!("elements nested deeper than {MAX_ELEMENT_DEPTH}"),
            ));
        }
        let tag = node.tag_name().name();
        let attrs = self.attributes(src, node)?;
        let parent = match parent {
            Parent::Transform(matrix) => return self.transform_op(tag, &attrs, &at, matrix),
            Parent::Object(object) => object,
        };
        if matches!(tag, "translate" | "rotate" | "scale" | "matrix" | "lookat") {
            return Err(error(
                &at,
                format!("<{tag}> can only occur in a <transform>"),
            ));
        }
        if let Some(class) = Class::from_tag(tag)
            && (!matches!(class, Class::Spectrum | Class::Rgb) || attrs.get("type").is_some())
        {
            return self.object(src, node, class, attrs, at, parent, depth);
        }
        let property = |name: &str, value: Value| Property {
            name: name.to_string(),
            value,
            at: at.clone(),
            read: Default::default(),
        };
        let value_of = |what: &str, read: &dyn Fn(&str) -> Result<Value, String>| {
            attrs.check(&["name", "value"], tag, &at)?;
            let name = attrs.need("name", tag, &at)?;
            let value = attrs.need("value", tag, &at)?;
            let value = read(value).map_err(|e| error(&at, format!("<{what}> \"{name}\": {e}")))?;
            Ok::<_, LoadError>(property(name, value))
        };
        let new = match tag {
            "float" => value_of(tag, &|v| values::float(v).map(Value::Float))?,
            "integer" => value_of(tag, &|v| values::integer(v).map(Value::Integer))?,
            "boolean" => value_of(tag, &|v| values::boolean(v).map(Value::Boolean))?,
            "string" => value_of(tag, &|v| Ok(Value::String(v.to_string())))?,
            "rgb" => value_of(tag, &|v| values::one_or_three(v).map(Value::Rgb))?,
            "point" | "vector" => {
                attrs.check(&["name", "value", "x", "y", "z"], tag, &at)?;
                let name = attrs.need("name", tag, &at)?;
                let v = attrs.xyz(0.0, tag, &at)?;
                property(
                    name,
                    if tag == "point" {
                        Value::Point(v)
                    } else {
                        Value::Vector(v)
                    },
                )
            }
            "spectrum" => {
                attrs.check(&["name", "value", "filename"], tag, &at)?;
                let name = attrs.need("name", tag, &at)?;
                let spectrum = match (attrs.get("value"), attrs.get("filename")) {
                    (Some(v), None) => values::spectrum_text(v),
                    (None, Some(f)) => {
                        let bytes = self.read(f, &at, "spectrum file")?.1;
                        std::str::from_utf8(&bytes)
                            .map_err(|_| format!("spectrum file \"{f}\" is not UTF-8 text"))
                            .and_then(values::spd_file)
                    }
                    _ => Err("<spectrum> needs one of \"value\" or \"filename\"".to_string()),
                };
                let spectrum =
                    spectrum.map_err(|e| error(&at, format!("<spectrum> \"{name}\": {e}")))?;
                property(name, Value::Spectrum(spectrum))
            }
            "transform" => {
                attrs.check(&["name"], tag, &at)?;
                let name = attrs.need("name", tag, &at)?;
                let mut matrix = values::IDENTITY;
                for child in node.children() {
                    self.element(src, child, Parent::Transform(&mut matrix), depth + 1, false)?;
                }
                property(name, Value::Transform(matrix))
            }
            "ref" => {
                attrs.check(&["name", "id"], tag, &at)?;
                let id = attrs.need("id", tag, &at)?;
                parent.children.push(RawChild {
                    name: attrs.get("name").map(str::to_string),
                    target: Target::Id {
                        id: id.to_string(),
                        at,
                    },
                });
                return self.no_children(src, node);
            }
            "alias" => {
                attrs.check(&["id", "as"], tag, &at)?;
                let id = attrs.need("id", tag, &at)?;
                let alias = attrs.need("as", tag, &at)?;
                self.define_id(alias, &at)?;
                if !self.arena.alias(id, alias, at.clone()) {
                    return Err(error(
                        &at,
                        format!("<alias>: referenced id \"{id}\" not found"),
                    ));
                }
                return self.no_children(src, node);
            }
            "default" => {
                attrs.check(&["name", "value"], tag, &at)?;
                let name = attrs.need("name", tag, &at)?;
                let value = attrs.need("value", tag, &at)?;
                if name.is_empty() {
                    return Err(error(&at, "<default>: the name is empty"));
                }
                if !self.params.iter().any(|(n, _)| n == name) {
                    self.params.push((name.to_string(), value.to_string()));
                }
                return self.no_children(src, node);
            }
            "path" => {
                attrs.check(&["value"], tag, &at)?;
                let value = attrs.need("value", tag, &at)?;
                if !top {
                    return Err(error(&at, "<path> can only be a child of the root <scene>"));
                }
                let dir = paths::join(paths::directory(src.file), value);
                self.search.insert(0, dir);
                return self.no_children(src, node);
            }
            "include" => {
                attrs.check(&["filename"], tag, &at)?;
                let name = attrs.need("filename", tag, &at)?;
                return self.include(name, &at, parent, depth, top);
            }
            _ => return Err(error(&at, format!("unexpected tag <{tag}>"))),
        };
        if new.name.starts_with('_') {
            return Err(error(
                &at,
                format!(
                    "invalid name \"{}\": leading underscores are reserved",
                    new.name
                ),
            ));
        }
        if parent.properties.iter().any(|p| p.name == new.name) {
            self.warn(
                &at,
                format!("property \"{}\" given twice; both are kept", new.name),
            );
        }
        parent.properties.push(new);
        if tag != "transform" {
            self.no_children(src, node)?;
        }
        Ok(())
    }

    /// Properties have no element children (comments and whitespace are fine).
    fn no_children(&self, src: &Source, node: Node) -> Result<(), LoadError> {
        for child in node.children() {
            match child.node_type() {
                NodeType::Element => {
                    return Err(error(
                        &src.at(child),
                        format!(
                            "<{}> cannot occur as a child of <{}>",
                            child.tag_name().name(),
                            node.tag_name().name()
                        ),
                    ));
                }
                NodeType::Text if child.text().is_some_and(|t| !t.trim().is_empty()) => {
                    return Err(error(&src.at(child), "unexpected text content"));
                }
                _ => {}
            }
        }
        Ok(())
    }

    #[allow(clippy::too_many_arguments)]
    fn object(
        &mut self,
        src: &Source,
        node: Node,
        class: Class,
        attrs: Attributes,
        at: Location,
        parent: &mut RawObject,
        depth: usize,
    ) -> Result<(), LoadError> {
        let tag = class.tag();
        if class == Class::Scene {
            return Err(error(&at, "<scene> can only be the root element"));
        }
        attrs.check(&["type", "id", "name"], tag, &at)?;
        let kind = attrs.need("type", tag, &at)?.to_string();
        let name = attrs.get("name").map(str::to_string);
        if let Some(name) = &name
            && name.starts_with('_')
        {
            return Err(error(
                &at,
                format!("invalid name \"{name}\": leading underscores are reserved"),
            ));
        }
        let id = attrs.get("id").map(str::to_string);
        if let Some(id) = &id {
            self.define_id(id, &at)?;
        }
        let mut object = RawObject::new(class, kind, id, at);
        for child in node.children() {
            self.element(src, child, Parent::Object(&mut object), depth + 1, false)?;
        }
        let index = self.arena.push(object);
        parent.children.push(RawChild {
            name,
            target: Target::Index(index),
        });
        Ok(())
    }

    fn transform_op(
        &mut self,
        tag: &str,
        attrs: &Attributes,
        at: &Location,
        matrix: &mut values::Matrix,
    ) -> Result<(), LoadError> {
        let op = match tag {
            "translate" => {
                attrs.check(&["value", "x", "y", "z"], tag, at)?;
                values::translate(attrs.xyz(0.0, tag, at)?)
            }
            "scale" => {
                attrs.check(&["value", "x", "y", "z"], tag, at)?;
                values::scale(attrs.xyz(1.0, tag, at)?)
            }
            "rotate" => {
                attrs.check(&["value", "x", "y", "z", "angle"], tag, at)?;
                let angle = attrs.need("angle", tag, at)?;
                let angle =
                    values::float(angle).map_err(|e| error(at, format!("<rotate>: {e}")))?;
                let axis = attrs.xyz(0.0, tag, at)?;
                values::rotate(axis, angle).map_err(|e| error(at, format!("<rotate>: {e}")))?
            }
            "matrix" => {
                attrs.check(&["value"], tag, at)?;
                let text = attrs.need("value", tag, at)?;
                let numbers = values::tokens(text);
                let read =
                    |t: &str| values::float(t).map_err(|e| error(at, format!("<matrix>: {e}")));
                let mut m = values::IDENTITY;
                match numbers.len() {
                    16 => {
                        for (k, t) in numbers.iter().enumerate() {
                            m[k / 4][k % 4] = read(t)?;
                        }
                    }
                    9 => {
                        for (k, t) in numbers.iter().enumerate() {
                            m[k / 3][k % 3] = read(t)?;
                        }
                    }
                    n => {
                        return Err(error(
                            at,
                            format!("<matrix>: expected 16 or 9 values, got {n}"),
                        ));
                    }
                }
                m
            }
            "lookat" => {
                attrs.check(&["origin", "target", "up"], tag, at)?;
                let triple = |name: &str| {
                    let text = attrs.need(name, tag, at)?;
                    values::floats::<3>(text)
                        .map_err(|e| error(at, format!("<lookat> \"{name}\": {e}")))
                };
                let origin = triple("origin")?;
                let target = triple("target")?;
                let up = match attrs.get("up") {
                    Some(_) => triple("up")?,
                    None => [0.0; 3],
                };
                values::look_at(origin, target, up).map_err(|e| error(at, e))?
            }
            _ => {
                return Err(error(
                    at,
                    format!("a <transform> can only contain transform operations, not <{tag}>"),
                ));
            }
        };
        *matrix = values::multiply(&op, matrix);
        Ok(())
    }

    /// Reads a file a scene names: tried in each `<path>` directory (the latest first),
    /// then next to the file being read, then next to the scene file.
    fn read(&self, name: &str, at: &Location, what: &str) -> Result<(String, Vec<u8>), LoadError> {
        let mut candidates: Vec<String> = Vec::new();
        if paths::is_absolute(name) {
            candidates.push(paths::join("", name));
        } else {
            for dir in &self.search {
                candidates.push(paths::join(dir, name));
            }
            for file in [self.includes.last(), self.includes.first()]
                .into_iter()
                .flatten()
            {
                candidates.push(paths::join(paths::directory(file), name));
            }
        }
        let mut seen = HashMap::new();
        candidates.retain(|c| seen.insert(c.clone(), ()).is_none());
        let mut last = None;
        for candidate in candidates {
            match (self.resolve)(&candidate) {
                Ok(bytes) => return Ok((candidate, bytes)),
                Err(e) => last = Some((candidate, e)),
            }
        }
        Err(match last {
            Some((candidate, e)) => error(at, format!("cannot read {what} \"{candidate}\": {e}")),
            None => error(at, format!("cannot read {what} \"{name}\"")),
        })
    }

    /// `<include>`: the included file's `<scene>` children join the parent in place; a
    /// file whose root is one object adds that object.
    fn include(
        &mut self,
        name: &str,
        at: &Location,
        parent: &mut RawObject,
        depth: usize,
        top: bool,
    ) -> Result<(), LoadError> {
        let (file, bytes) = self.read(name, at, "included file")?;
        if self.includes.contains(&file) {
            let chain: Vec<&str> = self
                .includes
                .iter()
                .map(String::as_str)
                .chain([file.as_str()])
                .collect();
            return Err(error(at, format!("include cycle: {}", chain.join(" -> "))));
        }
        if self.includes.len() > MAX_INCLUDE_DEPTH {
            return Err(error(
                at,
                format!("includes nested deeper than {MAX_INCLUDE_DEPTH}"),
            ));
        }
        let text = std::str::from_utf8(&bytes)
            .map_err(|_| error(at, format!("included file \"{file}\" is not UTF-8 text")))?;
        let doc = xml(text, &file)?;
        let src = Source {
            file: &file,
            doc: &doc,
        };
        self.includes.push(file.clone());
        let root = doc.root_element();
        let result = if root.tag_name().name() == "scene" {
            let root_at = src.at(root);
            let attrs = self.attributes(&src, root)?;
            attrs.check(&["version"], "scene", &root_at)?;
            if let Some(v) = attrs.get("version") {
                self.version(v, &root_at)?;
            }
            root.children()
                .try_for_each(|child| self.element(&src, child, Parent::Object(parent), depth, top))
        } else {
            self.element(&src, root, Parent::Object(parent), depth, false)
        };
        self.includes.pop();
        result
    }
}
