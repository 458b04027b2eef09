//! What a cell must still be split for, and the choice of the splitting plane.
//!
//! Every splitting plane is either the plane of an input triangle with a fragment in the
//! cell, or the plane through a reflex edge meeting the open cell and a third input
//! vertex (typically an end point of another reflex edge: such planes resolve many reflex
//! edges at once, e.g. the station planes of a ring). Both kinds have the bit size of a
//! triangle plane. Each also tells, for free, whether a part of the cell left without
//! fragments is inside the solid (see [`Choice`]).

use crate::fragments::{Frag, Origin};
use crate::solid::Solid;
use apart_kernel::plane::Plane;
use apart_kernel::predicates::dot_sign;
use apart_kernel::{Sign, Vec3};
use rustc_hash::FxHashMap;
use std::sync::Arc;

/// The elements that forbid a cell from being a leaf, because the solid may fail to be
/// locally convex there: reflex edges, non-manifold edges and non-manifold vertices
/// meeting the open cell.
#[derive(Debug, Default)]
pub(crate) struct Live {
    pub reflex: Vec<u32>,
    pub nm_edges: Vec<u32>,
    pub nm_verts: Vec<u32>,
}

impl Live {
    pub fn is_empty(&self) -> bool {
        self.reflex.is_empty() && self.nm_edges.is_empty() && self.nm_verts.is_empty()
    }
}

/// The live elements of a cell, read off its fragments: a piece of an input edge or an
/// input vertex kept by some fragment and not on the cell boundary meets the open cell.
pub(crate) fn live(solid: &Solid, frags: &[Arc<Frag>]) -> Live {
    let mut l = Live::default();
    for f in frags {
        for e in &f.edges {
            if let (Origin::Side(k), false) = (e.origin, e.bnd) {
                let id = solid.tri_edge[f.tri as usize][k as usize];
                let info = &solid.edges[id as usize];
                if info.non_manifold {
                    l.nm_edges.push(id);
                } else if info.reflex {
                    l.reflex.push(id);
                }
            }
        }
        for p in &f.pts {
            if !p.bnd && p.vertex != crate::fragments::NONE && solid.nm_vertex[p.vertex as usize] {
                l.nm_verts.push(p.vertex);
            }
        }
    }
    for v in [&mut l.reflex, &mut l.nm_edges, &mut l.nm_verts] {
        v.sort_unstable();
        v.dedup();
    }
    l
}

/// A splitting plane and the status of a part of the cell that ends up without fragments.
///
/// Why the status is known: the plane always contains either a fragment of the cell (a
/// triangle plane) or a reflex edge meeting the open cell. A fragment in the plane has
/// the solid locally on its inner side only, so an empty part on its outer side is
/// outside and one on its inner side is inside. At a reflex edge in the plane whose
/// triangles both lie (weakly) on one side, the exterior wedge (below 180°) lies between
/// them, so the solid fills the other side near the edge: an empty part there is inside.
#[derive(Clone, Copy, Debug)]
pub(crate) struct Choice {
    pub plane: Plane,
    pub below_inside: bool,
    pub above_inside: bool,
}

#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub(crate) enum Witness {
    /// The plane is the outward plane of a triangle with a fragment in the cell.
    Face,
    /// The plane contains a reflex edge meeting the open cell.
    Reflex,
}

impl Witness {
    pub fn choice(self, plane: Plane) -> Choice {
        match self {
            Witness::Face => Choice {
                plane,
                below_inside: true,
                above_inside: false,
            },
            Witness::Reflex => Choice {
                plane,
                below_inside: true,
                above_inside: true,
            },
        }
    }
}

/// How good a plane is: resolve many live elements cleanly, cross few, cut few
/// fragments.
///
/// A plane through a reflex edge removes it from both open parts, but how matters. With
/// outward normals `n1`, `n2` of the edge's faces, the exterior wedge at the edge is where
/// `n1·u >= 0` and `n2·u >= 0`. If one of the plane's half-planes at the edge, direction
/// `u`, lies in that closed wedge (`n1·u` and `n2·u` not of opposite signs) the cut is
/// clean: on both sides the solid is a single convex wedge there. Otherwise both
/// half-planes run inside the solid and one side gets two wedges touching along the
/// edge: an extra piece.
#[derive(Clone, Copy, Debug, Default)]
struct Score {
    clean: i64,
    pinched: i64,
    crossed: i64,
    coplanar: i64,
    cut: i64,
    below: i64,
    above: i64,
    /// Live edges strictly below and strictly above the plane (neither in it nor
    /// crossing it).
    live_below: i64,
    live_above: i64,
}

impl Score {
    fn key(&self) -> (i64, bool, i64, i64) {
        (
            self.clean - self.pinched - self.crossed,
            self.balanced(),
            self.coplanar - self.cut,
            -(self.below - self.above).abs(),
        )
    }

    /// The live edges left on the smaller side are at least a quarter of those left on
    /// either side (or there are at most 2): splitting such cells again and again makes a
    /// tree of logarithmic depth. Without it a hole's wall is peeled one facet at a
    /// time (the planes cutting off a few facets cut the fewest fragments), and every
    /// split walks almost all fragments: quadratic time.
    fn balanced(&self) -> bool {
        let (lo, hi) = (
            self.live_below.min(self.live_above),
            self.live_below.max(self.live_above),
        );
        lo + hi <= 2 || 3 * lo >= hi
    }
}

/// Whether the plane `h` through reflex edge `e` cuts it cleanly (see [`Score`]).
fn clean_cut(solid: &Solid, e: u32, h: &Plane) -> bool {
    let info = &solid.edges[e as usize];
    if info.non_manifold || info.tris.len() != 2 {
        return true;
    }
    let (a, b) = solid.edge_ends(e);
    let dir = Vec3::from_i64(*b).sub(&Vec3::from_i64(*a));
    let u = Vec3::from_i128(h.n).cross(&dir);
    let [n1, n2] = [0, 1].map(|i| Vec3::from_i128(solid.planes[info.tris[i] as usize].n));
    dot_sign(&n1, &u) * dot_sign(&n2, &u) != Sign::Negative
}

fn dist2(a: &[i64; 3], b: &[i64; 3]) -> f64 {
    (0..3).map(|k| (a[k] as f64 - b[k] as f64).powi(2)).sum()
}

/// Evenly spread indices `0..n`, at most `k` of them.
fn spread(n: usize, k: usize) -> impl Iterator<Item = usize> {
    let step = n.div_ceil(k.max(1)).max(1);
    (0..n).step_by(step)
}

fn element_score(solid: &Solid, live: &Live, h: &Plane) -> Score {
    let mut s = Score::default();
    for &e in live.reflex.iter().chain(&live.nm_edges) {
        let (a, b) = solid.edge_ends(e);
        let (sa, sb) = (h.side_int(a), h.side_int(b));
        if sa == Sign::Zero && sb == Sign::Zero {
            if clean_cut(solid, e, h) {
                s.clean += 1;
            } else {
                s.pinched += 1;
            }
        } else if sa * sb == Sign::Negative {
            s.crossed += 1;
        } else if sa == Sign::Negative || sb == Sign::Negative {
            s.live_below += 1;
        } else {
            s.live_above += 1;
        }
    }
    for &v in &live.nm_verts {
        if h.side_int(&solid.pts[v as usize]) == Sign::Zero {
            s.clean += 1;
        }
    }
    s
}

fn fragment_score(solid: &Solid, frags: &[Arc<Frag>], h: &Plane, s: &mut Score) {
    for f in frags {
        match f.straddle(h, solid) {
            (true, true) => {
                s.cut += 1;
                s.below += 1;
                s.above += 1;
            }
            (true, false) => s.below += 1,
            (false, true) => s.above += 1,
            (false, false) => s.coplanar += 1,
        }
    }
}

/// Candidate planes through live elements: for reflex edges, the planes of their faces
/// and the planes through them and other coplanar live reflex edges; otherwise the face
/// planes at non-manifold edges, then at non-manifold vertices.
pub(crate) fn candidates(
    solid: &Solid,
    in_cell: &FxHashMap<u32, u32>,
    live: &Live,
) -> Vec<(Plane, Witness)> {
    let mut cands: Vec<(Plane, Witness)> = Vec::new();
    let mut seen: rustc_hash::FxHashSet<Plane> = rustc_hash::FxHashSet::default();
    let mut add = |p: Plane, w: Witness, cands: &mut Vec<(Plane, Witness)>| {
        if seen.insert(p.unoriented()) {
            cands.push((p, w));
        }
    };
    let faces_of = |tris: &[u32]| -> Vec<u32> {
        tris.iter()
            .copied()
            .filter(|t| in_cell.contains_key(t))
            .collect()
    };
    if !live.reflex.is_empty() {
        let r = &live.reflex;
        for i in spread(r.len(), 12) {
            let e = r[i];
            let info = &solid.edges[e as usize];
            for t in faces_of(&info.tris) {
                add(solid.planes[t as usize], Witness::Face, &mut cands);
            }
            // Planes through e and another live reflex edge coplanar with it.
            let (a, b) = solid.edge_ends(e);
            // Per plane: how many edges it holds, and how far (squared, in floating
            // point: a preference only) its farthest one lies from e.
            let mut count: FxHashMap<Plane, (u32, f64)> =
                FxHashMap::with_capacity_and_hasher(r.len().min(400), Default::default());
            for j in spread(r.len(), 400) {
                if j == i {
                    continue;
                }
                let (c, d) = solid.edge_ends(r[j]);
                let p = match Plane::through(a, b, c) {
                    Some(p) => p,
                    None => match Plane::through(a, b, d) {
                        Some(p) => p,
                        None => continue, // collinear with e
                    },
                };
                if p.side_int(c) == Sign::Zero && p.side_int(d) == Sign::Zero {
                    let far = dist2(a, c);
                    let e = count.entry(p.unoriented()).or_insert((0, 0.0));
                    e.0 += 1;
                    e.1 = e.1.max(far);
                }
            }
            // Most edges first; among equals the farthest (through a hole, the plane to
            // the opposite wall halves the wall: see `Score::balanced`), then the first
            // normal, to stay deterministic.
            let mut best: Vec<(u32, f64, Plane)> =
                count.into_iter().map(|(p, (c, f))| (c, f, p)).collect();
            best.sort_unstable_by(|x, y| {
                y.0.cmp(&x.0)
                    .then_with(|| y.1.total_cmp(&x.1))
                    .then_with(|| x.2.n.cmp(&y.2.n))
            });
            for (_, _, p) in best.into_iter().take(2) {
                add(p, Witness::Reflex, &mut cands);
            }
        }
    } else if !live.nm_edges.is_empty() {
        for i in spread(live.nm_edges.len(), 8) {
            let info = &solid.edges[live.nm_edges[i] as usize];
            for t in faces_of(&info.tris) {
                add(solid.planes[t as usize], Witness::Face, &mut cands);
            }
        }
    } else {
        for i in spread(live.nm_verts.len(), 8) {
            if let Some(ts) = solid.nm_vertex_tris.get(&live.nm_verts[i]) {
                for t in faces_of(ts) {
                    add(solid.planes[t as usize], Witness::Face, &mut cands);
                }
            }
        }
    }
    cands
}

/// Fragments scored per candidate plane at most (see [`for_live`]).
const SAMPLE: usize = 1024;

/// Chooses the best candidate plane through a live element. `in_cell` tells which
/// triangles have a fragment here.
pub(crate) fn for_live(
    solid: &Solid,
    frags: &[Arc<Frag>],
    in_cell: &FxHashMap<u32, u32>,
    live: &Live,
) -> Choice {
    let cands = candidates(solid, in_cell, live);
    let mut scored: Vec<(Score, Plane, Witness)> = cands
        .into_iter()
        .map(|(p, w)| (element_score(solid, live, &p), p, w))
        .collect();
    let primary = |s: &Score| (s.key().0, s.key().1);
    scored.sort_by(|x, y| {
        primary(&y.0)
            .cmp(&primary(&x.0))
            .then_with(|| x.1.n.cmp(&y.1.n))
    });
    // Fragments only break ties of the primary criteria.
    let top = scored.first().map(|s| primary(&s.0));
    scored.retain(|s| Some(primary(&s.0)) == top);
    scored.truncate(6);
    // On large cells an evenly spread sample of the fragments estimates the counts
    // well enough (the choice is a preference; any candidate is a valid cut).
    let sample: Vec<Arc<Frag>>;
    let frags = if frags.len() > SAMPLE {
        sample = spread(frags.len(), SAMPLE)
            .map(|i| frags[i].clone())
            .collect();
        &sample[..]
    } else {
        frags
    };
    let mut best: Option<(Score, Plane, Witness)> = None;
    for (mut s, p, w) in scored {
        fragment_score(solid, frags, &p, &mut s);
        if best.as_ref().is_none_or(|b| s.key() > b.0.key()) {
            best = Some((s, p, w));
        }
    }
    let (_, p, w) = best.expect("a live element has candidate planes");
    w.choice(p)
}

/// Chooses the plane of a fragment to separate the connected groups of fragments of a
/// cell without live elements: cut as few fragments as possible, and leave fragments on
/// both sides.
pub(crate) fn for_groups(solid: &Solid, frags: &[Arc<Frag>]) -> Choice {
    let mut planes: Vec<Plane> = Vec::new();
    let mut seen = rustc_hash::FxHashSet::default();
    for f in frags {
        let p = solid.planes[f.tri as usize];
        if seen.insert(p) {
            planes.push(p);
        }
    }
    let mut best: Option<((i64, i64, i64), Plane)> = None;
    for i in spread(planes.len(), 24) {
        let p = planes[i];
        let mut s = Score::default();
        fragment_score(solid, frags, &p, &mut s);
        let key = (-s.cut, s.below.min(s.above), s.coplanar);
        if best.as_ref().is_none_or(|b| key > b.0) {
            best = Some((key, p));
        }
    }
    Witness::Face.choice(best.expect("a cell with fragments").1)
}
