//! Reading glTF accessors without trusting them: every byte range is checked with
//! overflow-free arithmetic before it is touched, so a hostile file yields an error, never a
//! panic, and the number of elements read is bounded by the bytes actually present.

use gltf::accessor::{DataType, Dimensions};
use gltf::Accessor;

/// Where an accessor's elements are: the bytes from its first element to the end of its
/// view, the stride between elements and their count.
struct Layout<'b> {
    bytes: &'b [u8],
    stride: usize,
    count: usize,
    component: DataType,
}

impl Layout<'_> {
    /// Component `j` of element `i` as f64 (normalized integers mapped to [0, 1]).
    fn component(&self, i: usize, j: usize, normalized: bool) -> Option<f64> {
        let size = component_size(self.component);
        let at = i.checked_mul(self.stride)?.checked_add(j * size)?;
        let b = self.bytes.get(at..at.checked_add(size)?)?;
        let v = match self.component {
            DataType::F32 => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::U8 if normalized => f64::from(b[0]) / 255.0,
            DataType::U16 if normalized => f64::from(u16::from_le_bytes([b[0], b[1]])) / 65535.0,
            DataType::U8 => f64::from(b[0]),
            DataType::U16 => f64::from(u16::from_le_bytes([b[0], b[1]])),
            DataType::U32 => f64::from(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            DataType::I8 | DataType::I16 => return None,
        };
        Some(v)
    }

    fn index(&self, i: usize) -> Option<u32> {
        let size = component_size(self.component);
        let at = i.checked_mul(self.stride)?;
        let b = self.bytes.get(at..at.checked_add(size)?)?;
        match self.component {
            DataType::U8 => Some(u32::from(b[0])),
            DataType::U16 => Some(u32::from(u16::from_le_bytes([b[0], b[1]]))),
            DataType::U32 => Some(u32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            _ => None,
        }
    }
}

fn component_size(t: DataType) -> usize {
    match t {
        DataType::I8 | DataType::U8 => 1,
        DataType::I16 | DataType::U16 => 2,
        DataType::U32 | DataType::F32 => 4,
    }
}

fn dims(d: Dimensions) -> usize {
    match d {
        Dimensions::Scalar => 1,
        Dimensions::Vec2 => 2,
        Dimensions::Vec3 => 3,
        Dimensions::Vec4 | Dimensions::Mat2 => 4,
        Dimensions::Mat3 => 9,
        Dimensions::Mat4 => 16,
    }
}

/// Checks the accessor's byte range against its buffer view and buffer.
fn layout<'b>(acc: &Accessor<'_>, buffers: &'b [Vec<u8>]) -> Result<Layout<'b>, String> {
    if acc.sparse().is_some() {
        return Err("sparse accessors are not supported; re-export without sparse storage".into());
    }
    let view = acc
        .view()
        .ok_or("accessor has no bufferView (all zeros); nothing to read")?;
    let data = buffers
        .get(view.buffer().index())
        .ok_or("bufferView refers to a missing buffer")?;
    let view_end = view
        .offset()
        .checked_add(view.length())
        .filter(|&end| end <= data.len())
        .ok_or("bufferView extends past the end of its buffer")?;
    let view_bytes = &data[view.offset()..view_end];
    let component = acc.data_type();
    let elem = component_size(component) * dims(acc.dimensions());
    let stride = view.stride().unwrap_or(elem);
    if stride < elem {
        return Err(format!(
            "byteStride {stride} is smaller than an element ({elem} bytes)"
        ));
    }
    let count = acc.count();
    let needed = match count {
        0 => Some(0),
        c => (c - 1)
            .checked_mul(stride)
            .and_then(|x| x.checked_add(elem))
            .and_then(|x| x.checked_add(acc.offset())),
    };
    let bytes = needed
        .filter(|&n| n <= view_bytes.len())
        .and_then(|_| view_bytes.get(acc.offset()..))
        .ok_or_else(|| format!("{count} elements do not fit in the bufferView"))?;
    Ok(Layout {
        bytes,
        stride,
        count,
        component,
    })
}

/// `N`-component float (or normalized unsigned integer, if `allow_normalized`) elements.
pub(crate) fn read_floats<const N: usize>(
    acc: &Accessor<'_>,
    buffers: &[Vec<u8>],
    allow_normalized: bool,
) -> Result<Vec<[f64; N]>, String> {
    if dims(acc.dimensions()) != N {
        return Err(format!(
            "expected {N} components, found {:?}",
            acc.dimensions()
        ));
    }
    let ok_type = match acc.data_type() {
        DataType::F32 => true,
        DataType::U8 | DataType::U16 => allow_normalized && acc.normalized(),
        _ => false,
    };
    if !ok_type {
        return Err(format!(
            "component type {:?}{} is not allowed here",
            acc.data_type(),
            if acc.normalized() {
                " (normalized)"
            } else {
                ""
            }
        ));
    }
    let l = layout(acc, buffers)?;
    let mut out = Vec::with_capacity(l.count);
    for i in 0..l.count {
        let mut e = [0.0; N];
        for (j, slot) in e.iter_mut().enumerate() {
            *slot = l
                .component(i, j, acc.normalized())
                .ok_or("element outside its bufferView")?;
        }
        out.push(e);
    }
    Ok(out)
}

/// Scalar unsigned integer indices.
pub(crate) fn read_indices(acc: &Accessor<'_>, buffers: &[Vec<u8>]) -> Result<Vec<u32>, String> {
    let ok = matches!(
        acc.data_type(),
        DataType::U8 | DataType::U16 | DataType::U32
    );
    if !ok || acc.dimensions() != Dimensions::Scalar {
        return Err(format!(
            "indices must be unsigned integer scalars, found {:?} {:?}",
            acc.data_type(),
            acc.dimensions()
        ));
    }
    let l = layout(acc, buffers)?;
    (0..l.count)
        .map(|i| {
            l.index(i)
                .ok_or_else(|| "index outside its bufferView".to_owned())
        })
        .collect()
}
