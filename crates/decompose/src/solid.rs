//! The input solid, checked and indexed: triangle planes, undirected edges with the
//! pairing of their triangles, reflex and non-manifold marks.

use crate::reflex::pair_around_edge;
use crate::DecomposeError;
use crate::MAX_COORD_BITS;
use apart_kernel::plane::Plane;
use apart_kernel::{Aabb, Int, Sign, Vec3};

/// An undirected edge of the mesh.
#[derive(Clone, Debug)]
pub(crate) struct EdgeInfo {
    /// End points, smaller index first.
    pub ends: [u32; 2],
    /// Some pair of triangles around the edge meets at a reflex dihedral angle.
    pub reflex: bool,
    /// More than two triangles use the edge.
    pub non_manifold: bool,
    /// The triangles using the edge.
    pub tris: Vec<u32>,
}

/// A closed, consistently oriented triangle mesh with integer coordinates.
pub(crate) struct Solid {
    pub pts: Vec<[i64; 3]>,
    pub tris: Vec<[u32; 3]>,
    /// Outward plane of each triangle.
    pub planes: Vec<Plane>,
    /// Edge id of side `k` (corner `k` to corner `k + 1`) of each triangle.
    pub tri_edge: Vec<[u32; 3]>,
    /// The triangle paired with each triangle across its side `k`.
    pub partner: Vec<[u32; 3]>,
    pub edges: Vec<EdgeInfo>,
    /// Vertices around which the surface is not one cone (several cycles of triangles).
    pub nm_vertex: Vec<bool>,
    /// Triangles around each non-manifold vertex.
    pub nm_vertex_tris: rustc_hash::FxHashMap<u32, Vec<u32>>,
    /// Six times the enclosed volume.
    pub volume6: Int,
    /// Bounding box of the used points.
    pub bbox: Aabb,
}

impl Solid {
    /// Checks and indexes the input. Errors name the offending element.
    pub fn new(points: &[Vec3], triangles: &[[u32; 3]]) -> Result<Solid, DecomposeError> {
        if triangles.is_empty() {
            return Err(DecomposeError::Empty);
        }
        let pts = small_points(points)?;
        Solid::build(pts, triangles, true)
    }

    /// The indexed mesh. With `strict`, errors for an unbalanced edge, a failed pairing
    /// around a non-manifold edge and a non-positive volume; otherwise such edges are
    /// only marked non-manifold (unpaired).
    fn build(
        pts: Vec<[i64; 3]>,
        triangles: &[[u32; 3]],
        strict: bool,
    ) -> Result<Solid, DecomposeError> {
        let mut planes = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            if tri.iter().any(|&v| v as usize >= pts.len()) {
                return Err(DecomposeError::BadIndex { triangle: t });
            }
            let [a, b, c] = tri.map(|v| &pts[v as usize]);
            let pl = Plane::through(a, b, c)
                .ok_or(DecomposeError::DegenerateTriangle { triangle: t })?;
            planes.push(pl);
        }
        // Half-edges sorted by undirected key.
        let mut half: Vec<(u32, u32, u32, u8)> = Vec::with_capacity(triangles.len() * 3);
        for (t, tri) in triangles.iter().enumerate() {
            for k in 0..3 {
                let (u, v) = (tri[k], tri[(k + 1) % 3]);
                half.push((u.min(v), u.max(v), t as u32, k as u8));
            }
        }
        half.sort_unstable();
        let mut edges = Vec::new();
        let mut tri_edge = vec![[u32::MAX; 3]; triangles.len()];
        let mut partner = vec![[u32::MAX; 3]; triangles.len()];
        let mut i = 0;
        while i < half.len() {
            let (u, v) = (half[i].0, half[i].1);
            let mut j = i;
            while j < half.len() && half[j].0 == u && half[j].1 == v {
                j += 1;
            }
            let group = &half[i..j];
            let id = edges.len() as u32;
            // Forward: the triangle runs u -> v.
            let uses: Vec<(u32, bool)> = group
                .iter()
                .map(|&(_, _, t, k)| (t, triangles[t as usize][k as usize] == u))
                .collect();
            let fwd = uses.iter().filter(|x| x.1).count();
            let balanced = fwd * 2 == uses.len();
            if strict && !balanced {
                return Err(DecomposeError::NotClosed { edge: [u, v] });
            }
            let pairs: Vec<(u32, u32)> = if !balanced {
                Vec::new()
            } else if uses.len() == 2 {
                let (a, b) = if uses[0].1 {
                    (uses[0].0, uses[1].0)
                } else {
                    (uses[1].0, uses[0].0)
                };
                vec![(a, b)]
            } else {
                match pair_around_edge(&pts, triangles, [u, v], &uses) {
                    Some(p) => p,
                    None if !strict => Vec::new(),
                    None => return Err(DecomposeError::BadNonManifoldEdge { edge: [u, v] }),
                }
            };
            let mut reflex = false;
            for &(a, b) in &pairs {
                // The third vertex of b strictly above the plane of a.
                let w = third(&triangles[b as usize], u, v);
                if planes[a as usize].side_int(&pts[w as usize]) == Sign::Positive {
                    reflex = true;
                }
            }
            for &(_, _, t, k) in group {
                tri_edge[t as usize][k as usize] = id;
            }
            for &(a, b) in &pairs {
                set_partner(&mut partner, triangles, a, b, u, v);
                set_partner(&mut partner, triangles, b, a, u, v);
            }
            edges.push(EdgeInfo {
                ends: [u, v],
                reflex,
                non_manifold: uses.len() > 2 || !balanced,
                tris: uses.iter().map(|x| x.0).collect(),
            });
            i = j;
        }
        let (nm_vertex, nm_vertex_tris) = non_manifold_vertices(pts.len(), triangles, &partner);
        let mut volume6 = Int::ZERO;
        for tri in triangles {
            let [a, b, c] = tri.map(|v| Vec3::from_i64(pts[v as usize]));
            volume6 += a.dot(&b.cross(&c));
        }
        if strict && volume6 <= Int::ZERO {
            return Err(DecomposeError::NotPositive);
        }
        let mut bbox = Aabb::EMPTY;
        for tri in triangles {
            for &v in tri {
                bbox = bbox.with(&pts[v as usize]);
            }
        }
        Ok(Solid {
            pts,
            tris: triangles.to_vec(),
            planes,
            tri_edge,
            partner,
            edges,
            nm_vertex,
            nm_vertex_tris,
            volume6,
            bbox,
        })
    }

    /// A surface for the union solid (see `union`): the triangles with non-collinear
    /// corners, indexed as by [`Solid::new`] but without its errors for a failed pairing
    /// or a non-positive volume (unbalanced or unpaired edges are marked non-manifold).
    /// Checks indices, coordinates and closure: every edge used equally often in both
    /// directions, counting collinear triangles too (a corner repeated in a triangle
    /// makes no edge).
    pub fn surface(points: &[Vec3], triangles: &[[u32; 3]]) -> Result<Solid, DecomposeError> {
        if triangles.is_empty() {
            return Err(DecomposeError::Empty);
        }
        let pts = small_points(points)?;
        let mut half: Vec<(u32, u32, bool)> = Vec::with_capacity(triangles.len() * 3);
        let mut tris = Vec::with_capacity(triangles.len());
        for (t, tri) in triangles.iter().enumerate() {
            if tri.iter().any(|&v| v as usize >= pts.len()) {
                return Err(DecomposeError::BadIndex { triangle: t });
            }
            for k in 0..3 {
                let (u, v) = (tri[k], tri[(k + 1) % 3]);
                if u != v {
                    half.push((u.min(v), u.max(v), u < v));
                }
            }
            let [a, b, c] = tri.map(|v| &pts[v as usize]);
            if Plane::through(a, b, c).is_some() {
                tris.push(*tri);
            }
        }
        half.sort_unstable();
        let mut i = 0;
        while i < half.len() {
            let (u, v) = (half[i].0, half[i].1);
            let mut j = i;
            let mut balance = 0i64;
            while j < half.len() && half[j].0 == u && half[j].1 == v {
                balance += if half[j].2 { 1 } else { -1 };
                j += 1;
            }
            if balance != 0 {
                return Err(DecomposeError::NotClosed { edge: [u, v] });
            }
            i = j;
        }
        if tris.is_empty() {
            return Err(DecomposeError::NotPositive);
        }
        Solid::build(pts, &tris, false)
    }

    /// End points of triangle `t`'s side `k`.
    pub fn side_ends(&self, t: u32, k: u8) -> (&[i64; 3], &[i64; 3]) {
        let tri = &self.tris[t as usize];
        (
            &self.pts[tri[k as usize] as usize],
            &self.pts[tri[(k as usize + 1) % 3] as usize],
        )
    }

    /// End points of edge `e`.
    pub fn edge_ends(&self, e: u32) -> (&[i64; 3], &[i64; 3]) {
        let [a, b] = self.edges[e as usize].ends;
        (&self.pts[a as usize], &self.pts[b as usize])
    }
}

/// The points as `i64` triples, each coordinate below `2^MAX_COORD_BITS` in magnitude.
fn small_points(points: &[Vec3]) -> Result<Vec<[i64; 3]>, DecomposeError> {
    let limit = 1i64 << MAX_COORD_BITS;
    let mut pts = Vec::with_capacity(points.len());
    for (i, p) in points.iter().enumerate() {
        let c = p
            .as_small()
            .filter(|c| c.iter().all(|v| v.abs() < limit))
            .ok_or(DecomposeError::CoordinateTooLarge { point: i })?;
        pts.push(*c);
    }
    Ok(pts)
}

/// The vertex of `tri` other than `u` and `v`.
pub(crate) fn third(tri: &[u32; 3], u: u32, v: u32) -> u32 {
    *tri.iter()
        .find(|&&w| w != u && w != v)
        .expect("triangle with distinct corners")
}

fn set_partner(partner: &mut [[u32; 3]], tris: &[[u32; 3]], a: u32, b: u32, u: u32, v: u32) {
    let tri = &tris[a as usize];
    for k in 0..3 {
        let (x, y) = (tri[k], tri[(k + 1) % 3]);
        if (x == u && y == v) || (x == v && y == u) {
            partner[a as usize][k] = b;
        }
    }
}

/// Marks vertices whose incident triangles, linked across paired edges, form more than
/// one cycle (the surface touches itself there).
fn non_manifold_vertices(
    n: usize,
    tris: &[[u32; 3]],
    partner: &[[u32; 3]],
) -> (Vec<bool>, rustc_hash::FxHashMap<u32, Vec<u32>>) {
    let mut around: Vec<Vec<u32>> = vec![Vec::new(); n];
    for (t, tri) in tris.iter().enumerate() {
        for &v in tri {
            around[v as usize].push(t as u32);
        }
    }
    let mut nm = vec![false; n];
    let mut lists = rustc_hash::FxHashMap::default();
    for (v, ts) in around.iter().enumerate() {
        if ts.len() < 3 {
            continue;
        }
        // Walk from the first triangle across the two sides at v.
        let mut seen = rustc_hash::FxHashSet::default();
        let mut stack = vec![ts[0]];
        seen.insert(ts[0]);
        while let Some(t) = stack.pop() {
            let tri = &tris[t as usize];
            let i = tri.iter().position(|&w| w as usize == v).unwrap();
            for k in [i, (i + 2) % 3] {
                let p = partner[t as usize][k];
                if p != u32::MAX && seen.insert(p) {
                    stack.push(p);
                }
            }
        }
        if seen.len() != ts.len() {
            nm[v] = true;
            lists.insert(v as u32, ts.clone());
        }
    }
    (nm, lists)
}
