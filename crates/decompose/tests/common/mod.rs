//! apart's exact types for the test inputs of `apart_testkit`: the solids of
//! `apart_testkit::shapes` with their volume as a rational, the curved parts of
//! `apart_testkit::curved` snapped to an integer grid as the assembly loader does; and
//! the check of a shape's sample points against the pieces of its decomposition.
#![allow(dead_code)]

use apart_kernel::{Grid, Int, Rational, Vec3};
use apart_pieces::{Containment, Polytope};
use apart_testkit::curved::NamedSoup;
use apart_testkit::shapes;

/// A shape of `apart_testkit::shapes` in exact types.
pub struct Exact {
    pub name: &'static str,
    pub points: Vec<Vec3>,
    pub tris: Vec<[u32; 3]>,
    /// The volume, from a formula independent of the decomposition code.
    pub volume: Rational,
    /// Reflex edges counted by hand, when known.
    pub reflex: Option<usize>,
    /// Sample points `x / w`: `true` strictly inside, `false` strictly outside.
    pub samples: Vec<shapes::Sample>,
}

/// `shape` with its points as `Vec3` and its volume as a rational.
pub fn exact(shape: &shapes::Shape) -> Exact {
    Exact {
        name: shape.name,
        points: shape.points.iter().map(|&p| Vec3::from_i64(p)).collect(),
        tris: shape.tris.clone(),
        volume: Rational::from_i128(shape.volume[0], shape.volume[1]),
        reflex: shape.reflex,
        samples: shape.samples.clone(),
    }
}

/// Where the point `x / w` lies in a polytope, exactly.
pub fn locate(p: &Polytope, x: &[i128; 3], w: i128) -> Containment {
    let stored = Vec3::from_i128(*x).scale(p.den());
    let w = Int::from(w);
    let mut on = false;
    for f in p.facets() {
        let v = f.normal.dot(&stored) - &f.offset * &w;
        if v > Int::ZERO {
            return Containment::Outside;
        }
        if v == Int::ZERO {
            on = true;
        }
    }
    if on {
        Containment::Boundary
    } else {
        Containment::Inside
    }
}

/// Checks the sample points against the pieces: a point strictly inside the solid is in
/// some closed piece and in at most one open piece; a point outside is in no piece.
pub fn check_samples(shape: &Exact, pieces: &[Polytope]) {
    for (x, w, inside) in &shape.samples {
        let loc: Vec<Containment> = pieces.iter().map(|p| locate(p, x, *w)).collect();
        let interior = loc.iter().filter(|c| **c == Containment::Inside).count();
        let closed = loc.iter().filter(|c| **c != Containment::Outside).count();
        if *inside {
            assert!(
                closed >= 1 && interior <= 1,
                "{}: inside point {x:?}/{w} in {closed} closed, {interior} open pieces",
                shape.name
            );
        } else {
            assert_eq!(
                closed, 0,
                "{}: outside point {x:?}/{w} is in a piece",
                shape.name
            );
        }
    }
}

/// A curved part snapped to integers: name, points, triangles.
pub struct Snapped {
    pub name: String,
    pub points: Vec<Vec3>,
    pub tris: Vec<[u32; 3]>,
}

/// Snaps every part on the one grid of 30 bits chosen for all of them (fans of polygons
/// into triangles; the generators emit triangles only).
pub fn snap(parts: &[NamedSoup]) -> Vec<Snapped> {
    let grid = Grid::choose(
        parts
            .iter()
            .flat_map(|(_, s)| s.vertices.iter().flatten().copied()),
        30,
    )
    .expect("finite coordinates");
    parts
        .iter()
        .map(|(name, s)| Snapped {
            name: name.clone(),
            points: s
                .vertices
                .iter()
                .map(|v| Vec3::new(grid.snap(v[0]), grid.snap(v[1]), grid.snap(v[2])))
                .collect(),
            tris: s
                .faces
                .iter()
                .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
                .collect(),
        })
        .collect()
}

/// The part called `name`, snapped with all of `parts`.
pub fn part(parts: &[NamedSoup], name: &str) -> Snapped {
    snap(parts)
        .into_iter()
        .find(|p| p.name == name)
        .expect("a part of that name")
}
