//! Shapes shared by the crate's unit tests.

use apart_formats::{Polygons, RawObject};

/// The six faces of a cuboid, counter-clockwise seen from outside, as corner indices:
/// corner `b` takes coordinate `k` from the high end when bit `k` of `b` is set.
pub(crate) const CUBOID_QUADS: [[u32; 4]; 6] = [
    [0, 2, 3, 1],
    [4, 5, 7, 6],
    [0, 1, 5, 4],
    [2, 6, 7, 3],
    [0, 4, 6, 2],
    [1, 3, 7, 5],
];

/// The eight corners of the cuboid `lo..hi`, numbered as [`CUBOID_QUADS`] expects.
pub(crate) fn cuboid_corners<T: Copy>(lo: [T; 3], hi: [T; 3]) -> Vec<[T; 3]> {
    (0..8)
        .map(|b| [0, 1, 2].map(|k| if b >> k & 1 == 1 { hi[k] } else { lo[k] }))
        .collect()
}

/// The cuboid `lo..hi` as a raw object of six outward quadrilaterals.
pub(crate) fn cuboid_raw(lo: [f64; 3], hi: [f64; 3]) -> RawObject {
    RawObject {
        name: None,
        vertices: cuboid_corners(lo, hi),
        faces: Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>()),
    }
}
