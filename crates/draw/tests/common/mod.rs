//! Assemblies, plans and pixel checks shared by the picture tests: the assemblies of
//! `apart_testkit::assemblies` as parts and the sheet-metal parts of
//! `apart_testkit::sheet_metal` as placement models, shipped examples, and colour tests
//! on pixels.

#![allow(dead_code)]

use apart_assembly::{load, Assembly, LoadOptions, Part};
use apart_draw::colors::Rgb;
use apart_kernel::{Grid, Rational, Vec3};
use apart_pieces::Polytope;
use apart_plan::{parts_of, sequence, BlockingRegions, Sequence, SequenceOptions};
use apart_stack::orientation::Orientation;
use apart_stack::part::PartModel;
use apart_testkit::assemblies::{self, Piece};
use apart_testkit::sheet_metal::SheetPart;
use resvg::tiny_skia::Pixmap;
use std::path::PathBuf;

/// A shipped example assembly (loaded through the loader, with meshes).
pub fn example(name: &str) -> Assembly {
    let path = PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name);
    let loaded = load(&path, &LoadOptions::default()).unwrap();
    assert!(loaded.is_valid(), "{name}: {:?}", loaded.problems);
    loaded.assembly
}

/// An assembly of parts given only by convex pieces (no meshes), on the unit grid.
pub fn assembly_of(name: &str, parts: Vec<Part>) -> Assembly {
    Assembly {
        name: name.into(),
        grid: Grid::unit(30),
        max_snap_displacement: 0.0,
        parts,
        tolerance: None,
    }
}

/// An axis-aligned box [lo, hi].
pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
    Polytope::cuboid(lo, hi).unwrap()
}

/// A part given by convex pieces only.
pub fn part(name: &str, pieces: Vec<Polytope>) -> Part {
    Part::from_pieces(name, pieces)
}

/// The parts of an assembly of `apart_testkit::assemblies`.
pub fn parts(parts: Vec<assemblies::Part>) -> Vec<Part> {
    let piece = |p: &Piece| match p {
        Piece::Box(lo, hi) => cuboid(*lo, *hi),
        Piece::Hull(points) => {
            let v: Vec<Vec3> = points.iter().map(|&q| Vec3::from(q)).collect();
            Polytope::hull_of_points(&v).unwrap()
        }
    };
    parts
        .iter()
        .map(|p| part(&p.name, p.pieces.iter().map(piece).collect()))
        .collect()
}

/// A 20-part assembly: `assemblies::brick_rows`.
pub fn brick_rows() -> Vec<Part> {
    parts(assemblies::brick_rows())
}

/// A sheet-metal test part as a placement model, its mesh kept: the cube as one convex
/// piece (the hull of its corners), the others decomposed as the loader decomposes them.
pub fn sheet_model(part: SheetPart) -> PartModel {
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
        apart_decompose::decompose(&points, &triangles, &apart_decompose::Options::default())
            .expect("the part decomposes")
            .pieces
    };
    let mut model = PartModel::from_pieces(part.name, pieces).expect("pieces");
    model.mesh = Some((points, triangles));
    model
}

/// The integer `v` as a rational.
pub fn q(v: i64) -> Rational {
    Rational::from(v)
}

/// `n / d` as a rational.
pub fn qfrac(n: i64, d: i64) -> Rational {
    Rational::from_i128(n.into(), d.into())
}

/// A floor region `factor_num / factor_den` times the part's footprint in each
/// direction, centred on the footprint of the part as given.
pub fn floor_around(part: &PartModel, factor_num: i64, factor_den: i64) -> [Rational; 4] {
    let e = part.orient(&Orientation::IDENTITY).extent;
    let half = |i: usize| {
        let w = &e.max[i] - &e.min[i];
        let c = &(&e.max[i] + &e.min[i]) * &qfrac(1, 2);
        let r = &(&w * &qfrac(factor_num, factor_den)) * &qfrac(1, 2);
        (&c - &r, &c + &r)
    };
    let (x0, x1) = half(0);
    let (y0, y1) = half(1);
    [x0, y0, x1, y1]
}

/// The shared regions and the default plan of an assembly.
pub fn plan(assembly: &Assembly) -> (BlockingRegions, Sequence) {
    let regions = BlockingRegions::compute(parts_of(assembly).unwrap()).unwrap();
    let plan = sequence(&regions, &SequenceOptions::default());
    (regions, plan)
}

/// The bounding-box diagonal of an assembly in input units, from its meshes (or pieces).
pub fn diagonal(assembly: &Assembly) -> f64 {
    let mut lo = [f64::INFINITY; 3];
    let mut hi = [f64::NEG_INFINITY; 3];
    for part in &assembly.parts {
        let points: Vec<[f64; 3]> = match &part.mesh {
            Some(m) => m
                .vertices
                .iter()
                .map(|v| v.map(|q| assembly.grid.to_units(q)))
                .collect(),
            None => part
                .pieces
                .iter()
                .flat_map(|pc| {
                    let den = apart_kernel::int::to_f64(pc.den());
                    pc.vertices()
                        .iter()
                        .map(move |v| v.approx().map(|c| c / den))
                        .collect::<Vec<_>>()
                })
                .map(|p| p.map(|c| c * assembly.grid.step()))
                .collect(),
        };
        for p in points {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
    }
    ((0..3).map(|k| (hi[k] - lo[k]).powi(2)).sum::<f64>()).sqrt()
}

/// RGB of a pixel of a decoded (opaque) PNG.
pub fn pixel(p: &Pixmap, x: u32, y: u32) -> [u8; 3] {
    let c = p.pixel(x, y).unwrap();
    [c.red(), c.green(), c.blue()]
}

/// True when `c` is `base` shaded by a factor between 0.3 and 1 (flat shading keeps the
/// ratios of the channels), within rounding.
pub fn is_shade_of(c: [u8; 3], base: Rgb) -> bool {
    let b = [base.0 as f64, base.1 as f64, base.2 as f64];
    let p = c.map(|v| v as f64);
    let bb: f64 = b.iter().map(|v| v * v).sum();
    let s = (p[0] * b[0] + p[1] * b[1] + p[2] * b[2]) / bb;
    (0.3..=1.02).contains(&s) && (0..3).all(|k| (p[k] - s * b[k]).abs() <= 4.0)
}

/// How many pixels in columns `[0, max_x)` are shades of `base`.
pub fn count_shades(p: &Pixmap, base: Rgb, max_x: u32) -> usize {
    let mut n = 0;
    for y in 0..p.height() {
        for x in 0..max_x.min(p.width()) {
            if is_shade_of(pixel(p, x, y), base) {
                n += 1;
            }
        }
    }
    n
}

/// The part whose colour `c` is a shade of (flat shading scales the three channels by
/// one factor), `Some(None)` for the white background, and `None` for a colour of no
/// part (an outline, a blend at an edge). A channel may be off by 8 levels: where two
/// paths of one face meet, resvg's anti-aliasing lets up to 4 levels of what lies
/// behind show through.
pub fn part_of(c: [u8; 3], colors: &[Rgb]) -> Option<Option<usize>> {
    if c == [255, 255, 255] {
        return Some(None);
    }
    let p = c.map(|v| v as f64);
    colors
        .iter()
        .enumerate()
        .filter_map(|(k, base)| {
            let b = [base.0 as f64, base.1 as f64, base.2 as f64];
            let s = (p[0] * b[0] + p[1] * b[1] + p[2] * b[2])
                / (b[0] * b[0] + b[1] * b[1] + b[2] * b[2]);
            let err = (0..3).map(|i| (p[i] - s * b[i]).abs()).fold(0.0, f64::max);
            (err <= 8.0 && (0.3..=1.02).contains(&s)).then_some((err, k))
        })
        .min_by(|a, b| a.0.total_cmp(&b.0))
        .map(|(_, k)| Some(k))
}
