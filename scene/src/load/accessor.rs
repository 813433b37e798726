//! Checks that an accessor can be read as the type a glTF attribute must have, before the
//! gltf crate's reader reads it.
//!
//! The reader trusts the document: an index accessor of floats reaches an `unreachable!`,
//! a zero count or a byte stride shorter than an element fails its debug assertions or
//! underflows, and byte ranges are summed unchecked. Validation (gltf-json 1.4) checks
//! none of these, so a malformed file would panic inside the reader. This module turns
//! each into an error naming the accessor.

use gltf::accessor::{DataType, Dimensions};

use super::LoadError;

/// What an attribute must be: the component types it may use and its element shape.
pub(super) struct Expected {
    pub(super) what: &'static str,
    pub(super) types: &'static [DataType],
    pub(super) dimensions: Dimensions,
}

pub(super) const POSITION: Expected = Expected {
    what: "POSITION",
    types: &[DataType::F32],
    dimensions: Dimensions::Vec3,
};
pub(super) const NORMAL: Expected = Expected {
    what: "NORMAL",
    types: &[DataType::F32],
    dimensions: Dimensions::Vec3,
};
pub(super) const TEXCOORD: Expected = Expected {
    what: "TEXCOORD_0",
    types: &[DataType::F32, DataType::U8, DataType::U16],
    dimensions: Dimensions::Vec2,
};
pub(super) const INDICES: Expected = Expected {
    what: "index",
    types: &[DataType::U8, DataType::U16, DataType::U32],
    dimensions: Dimensions::Scalar,
};

/// Whether `accessor` of primitive owner `name` is a readable `expected`: its component
/// type and shape, at least one element, a byte stride no shorter than an element, and
/// every byte range (the dense view's and a sparse substitution's indices and values)
/// inside its buffer view and that view inside its buffer (`buffers`, by index).
pub(super) fn check(
    accessor: &gltf::Accessor,
    expected: &Expected,
    name: &str,
    buffers: &[Vec<u8>],
) -> Result<(), LoadError> {
    let fail = |why: String| {
        Err(LoadError::Geometry(format!(
            "{name}: {} accessor {} {why}",
            expected.what,
            accessor.index()
        )))
    };
    let (data_type, dimensions) = (accessor.data_type(), accessor.dimensions());
    if !expected.types.contains(&data_type) || dimensions != expected.dimensions {
        let types: Vec<&str> = expected.types.iter().map(|&t| type_name(t)).collect();
        return fail(format!(
            "is {} {}, not {} {}",
            type_name(data_type),
            shape_name(dimensions),
            types.join(" or "),
            shape_name(expected.dimensions)
        ));
    }
    let element = accessor.size();
    if accessor.count() == 0 {
        return fail("has no elements".into());
    }
    if let Some(view) = accessor.view()
        && !fits(&view, accessor.offset(), accessor.count(), element, buffers)
    {
        return fail("cannot be read (it runs past its buffer view or buffer)".into());
    }
    if let Some(sparse) = accessor.sparse() {
        let count = sparse.count();
        let indices = sparse.indices();
        let index_size = match indices.index_type() {
            gltf::accessor::sparse::IndexType::U8 => 1,
            gltf::accessor::sparse::IndexType::U16 => 2,
            gltf::accessor::sparse::IndexType::U32 => 4,
        };
        let values = sparse.values();
        if count == 0
            || count > accessor.count()
            || !fits(
                &indices.view(),
                indices.offset(),
                count,
                index_size,
                buffers,
            )
            || !fits(&values.view(), values.offset(), count, element, buffers)
        {
            return fail("has a sparse substitution that cannot be read".into());
        }
    }
    Ok(())
}

/// Whether `count` elements of `size` bytes from `offset` (spaced by the view's stride, or
/// packed) lie inside `view`, and the view inside its buffer; all in checked arithmetic.
fn fits(
    view: &gltf::buffer::View,
    offset: usize,
    count: usize,
    size: usize,
    buffers: &[Vec<u8>],
) -> bool {
    let stride = view.stride().unwrap_or(size);
    let end = stride
        .checked_mul(count - 1)
        .and_then(|span| span.checked_add(offset))
        .and_then(|start| start.checked_add(size));
    let view_end = view.offset().checked_add(view.length());
    let buffer = buffers.get(view.buffer().index()).map_or(0, Vec::len);
    stride >= size
        && matches!((end, view_end), (Some(end), Some(view_end))
            if end <= view.length() && view_end <= buffer)
}

/// A component type as the glTF specification names it.
fn type_name(t: DataType) -> &'static str {
    match t {
        DataType::I8 => "BYTE",
        DataType::U8 => "UNSIGNED_BYTE",
        DataType::I16 => "SHORT",
        DataType::U16 => "UNSIGNED_SHORT",
        DataType::U32 => "UNSIGNED_INT",
        DataType::F32 => "FLOAT",
    }
}

/// An accessor type as the glTF specification names it.
fn shape_name(d: Dimensions) -> &'static str {
    match d {
        Dimensions::Scalar => "SCALAR",
        Dimensions::Vec2 => "VEC2",
        Dimensions::Vec3 => "VEC3",
        Dimensions::Vec4 => "VEC4",
        Dimensions::Mat2 => "MAT2",
        Dimensions::Mat3 => "MAT3",
        Dimensions::Mat4 => "MAT4",
    }
}
