//! The open boundary of a surface taken as a chain of oriented triangles, and closing it.
//!
//! A triangle soup's winding number is well defined (the same whichever ray counts it)
//! exactly when its boundary as a chain is zero: every undirected edge is used as often
//! one way as the other. Non-manifold edges whose faces do not alternate, doubled walls
//! and crossing faces are all fine then; what is not is a *net* boundary edge. This
//! module finds the net boundary (edges with more uses one way than the other, with
//! that multiplicity), splits it into simple loops (it is balanced at every vertex,
//! the boundary of a boundary being zero), and caps each loop that can be capped
//! without guessing:
//!
//! - a loop that is planar, or nearly so (every vertex within [`PLANAR`] of the loop's
//!   size from the plane through its centroid with its Newell normal): every cap
//!   spanning it inside that slab encloses the same solid up to the slab;
//! - a seam: a long thin loop whose two sides lie within `gap` of each other (every
//!   vertex but the loop's two ends within `gap` of an edge of the loop that does not
//!   touch it): any cap adds or removes at most a strip `gap` wide.
//!
//! A cap runs against the loop, so that its boundary cancels it; its triangles come
//! from the crate's polygon triangulation (exact for planar simple loops, strips and
//! fans otherwise), which drops zero-area triangles. What those leave (loops whose
//! vertices are collinear, which bound no area) is returned as zero-area balancing
//! triangles, for a chain-level consumer such as the exact winding-number
//! decomposition, and never added to the mesh.

use super::edges::{runs, uses};
use crate::mesh::Mesh;
use crate::triangulate::triangulate;
use apart_kernel::orient::collinear;
use std::collections::HashMap;

/// A loop counts as nearly planar when every vertex lies within this fraction of the
/// loop's size (the diagonal of its box) from its plane.
pub const PLANAR: f64 = 0.02;
/// Loops longer than this are not tested for being seams (the test is quadratic).
const SEAM_MAX: usize = 4096;

/// A boundary loop left open.
#[derive(Clone, Debug, PartialEq)]
pub struct OpenLoop {
    /// Its number of edges.
    pub edges: usize,
    /// Its size: the diagonal of its bounding box, in grid units.
    pub size: f64,
    /// The farthest any vertex lies from the loop's plane, in grid units.
    pub deviation: f64,
    /// One of its vertices (a grid point).
    pub at: [i64; 3],
}

impl OpenLoop {
    fn new(lp: &[u32], v: &[[i64; 3]], shape: &LoopShape) -> OpenLoop {
        OpenLoop {
            edges: lp.len(),
            size: shape.size,
            deviation: shape.deviation,
            at: v[lp[0] as usize],
        }
    }
}

/// What [`close_loops`] did.
#[derive(Clone, Debug, Default, PartialEq)]
pub struct LoopClosing {
    /// Net boundary edges found (with multiplicity).
    pub boundary_edges: usize,
    /// Loops capped because they are planar or nearly so.
    pub planar: usize,
    /// Loops capped because they are seams.
    pub seams: usize,
    /// Triangles added to the mesh.
    pub triangles: usize,
    /// Zero-area triangles that balance what the caps' triangulation dropped (not in
    /// the mesh; see the module documentation).
    pub balance: Vec<[u32; 3]>,
    /// Loops that could not be capped: the surface stays open there.
    pub open: Vec<OpenLoop>,
}

/// The net boundary of `mesh` as a chain: each directed edge `a → b` used more often
/// that way than the other, repeated by the difference.
pub fn net_boundary(mesh: &Mesh) -> Vec<(u32, u32)> {
    let mut out = Vec::new();
    for run in runs(&uses(mesh)) {
        let f = run.iter().filter(|u| u.forward).count() as i64;
        let net = 2 * f - run.len() as i64;
        let (lo, hi) = (run[0].lo(), run[0].hi());
        let e = if net > 0 { (lo, hi) } else { (hi, lo) };
        out.extend(std::iter::repeat_n(e, net.unsigned_abs() as usize));
    }
    out
}

/// Undirected edges used by more than two triangles.
pub fn nonmanifold_edges(mesh: &Mesh) -> usize {
    runs(&uses(mesh)).filter(|r| r.len() > 2).count()
}

/// Splits a balanced set of directed edges into simple closed loops (vertex lists, loop
/// edge `i` running from vertex `i` to vertex `i + 1`).
pub fn simple_loops(edges: &[(u32, u32)]) -> Vec<Vec<u32>> {
    let mut out_of: HashMap<u32, Vec<u32>> = HashMap::new();
    for &(a, b) in edges {
        out_of.entry(a).or_default().push(b);
    }
    let mut loops = Vec::new();
    let mut starts: Vec<u32> = out_of.keys().copied().collect();
    starts.sort_unstable();
    for s in starts {
        while let Some(next) = out_of.get_mut(&s).and_then(Vec::pop) {
            // Walk from s until a vertex of the path repeats; cut off each cycle.
            let mut path = vec![s];
            let mut pos: HashMap<u32, usize> = HashMap::from([(s, 0)]);
            let mut v = next;
            loop {
                if let Some(&i) = pos.get(&v) {
                    // Back at `v`: the path from it is a cycle; go on from `v`.
                    let cycle: Vec<u32> = path.split_off(i);
                    for u in &cycle {
                        pos.remove(u);
                    }
                    if cycle.len() >= 2 {
                        loops.push(cycle);
                    }
                }
                pos.insert(v, path.len());
                path.push(v);
                match out_of.get_mut(&v).and_then(Vec::pop) {
                    Some(w) => v = w,
                    None => break, // unbalanced input: give up on this walk
                }
            }
        }
    }
    loops
}

/// Caps the loops of the net boundary of `mesh` that are planar or nearly so, or seams
/// narrower than `gap` (grid units); see the module documentation.
pub fn close_loops(mesh: &mut Mesh, gap: f64) -> LoopClosing {
    let boundary = net_boundary(mesh);
    let mut c = LoopClosing {
        boundary_edges: boundary.len(),
        ..LoopClosing::default()
    };
    if boundary.is_empty() {
        return c;
    }
    // The source face of a triangle along each boundary edge, for the caps.
    let mut source_of: HashMap<(u32, u32), u32> = HashMap::new();
    for (t, tri) in mesh.triangles.iter().enumerate() {
        for k in 0..3 {
            source_of
                .entry((tri[k], tri[(k + 1) % 3]))
                .or_insert(mesh.source_faces.get(t).copied().unwrap_or(0));
        }
    }
    let mut out = Vec::new();
    for lp in simple_loops(&boundary) {
        if is_collinear(&lp, &mesh.vertices) {
            // Bounds no area: balanced by a zero-area fan below.
            continue;
        }
        let shape = LoopShape::of(&lp, &mesh.vertices);
        let planar = shape.deviation <= PLANAR * shape.size;
        let seam = !planar && is_seam(&lp, &mesh.vertices, gap);
        if !planar && !seam {
            c.open.push(OpenLoop::new(&lp, &mesh.vertices, &shape));
            continue;
        }
        let source = source_of.get(&(lp[0], lp[1])).copied().unwrap_or(0);
        let reversed: Vec<u32> = lp.iter().rev().copied().collect();
        out.clear();
        triangulate(&reversed, &mesh.vertices, &mut out);
        c.triangles += out.len();
        if planar {
            c.planar += 1;
        } else {
            c.seams += 1;
        }
        mesh.source_faces
            .extend(std::iter::repeat_n(source, out.len()));
        mesh.triangles.append(&mut out);
    }
    // What the caps' triangulation dropped, and collinear loops: zero-area balance.
    let open_vertices: Vec<[i64; 3]> = c.open.iter().map(|o| o.at).collect();
    for lp in simple_loops(&net_boundary(mesh)) {
        if is_collinear(&lp, &mesh.vertices) {
            let rev: Vec<u32> = lp.iter().rev().copied().collect();
            c.balance
                .extend((1..rev.len() - 1).map(|i| [rev[0], rev[i], rev[i + 1]]));
        } else if !lp
            .iter()
            .any(|v| open_vertices.contains(&mesh.vertices[*v as usize]))
        {
            let shape = LoopShape::of(&lp, &mesh.vertices);
            c.open.push(OpenLoop::new(&lp, &mesh.vertices, &shape));
        }
    }
    c
}

/// Every vertex of the loop on one line (exactly).
fn is_collinear(lp: &[u32], v: &[[i64; 3]]) -> bool {
    let a = &v[lp[0] as usize];
    let Some(b) = lp.iter().map(|&i| &v[i as usize]).find(|p| *p != a) else {
        return true;
    };
    lp.iter().all(|&i| collinear(a, b, &v[i as usize]))
}

/// A loop's size and distance from planarity, in floating point (they only decide
/// whether a loop is capped, and are reported).
struct LoopShape {
    size: f64,
    deviation: f64,
}

impl LoopShape {
    fn of(lp: &[u32], v: &[[i64; 3]]) -> LoopShape {
        let p: Vec<[f64; 3]> = lp
            .iter()
            .map(|&i| v[i as usize].map(|c| c as f64))
            .collect();
        let n = p.len() as f64;
        let c = [0, 1, 2].map(|k| p.iter().map(|q| q[k]).sum::<f64>() / n);
        let mut lo = [f64::INFINITY; 3];
        let mut hi = [f64::NEG_INFINITY; 3];
        let mut normal = [0.0; 3];
        for (i, q) in p.iter().enumerate() {
            let r = &p[(i + 1) % p.len()];
            let (a, b) = (sub(q, &c), sub(r, &c));
            normal[0] += a[1] * b[2] - a[2] * b[1];
            normal[1] += a[2] * b[0] - a[0] * b[2];
            normal[2] += a[0] * b[1] - a[1] * b[0];
            for k in 0..3 {
                lo[k] = lo[k].min(q[k]);
                hi[k] = hi[k].max(q[k]);
            }
        }
        let size = dot(&sub(&hi, &lo), &sub(&hi, &lo)).sqrt();
        let len = dot(&normal, &normal).sqrt();
        let deviation = if len > 0.0 {
            p.iter()
                .map(|q| (dot(&sub(q, &c), &normal) / len).abs())
                .fold(0.0, f64::max)
        } else {
            f64::INFINITY
        };
        LoopShape { size, deviation }
    }
}

/// A long thin loop whose two sides lie within `gap` of each other: every vertex but at
/// most two (its ends) lies within `gap` of a loop edge not incident to it.
fn is_seam(lp: &[u32], v: &[[i64; 3]], gap: f64) -> bool {
    let n = lp.len();
    if !(4..=SEAM_MAX).contains(&n) || gap <= 0.0 {
        return false;
    }
    let p: Vec<[f64; 3]> = lp
        .iter()
        .map(|&i| v[i as usize].map(|c| c as f64))
        .collect();
    let mut far = 0;
    for i in 0..n {
        let near = (0..n).any(|j| {
            let j1 = (j + 1) % n;
            j != i && j1 != i && segment_distance(&p[i], &p[j], &p[j1]) <= gap
        });
        if !near {
            far += 1;
            if far > 2 {
                return false;
            }
        }
    }
    true
}

fn sub(a: &[f64; 3], b: &[f64; 3]) -> [f64; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn dot(a: &[f64; 3], b: &[f64; 3]) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// Distance from `x` to the segment `a b`.
fn segment_distance(x: &[f64; 3], a: &[f64; 3], b: &[f64; 3]) -> f64 {
    let ab = sub(b, a);
    let l = dot(&ab, &ab);
    let t = if l > 0.0 {
        (dot(&sub(x, a), &ab) / l).clamp(0.0, 1.0)
    } else {
        0.0
    };
    let q = [a[0] + t * ab[0], a[1] + t * ab[1], a[2] + t * ab[2]];
    let d = sub(x, &q);
    dot(&d, &d).sqrt()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn mesh(vertices: Vec<[i64; 3]>, triangles: Vec<[u32; 3]>) -> Mesh {
        let n = triangles.len();
        let m = vertices.len();
        Mesh {
            vertices,
            triangles,
            source_faces: (0..n as u32).collect(),
            source_vertices: (0..m as u32).collect(),
        }
    }

    /// A box [0,4]x[0,4]x[0,2] without its top, split into a ring of side faces.
    fn open_box() -> Mesh {
        let v = vec![
            [0, 0, 0],
            [4, 0, 0],
            [4, 4, 0],
            [0, 4, 0],
            [0, 0, 2],
            [4, 0, 2],
            [4, 4, 2],
            [0, 4, 2],
        ];
        let t = vec![
            [0, 2, 1],
            [0, 3, 2],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        mesh(v, t)
    }

    #[test]
    fn a_closed_box_has_no_boundary() {
        let mut m = open_box();
        m.triangles.extend([[4, 5, 6], [4, 6, 7]]);
        m.source_faces.extend([10, 11]);
        assert!(net_boundary(&m).is_empty());
    }

    #[test]
    fn the_open_top_is_one_planar_loop_and_is_capped() {
        let mut m = open_box();
        let b = net_boundary(&m);
        assert_eq!(b.len(), 4);
        let loops = simple_loops(&b);
        assert_eq!(loops.len(), 1);
        assert_eq!(loops[0].len(), 4);
        let c = close_loops(&mut m, 0.0);
        assert_eq!((c.planar, c.seams, c.open.len()), (1, 0, 0));
        assert!(net_boundary(&m).is_empty());
        assert_eq!(m.volume6(), apart_kernel::Int::from(6 * 4 * 4 * 2));
    }

    #[test]
    fn two_loops_touching_at_a_vertex_split_into_simple_loops() {
        // A figure eight: 0→1→2→0 and 0→3→4→0.
        let e = [(0, 1), (1, 2), (2, 0), (0, 3), (3, 4), (4, 0)];
        let mut loops = simple_loops(&e);
        loops.iter_mut().for_each(|l| l.sort_unstable());
        loops.sort();
        assert_eq!(loops, vec![vec![0, 1, 2], vec![0, 3, 4]]);
    }

    #[test]
    fn a_twisted_loop_stays_open_unless_it_is_a_seam() {
        // A saddle quadrilateral: far from planar, not thin.
        let mut m = mesh(
            vec![[0, 0, 0], [10, 0, 10], [10, 10, 0], [0, 10, 10], [5, 5, 40]],
            vec![[0, 1, 4], [1, 2, 4], [2, 3, 4], [3, 0, 4]],
        );
        let c = close_loops(&mut m, 1.0);
        assert_eq!(c.open.len(), 1);
        assert_eq!(c.open[0].edges, 4);
        assert!(c.open[0].deviation > PLANAR * c.open[0].size);
        assert_eq!(m.triangles.len(), 4);
    }

    #[test]
    fn a_flipped_face_among_good_ones_is_balanced_by_two_caps() {
        let mut m = open_box();
        m.triangles.extend([[4, 5, 6], [4, 7, 6]]); // the second runs the wrong way
        m.source_faces.extend([10, 11]);
        let c = close_loops(&mut m, 0.0);
        assert!(c.open.is_empty());
        assert!(net_boundary(&m).is_empty());
        // The flipped triangle plus two caps the right way: net one copy, right way.
        assert_eq!(m.volume6(), apart_kernel::Int::from(6 * 4 * 4 * 2));
    }
}
