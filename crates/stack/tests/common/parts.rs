//! The sheet-metal parts of `apart_testkit::sheet_metal` as placement models: the cube
//! as one convex piece (the hull of its corners), the others decomposed exactly (here, as
//! the loader does for the CLI: apart-stack itself never decomposes). Shared
//! by the stacking tests, the benchmark and the examples of apart-stack.
#![allow(dead_code)]

use apart_kernel::Vec3;
use apart_pieces::Polytope;
use apart_stack::part::PartModel;
use apart_testkit::sheet_metal::{self, SheetPart};

/// A placement model of a test part, its mesh kept.
pub fn model(part: SheetPart) -> PartModel {
    let points: Vec<Vec3> = part
        .mesh
        .points
        .iter()
        .map(|&p| Vec3::from_i64(p))
        .collect();
    let triangles = part.mesh.triangles;
    let pieces = if part.convex {
        vec![Polytope::hull_of_points(&points).expect("a convex solid")]
    } else {
        // Decomposed as the loader decomposes a non-convex part: placement never does.
        apart_decompose::decompose(&points, &triangles, &apart_decompose::Options::default())
            .expect("the part decomposes")
            .pieces
    };
    let mut model = PartModel::from_pieces(part.name, pieces).expect("pieces");
    model.mesh = Some((points, triangles));
    model
}

/// A unit-aligned cube `[0, size]³`.
pub fn cube(size: i64) -> PartModel {
    model(sheet_metal::cube(size))
}

/// The channel part with default dimensions.
pub fn channel() -> PartModel {
    model(sheet_metal::channel())
}

/// The triangle part with default dimensions.
pub fn triangle_part() -> PartModel {
    model(sheet_metal::triangle_part())
}

/// The complex part (plate, holes, flanges; 82 convex pieces).
pub fn complex_part() -> PartModel {
    model(sheet_metal::complex_part())
}
