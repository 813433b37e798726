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
    pub(super) dimensions: &'static [Dimensions],
}

/// Floats, or the integers `KHR_mesh_quantization` allows.
pub(super) const POSITION: Expected = Expected {
    what: "POSITION",
    types: QUANTIZED,
    dimensions: &[Dimensions::Vec3],
};
pub(super) const NORMAL: Expected = Expected {
    what: "NORMAL",
    types: &[DataType::F32, DataType::I8, DataType::I16],
    dimensions: &[Dimensions::Vec3],
};
pub(super) const TANGENT: Expected = Expected {
    what: "TANGENT",
    types: &[DataType::F32, DataType::I8, DataType::I16],
    dimensions: &[Dimensions::Vec4],
};
pub(super) const TEXCOORD: Expected = Expected {
    what: "TEXCOORD",
    types: QUANTIZED,
    dimensions: &[Dimensions::Vec2],
};
pub(super) const COLOR: Expected = Expected {
    what: "COLOR_0",
    types: &[DataType::F32, DataType::U8, DataType::U16],
    dimensions: &[Dimensions::Vec3, Dimensions::Vec4],
};
pub(super) const MORPH_TARGET: Expected = Expected {
    what: "morph target",
    types: QUANTIZED,
    dimensions: &[Dimensions::Vec3],
};
pub(super) const INDICES: Expected = Expected {
    what: "index",
    types: &[DataType::U8, DataType::U16, DataType::U32],
    dimensions: &[Dimensions::Scalar],
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
    if !expected.types.contains(&data_type) || !expected.dimensions.contains(&dimensions) {
        let types: Vec<&str> = expected.types.iter().map(|&t| type_name(t)).collect();
        let shapes: Vec<&str> = expected.dimensions.iter().map(|&d| shape_name(d)).collect();
        return fail(format!(
            "is {} {}, not {} {}",
            type_name(data_type),
            shape_name(dimensions),
            types.join(" or "),
            shapes.join(" or ")
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

/// The component types an attribute read by [`read_f32`] may use, by what
/// `KHR_mesh_quantization` allows: positions any type, directions signed normalized,
/// texture coordinates and colours any but UNSIGNED_INT.
pub(super) const QUANTIZED: &[DataType] = &[
    DataType::F32,
    DataType::I8,
    DataType::U8,
    DataType::I16,
    DataType::U16,
];

/// The values of a float-valued attribute of `N` components whatever its component type
/// (a checked accessor: see [`check`]): floats as they are; normalized integers as glTF
/// 2.0 §3.11 maps them (unsigned c / (2^b - 1), signed max(c / (2^(b-1) - 1), -1));
/// unnormalized integers as their values (`KHR_mesh_quantization`'s positions and
/// texture coordinates, which the node or texture transform then scales). None when the
/// data cannot be read.
pub(super) fn read_f32<const N: usize>(
    accessor: &gltf::Accessor,
    buffers: &[Vec<u8>],
) -> Option<Vec<[f32; N]>>
where
    [f32; N]: gltf::accessor::Item,
    [i8; N]: gltf::accessor::Item,
    [u8; N]: gltf::accessor::Item,
    [i16; N]: gltf::accessor::Item,
    [u16; N]: gltf::accessor::Item,
    [u32; N]: gltf::accessor::Item,
{
    fn read<T: gltf::accessor::Item + Copy, const N: usize>(
        accessor: &gltf::Accessor,
        buffers: &[Vec<u8>],
        convert: impl Fn(T) -> f32,
    ) -> Option<Vec<[f32; N]>>
    where
        [T; N]: gltf::accessor::Item,
    {
        let get = |b: gltf::Buffer| buffers.get(b.index()).map(Vec::as_slice);
        let iter = gltf::accessor::Iter::<[T; N]>::new(accessor.clone(), get)?;
        Some(iter.map(|v| v.map(&convert)).collect())
    }
    let normalized = accessor.normalized();
    let scale = |max: f32| if normalized { 1.0 / max } else { 1.0 };
    // The most negative signed value normalizes to just below -1.
    let floor = if normalized { -1.0 } else { f32::MIN };
    match accessor.data_type() {
        DataType::F32 => read::<f32, N>(accessor, buffers, |v| v),
        DataType::U8 => {
            let s = scale(255.0);
            read::<u8, N>(accessor, buffers, |v| f32::from(v) * s)
        }
        DataType::U16 => {
            let s = scale(65535.0);
            read::<u16, N>(accessor, buffers, |v| f32::from(v) * s)
        }
        DataType::I8 => {
            let s = scale(127.0);
            read::<i8, N>(accessor, buffers, |v| (f32::from(v) * s).max(floor))
        }
        DataType::I16 => {
            let s = scale(32767.0);
            read::<i16, N>(accessor, buffers, |v| (f32::from(v) * s).max(floor))
        }
        DataType::U32 => {
            let s = scale(u32::MAX as f32);
            read::<u32, N>(accessor, buffers, |v| v as f32 * s)
        }
    }
}
