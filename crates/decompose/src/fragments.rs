//! Fragments: the part of an input triangle inside the closed cell, as an exact convex
//! polygon, and their distribution when a cell is split.
//!
//! Why polygons rather than the separating-axis test "does the closed triangle meet the
//! open cell": clipping is exact with the same single predicate as cell splitting, it
//! keeps each fragment's vertices defined from input data (an input vertex, an input
//! segment crossed by a plane, or the triangle's plane and two cut planes), and it
//! records which pieces of the triangle's sides and corners lie on the cell boundary.
//! That last fact is what the partition needs: an input edge meets the open cell exactly
//! when some fragment keeps a piece of it that lies in no cut plane.
//!
//! Invariant: a fragment is a two-dimensional polygon meeting the open cell (it has a
//! point off every cell facet plane). Splitting keeps it: the part on one side of a plane
//! is kept only when some vertex is strictly on that side, and a fragment lying in the
//! cutting plane is on the boundary of both parts and is dropped.

use crate::solid::Solid;
use apart_kernel::plane::{HPoint, Plane};
use apart_kernel::Sign;
use std::sync::Arc;

/// No input vertex.
pub(crate) const NONE: u32 = u32::MAX;

/// Where a fragment's edge comes from.
#[derive(Clone, Copy, Debug)]
pub(crate) enum Origin {
    /// Part of side `k` of the triangle (corner `k` to corner `k + 1`).
    Side(u8),
    /// The intersection of the triangle's plane with a cut plane.
    Cut(Plane),
}

/// A fragment vertex.
#[derive(Clone, Debug)]
pub(crate) struct FPt {
    /// Shared: a crossing point belongs to both parts of a cut fragment, and a fragment
    /// copied to mark its boundary keeps its points.
    pub p: Arc<HPoint>,
    /// The input vertex it is, or [`NONE`].
    pub vertex: u32,
    /// It lies on the cell boundary.
    pub bnd: bool,
}

/// A fragment edge, from vertex `i` to vertex `i + 1`.
#[derive(Clone, Copy, Debug)]
pub(crate) struct FEdge {
    pub origin: Origin,
    /// It lies on the cell boundary (in some cut plane).
    pub bnd: bool,
}

/// The part of triangle `tri` in the closed cell.
#[derive(Clone, Debug)]
pub(crate) struct Frag {
    pub tri: u32,
    pub pts: Vec<FPt>,
    pub edges: Vec<FEdge>,
}

/// Where a fragment goes when its cell is split.
enum Placement {
    Below(Arc<Frag>),
    Above(Arc<Frag>),
    Both(Arc<Frag>, Arc<Frag>),
    /// In the cutting plane: on the boundary of both parts.
    On,
}

impl Frag {
    /// Every triangle whole, each input point one shared corner.
    pub fn all_whole(solid: &Solid) -> Vec<Arc<Frag>> {
        let corners: Vec<Arc<HPoint>> = solid
            .pts
            .iter()
            .map(|p| Arc::new(HPoint::int(*p)))
            .collect();
        (0..solid.tris.len() as u32)
            .map(|t| Arc::new(Frag::whole(solid, t, &corners)))
            .collect()
    }

    /// The whole triangle `t`, with `corners[v]` the input point `v`.
    fn whole(solid: &Solid, t: u32, corners: &[Arc<HPoint>]) -> Frag {
        let tri = solid.tris[t as usize];
        Frag {
            tri: t,
            pts: tri
                .iter()
                .map(|&v| FPt {
                    p: corners[v as usize].clone(),
                    vertex: v,
                    bnd: false,
                })
                .collect(),
            edges: (0..3)
                .map(|k| FEdge {
                    origin: Origin::Side(k),
                    bnd: false,
                })
                .collect(),
        }
    }

    /// Whether the fragment lies in `h`, known without a point test: its triangle's
    /// plane is `h`, either way round (vertices on a plane are the costly case of the
    /// exact side test).
    pub fn in_plane(&self, h: &Plane, solid: &Solid) -> bool {
        let own = &solid.planes[self.tri as usize];
        own == h || own.is_flip_of(h)
    }

    /// Whether some vertex is strictly below and some strictly above `h`.
    pub fn straddle(&self, h: &Plane, solid: &Solid) -> (bool, bool) {
        if self.in_plane(h, solid) {
            return (false, false);
        }
        let (mut below, mut above) = (false, false);
        for p in &self.pts {
            match h.side(&p.p) {
                Sign::Negative => below = true,
                Sign::Positive => above = true,
                Sign::Zero => {}
            }
            if below && above {
                break;
            }
        }
        (below, above)
    }
}

/// The fragments of a cell split by `h`: those below and those above (a fragment crossing
/// `h` is cut into both; one lying in `h` goes to neither).
pub(crate) fn split_by(
    frags: &[Arc<Frag>],
    h: &Plane,
    solid: &Solid,
) -> (Vec<Arc<Frag>>, Vec<Arc<Frag>>) {
    let mut below = Vec::with_capacity(frags.len());
    let mut above = Vec::with_capacity(frags.len());
    for f in frags {
        match place(f, h, solid) {
            Placement::Below(g) => below.push(g),
            Placement::Above(g) => above.push(g),
            Placement::Both(g, k) => {
                below.push(g);
                above.push(k);
            }
            Placement::On => {}
        }
    }
    (below, above)
}

/// Splits fragment `f` by `h`.
fn place(f: &Arc<Frag>, h: &Plane, solid: &Solid) -> Placement {
    if f.in_plane(h, solid) {
        return Placement::On;
    }
    // The signs on the stack: most fragments have few corners.
    let mut buf = [Sign::Zero; 12];
    let mut heap = Vec::new();
    let s: &mut [Sign] = if f.pts.len() <= buf.len() {
        &mut buf[..f.pts.len()]
    } else {
        heap.resize(f.pts.len(), Sign::Zero);
        &mut heap
    };
    for (si, p) in s.iter_mut().zip(&f.pts) {
        *si = h.side(&p.p);
    }
    let s = &*s;
    let pos = s.contains(&Sign::Positive);
    let neg = s.contains(&Sign::Negative);
    let zero = s.contains(&Sign::Zero);
    match (neg, pos) {
        (false, false) => Placement::On,
        (true, false) => Placement::Below(touching(f, s, zero)),
        (false, true) => Placement::Above(touching(f, s, zero)),
        (true, true) => {
            let m = f.pts.len();
            let cross: Vec<Option<Arc<HPoint>>> = (0..m)
                .map(|i| {
                    let j = (i + 1) % m;
                    (s[i] * s[j] == Sign::Negative).then(|| Arc::new(crossing(f, i, h, solid)))
                })
                .collect();
            Placement::Both(
                Arc::new(part(f, s, Sign::Negative, &cross, h)),
                Arc::new(part(f, s, Sign::Positive, &cross, h)),
            )
        }
    }
}

/// The fragment unchanged but for boundary marks where it touches the cutting plane.
fn touching(f: &Arc<Frag>, s: &[Sign], zero: bool) -> Arc<Frag> {
    if !zero {
        return f.clone();
    }
    let mut g = (**f).clone();
    let m = g.pts.len();
    for i in 0..m {
        if s[i] == Sign::Zero {
            g.pts[i].bnd = true;
            if s[(i + 1) % m] == Sign::Zero {
                g.edges[i].bnd = true;
            }
        }
    }
    Arc::new(g)
}

fn crossing(f: &Frag, i: usize, h: &Plane, solid: &Solid) -> HPoint {
    match f.edges[i].origin {
        Origin::Side(k) => {
            let (a, b) = solid.side_ends(f.tri, k);
            HPoint::on_segment(a, b, h)
        }
        Origin::Cut(g) => HPoint::meet(&solid.planes[f.tri as usize], &g, h),
    }
    .expect("a fragment edge crossing a plane meets it in one point")
}

#[derive(Clone, Copy, PartialEq, Eq)]
enum Src {
    Vertex(usize),
    Cross(usize),
}

fn part(f: &Frag, s: &[Sign], keep: Sign, cross: &[Option<Arc<HPoint>>], h: &Plane) -> Frag {
    let m = f.pts.len();
    let mut out: Vec<(FPt, Src)> = Vec::with_capacity(m + 2);
    for i in 0..m {
        if s[i] != -keep {
            let mut p = f.pts[i].clone();
            if s[i] == Sign::Zero {
                p.bnd = true;
            }
            out.push((p, Src::Vertex(i)));
        }
        if let Some(x) = &cross[i] {
            out.push((
                FPt {
                    p: x.clone(),
                    vertex: NONE,
                    bnd: true,
                },
                Src::Cross(i),
            ));
        }
    }
    let n = out.len();
    let edges = (0..n)
        .map(|a| {
            let (sa, sb) = (out[a].1, out[(a + 1) % n].1);
            let along = |i: usize, extra: bool| FEdge {
                origin: f.edges[i].origin,
                bnd: f.edges[i].bnd || extra,
            };
            match (sa, sb) {
                (Src::Vertex(i), Src::Vertex(j)) if j == (i + 1) % m => {
                    along(i, s[i] == Sign::Zero && s[j] == Sign::Zero)
                }
                (Src::Vertex(i), Src::Cross(j)) if j == i => along(i, false),
                (Src::Cross(i), Src::Vertex(j)) if j == (i + 1) % m => along(i, false),
                _ => FEdge {
                    origin: Origin::Cut(*h),
                    bnd: true,
                },
            }
        })
        .collect();
    Frag {
        tri: f.tri,
        pts: out.into_iter().map(|(p, _)| p).collect(),
        edges,
    }
}
