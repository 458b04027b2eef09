//! Accessors read from the buffers, every declared count, offset and stride checked
//! against the data before anything is allocated for it.

use super::malformed;
use crate::ReadError;
use gltf::accessor::{DataType, Dimensions};

/// The glTF name of an accessor type, such as `VEC3`.
fn type_name(d: Dimensions) -> &'static str {
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

/// A component type's code and name, such as `5126 (FLOAT)`.
fn component_name(t: DataType) -> String {
    let (code, name) = match t {
        DataType::I8 => (5120, "BYTE"),
        DataType::U8 => (5121, "UNSIGNED_BYTE"),
        DataType::I16 => (5122, "SHORT"),
        DataType::U16 => (5123, "UNSIGNED_SHORT"),
        DataType::U32 => (5125, "UNSIGNED_INT"),
        DataType::F32 => (5126, "FLOAT"),
    };
    format!("{code} ({name})")
}

/// Reads accessors, checking every declared size against the data.
pub(super) struct Data<'a> {
    pub(super) buffers: &'a [Vec<u8>],
    /// Bytes of the file and its buffers: what an accessor without data may declare.
    pub(super) budget: u128,
}

impl Data<'_> {
    /// The bytes of `count` elements of `size` bytes at `stride` from `offset` in
    /// buffer view `view`, checked to lie in the view and the view in its buffer.
    fn view_bytes(
        &self,
        what: &str,
        view: &gltf::buffer::View,
        offset: usize,
        count: usize,
        size: usize,
        stride: usize,
    ) -> Result<&[u8], ReadError> {
        let b = view.buffer().index();
        let buffer = self
            .buffers
            .get(b)
            .ok_or_else(|| malformed(format!("{what}: buffer {b} does not exist")))?;
        let (start, len) = (view.offset() as u128, view.length() as u128);
        if start + len > buffer.len() as u128 {
            return Err(malformed(format!(
                "{what}: buffer view {} (bytes {start} to {}) lies beyond the end of buffer {b} ({} bytes)",
                view.index(),
                start + len,
                buffer.len()
            )));
        }
        let data = &buffer[start as usize..(start + len) as usize];
        if count == 0 {
            return Ok(&[]);
        }
        let need = offset as u128 + stride as u128 * (count as u128 - 1) + size as u128;
        if need > len {
            return Err(malformed(format!(
                "{what}: {count} elements of {size} bytes at a stride of {stride} from byte {offset} need {need} bytes, but buffer view {} holds {len}",
                view.index()
            )));
        }
        Ok(&data[offset..need as usize])
    }

    /// Every element of `acc` (`size` bytes each) decoded, sparse substitutions
    /// applied; elements without data are all zero bytes. Every size is checked before
    /// anything is allocated for the elements.
    fn elements<T: Copy>(
        &self,
        what: &str,
        acc: &gltf::Accessor,
        size: usize,
        decode: impl Fn(&[u8]) -> T,
    ) -> Result<Vec<T>, ReadError> {
        let count = acc.count();
        // The dense data (bytes and stride), or `None` for zeros.
        let dense = match acc.view() {
            Some(view) => {
                let stride = view.stride().unwrap_or(size);
                if stride < size {
                    return Err(malformed(format!(
                        "{what}: buffer view {} has a byteStride of {stride}, less than an element ({size} bytes)",
                        view.index()
                    )));
                }
                Some((
                    self.view_bytes(what, &view, acc.offset(), count, size, stride)?,
                    stride,
                ))
            }
            None => {
                if count as u128 * size as u128 > self.budget {
                    return Err(malformed(format!(
                        "{what}: {count} elements without a buffer view, more than the {} bytes of the file and its buffers could describe",
                        self.budget
                    )));
                }
                None
            }
        };
        let sparse = match acc.sparse() {
            None => None,
            Some(sparse) => {
                let n = sparse.count();
                if n > count {
                    return Err(malformed(format!(
                        "{what}: {n} sparse substitutions for {count} elements"
                    )));
                }
                let indices = sparse.indices();
                let isize = indices.index_type().size();
                let ibytes = self.view_bytes(
                    &format!("{what}, sparse indices"),
                    &indices.view(),
                    indices.offset(),
                    n,
                    isize,
                    isize,
                )?;
                let values = sparse.values();
                let vbytes = self.view_bytes(
                    &format!("{what}, sparse values"),
                    &values.view(),
                    values.offset(),
                    n,
                    size,
                    size,
                )?;
                Some((n, isize, ibytes, vbytes))
            }
        };
        let mut out = match dense {
            Some((bytes, stride)) => (0..count)
                .map(|k| decode(&bytes[k * stride..k * stride + size]))
                .collect(),
            None => vec![decode(&vec![0u8; size]); count],
        };
        if let Some((n, isize, ibytes, vbytes)) = sparse {
            for j in 0..n {
                let b = &ibytes[j * isize..(j + 1) * isize];
                let k = match isize {
                    1 => b[0] as usize,
                    2 => u16::from_le_bytes([b[0], b[1]]) as usize,
                    _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]) as usize,
                };
                if k >= count {
                    return Err(malformed(format!(
                        "{what}: sparse index {k} is not below the count {count}"
                    )));
                }
                out[k] = decode(&vbytes[j * size..(j + 1) * size]);
            }
        }
        Ok(out)
    }

    /// The `FLOAT` `VEC3` positions of `acc`; other types are refused.
    pub(super) fn positions(
        &self,
        what: &str,
        acc: &gltf::Accessor,
    ) -> Result<Vec<[f64; 3]>, ReadError> {
        if acc.data_type() != DataType::F32 || acc.dimensions() != Dimensions::Vec3 {
            return Err(malformed(format!(
                "{what}: POSITION accessor {} has componentType {} and type {}; positions must be 5126 (FLOAT) VEC3 (quantized positions are not read)",
                acc.index(),
                component_name(acc.data_type()),
                type_name(acc.dimensions())
            )));
        }
        self.elements(what, acc, 12, |b| {
            let f = |o: usize| f32::from_le_bytes([b[o], b[o + 1], b[o + 2], b[o + 3]]) as f64;
            [f(0), f(4), f(8)]
        })
    }

    /// The unsigned integer indices of `acc`; other types are refused.
    pub(super) fn indices(&self, what: &str, acc: &gltf::Accessor) -> Result<Vec<u32>, ReadError> {
        let size = match acc.data_type() {
            DataType::U8 => 1,
            DataType::U16 => 2,
            DataType::U32 => 4,
            _ => 0,
        };
        if size == 0 || acc.dimensions() != Dimensions::Scalar {
            return Err(malformed(format!(
                "{what}: index accessor {} has componentType {} and type {}; indices must be 5121 (UNSIGNED_BYTE), 5123 (UNSIGNED_SHORT) or 5125 (UNSIGNED_INT) SCALAR",
                acc.index(),
                component_name(acc.data_type()),
                type_name(acc.dimensions())
            )));
        }
        self.elements(what, acc, size, |b| match size {
            1 => b[0] as u32,
            2 => u16::from_le_bytes([b[0], b[1]]) as u32,
            _ => u32::from_le_bytes([b[0], b[1], b[2], b[3]]),
        })
    }
}
