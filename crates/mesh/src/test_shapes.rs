//! Shapes shared by the crate's unit tests.

use apart_formats::{Polygons, RawObject};

pub(crate) use apart_testkit::solids::{cuboid_corners, CUBOID_QUADS};

/// The cuboid `lo..hi` as a raw object of six outward quadrilaterals.
pub(crate) fn cuboid_raw(lo: [f64; 3], hi: [f64; 3]) -> RawObject {
    RawObject {
        name: None,
        vertices: cuboid_corners(lo, hi),
        faces: Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>()),
    }
}
