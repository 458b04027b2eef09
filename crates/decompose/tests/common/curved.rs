//! Tessellated curved parts of `apart_testkit::curved`, snapped to an integer grid as the
//! assembly loader does (one grid of 30 bits for all parts of an assembly).
#![allow(dead_code)]

use apart_kernel::{Grid, Vec3};
use apart_testkit::curved::NamedSoup;

/// A part snapped to integers: name, points, triangles.
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

/// The part called `name`.
pub fn part(parts: &[NamedSoup], name: &str) -> Snapped {
    snap(parts)
        .into_iter()
        .find(|p| p.name == name)
        .expect("a part of that name")
}
