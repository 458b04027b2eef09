//! One batch build of the arrangement, step by step (see the module steps in
//! [`super`]): geometry first (canonical circles, vertices, crossings, edges cut along
//! circles), then topology (rotation system, boundary cycles, faces).

use super::{
    ArcLabel, Arrangement, BuildStats, CycleId, Edge, EdgeId, FaceId, HalfEdge, InputArc,
    InputPoint, UnionFind, Vertex, VertexId,
};
use crate::arc::{point_bbox, Arc};
use apart_kernel::bvh::{by_low_x, sweep_pairs_between, sweep_step};
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::spherical::circle_intersection;
use apart_kernel::{Aabb, Sign, Vec3};
use rayon::prelude::*;
use rustc_hash::FxHashMap as HashMap;
use std::hash::{BuildHasher, Hash, Hasher};
use std::ops::ControlFlow;

/// An input arc on its circle's canonical orientation.
struct Canon<L> {
    circle: u32,
    start: Vec3,
    end: Vec3,
    label: Option<L>,
}

/// Builds the arrangement of `arcs` and `points` once (structural arcs, if any, are
/// among `arcs`). With `par`, the steps that are independent per circle, per candidate
/// pair or per vertex run on all threads; what they produce is put together in the
/// sequential order, so that both paths give the same arrangement.
pub(super) fn build_once<L: ArcLabel + Send + Sync, P: Clone + Send + Sync>(
    arcs: &[InputArc<L>],
    points: &[InputPoint<P>],
    stats: &mut BuildStats,
    par: bool,
) -> Arrangement<L, P> {
    // Geometry.
    let (circles, canon) = canonical_arcs(arcs);
    let (mut table, ends, lone) = end_point_vertices(&canon, points);
    let mut rings = circle_rings(&circles, &canon, &ends, &table, par);
    let runs = Runs::of(&circles, &rings, &table.vertices);
    let mut extra = crossings(&circles, &rings, &runs, &mut table, stats, par);
    points_on_arcs(&circles, &rings, &runs, &lone, &table, &mut extra);
    let mut vertices = table.vertices;
    let edges = cut_circles(&circles, &mut rings, extra, &canon, &ends, &vertices, par);
    mark_real_vertices(&mut vertices, &edges, &canon, &ends);
    // Topology.
    let next = rotation_system(&mut vertices, &edges, &circles, par);
    let (cycle_of, cycles) = trace_cycles(&next);
    let (face_of_cycle, faces) = join_faces(&edges, &cycle_of, cycles.len());
    Arrangement {
        circles,
        vertices,
        edges,
        next,
        cycle_of,
        cycles,
        face_of_cycle,
        faces,
    }
}

/// Step 1: the canonical circles (first non-zero component of the normal positive), and
/// every arc put on its circle's orientation, its label flipped when the arc is.
fn canonical_arcs<L: ArcLabel>(arcs: &[InputArc<L>]) -> (Vec<Vec3>, Vec<Canon<L>>) {
    let mut circle_ids: HashMap<Vec3, u32> = HashMap::default();
    let mut circles: Vec<Vec3> = Vec::new();
    let canon = arcs
        .iter()
        .map(|ia| {
            let (n, flipped) = canonical_circle(&ia.arc.normal);
            let circle = *circle_ids.entry(n.clone()).or_insert_with(|| {
                circles.push(n);
                (circles.len() - 1) as u32
            });
            let (s, e) = (ia.arc.start.primitive(), ia.arc.end.primitive());
            if flipped {
                Canon {
                    circle,
                    start: e,
                    end: s,
                    label: ia.label.as_ref().map(|l| l.flipped()),
                }
            } else {
                Canon {
                    circle,
                    start: s,
                    end: e,
                    label: ia.label.clone(),
                }
            }
        })
        .collect();
    (circles, canon)
}

fn canonical_circle(n: &Vec3) -> (Vec3, bool) {
    let n = n.primitive();
    for i in 0..3 {
        match apart_kernel::int::sign_of(&n.get(i)) {
            Sign::Positive => return (n, false),
            Sign::Negative => return (n.neg(), true),
            Sign::Zero => {}
        }
    }
    panic!("zero circle normal")
}

/// Step 2: vertices at the arcs' end points (ids in arc order), then at the input points
/// (real, carrying their labels). Returns the table, each arc's end vertices, and the
/// input points that are not arc end points (to be located on arcs; the others are
/// found by the arc-arc tests, as an end point inside another arc is a crossing).
fn end_point_vertices<L, P: Clone>(
    canon: &[Canon<L>],
    points: &[InputPoint<P>],
) -> (VertexTable<P>, Vec<[VertexId; 2]>, Vec<VertexId>) {
    let mut table = VertexTable::<P>::default();
    let ends: Vec<[VertexId; 2]> = canon
        .iter()
        .map(|c| [table.get_or_insert(&c.start), table.get_or_insert(&c.end)])
        .collect();
    let endpoint_count = table.vertices.len();
    let lone = points
        .iter()
        .map(|ip| {
            let id = table.get_or_insert(&ip.point.primitive());
            let v = &mut table.vertices[id.index()];
            v.labels.push(ip.label.clone());
            v.structural = false;
            id
        })
        .filter(|id| id.index() >= endpoint_count)
        .collect();
    (table, ends, lone)
}

/// Step 3: per circle, its arcs' end points in counter-clockwise order and which of the
/// gaps between consecutive points its arcs cover.
fn circle_rings<L, P: Sync>(
    circles: &[Vec3],
    canon: &[Canon<L>],
    ends: &[[VertexId; 2]],
    table: &VertexTable<P>,
    par: bool,
) -> Vec<Ring> {
    let mut rings: Vec<Ring> = circles.iter().map(|_| Ring::default()).collect();
    for (i, c) in canon.iter().enumerate() {
        let ring = &mut rings[c.circle as usize];
        ring.arcs.push(i);
        ring.order.push(ends[i][0]);
        ring.order.push(ends[i][1]);
    }
    let sort = |(c, ring): (usize, &mut Ring)| {
        ring.sort(&circles[c], &table.vertices);
        ring.cover(ends);
    };
    if par {
        rings.par_iter_mut().enumerate().for_each(sort);
    } else {
        rings.iter_mut().enumerate().for_each(sort);
    }
    rings
}

/// The maximal covered runs of all circles (overlapping arcs collapse into one run):
/// their circles, boxes, and end points when shorter than a half circle.
#[derive(Default)]
struct Runs {
    circle: Vec<u32>,
    boxes: Vec<Aabb<f64>>,
    ends: Vec<Option<[VertexId; 2]>>,
}

impl Runs {
    fn of<P>(circles: &[Vec3], rings: &[Ring], vertices: &[Vertex<P>]) -> Runs {
        let mut runs = Runs::default();
        for (c, ring) in rings.iter().enumerate() {
            ring.runs(&circles[c], vertices, |b, ends| {
                runs.circle.push(c as u32);
                runs.boxes.push(b);
                runs.ends.push(ends);
            });
        }
        runs
    }

    /// True when run `run` is shorter than a half circle with both end points strictly on
    /// one side of the circle `other` (two cheap dot products before any construction).
    fn apart<P>(&self, run: usize, other: &Vec3, vertices: &[Vertex<P>]) -> bool {
        self.ends[run].is_some_and(|[a, b]| {
            let s = dot_sign(other, &vertices[a.index()].point);
            s != Sign::Zero && s == dot_sign(other, &vertices[b.index()].point)
        })
    }
}

/// Step 4: crossings. Each pair of circles with runs whose boxes meet is intersected
/// once; a crossing point counts when an arc of each circle covers it. Returns the new
/// points of each circle (vertices are created in the order the pairs come).
///
/// With `par`, the candidate pairs are filtered, and the circle pairs intersected and
/// their points tested, on all threads; only the numbering of the new vertices, in the
/// order of the pairs, is sequential.
fn crossings<P: Sync>(
    circles: &[Vec3],
    rings: &[Ring],
    runs: &Runs,
    table: &mut VertexTable<P>,
    stats: &mut BuildStats,
    par: bool,
) -> Vec<Vec<VertexId>> {
    // The circle pairs (oriented as their first candidate pair) of the candidate pairs
    // whose runs may meet, in the order of the pairs.
    let vertices = &table.vertices;
    let may_meet = |i: usize, j: usize| -> Option<(u32, u32)> {
        let (ca, cb) = (runs.circle[i], runs.circle[j]);
        let (na, nb) = (&circles[ca as usize], &circles[cb as usize]);
        (ca != cb && !runs.apart(i, nb, vertices) && !runs.apart(j, na, vertices))
            .then_some((ca, cb))
    };
    let (count, meeting) = candidate_pairs_with(&runs.boxes, par, may_meet);
    stats.candidate_pairs += count;
    let mut seen: rustc_hash::FxHashSet<(u32, u32)> = rustc_hash::FxHashSet::default();
    let circle_pairs: Vec<(u32, u32)> = meeting
        .into_iter()
        .filter(|&(ca, cb)| seen.insert((ca.min(cb), ca.max(cb))))
        .collect();
    drop(seen);
    // Each circle pair's crossing points `-p`, `p` (p = na × nb) that arcs of both
    // circles cover, with the vertex already at the point (an arc end point or an input
    // point) or the hash of the point.
    let table_ref = &*table;
    let meet = |&(ca, cb): &(u32, u32)| -> [Option<Crossing>; 2] {
        let (na, nb) = (&circles[ca as usize], &circles[cb as usize]);
        let Some(p) = circle_intersection(na, nb) else {
            return [None, None];
        };
        let (ra, rb) = (&rings[ca as usize], &rings[cb as usize]);
        let found = |q: Vec3| {
            (ra.covers(na, &q, table_ref) && rb.covers(nb, &q, table_ref)).then(|| {
                let known = table_ref.ids.get(&q).copied();
                let hash = if known.is_some() {
                    0
                } else {
                    rustc_hash::FxBuildHasher.hash_one(&q)
                };
                Crossing {
                    point: q,
                    known,
                    hash,
                }
            })
        };
        [found(p.neg()), found(p)]
    };
    let mut points: Vec<[Option<Crossing>; 2]> = if par {
        circle_pairs.par_iter().map(meet).collect()
    } else {
        circle_pairs.iter().map(meet).collect()
    };
    // Number the points in order: a point seen before keeps its vertex; a new one gets
    // the next id.
    let base = table.vertices.len();
    let mut fresh: Vec<(usize, usize)> = Vec::new();
    let mut ids: Vec<[Option<VertexId>; 2]> = Vec::with_capacity(points.len());
    {
        let mut new_ids: std::collections::HashMap<Hashed<'_>, VertexId, PassHash> =
            std::collections::HashMap::with_capacity_and_hasher(points.len(), PassHash);
        for (k, pts) in points.iter().enumerate() {
            let mut row = [None, None];
            for (s, x) in pts.iter().enumerate() {
                let Some(x) = x else { continue };
                row[s] = Some(x.known.unwrap_or_else(|| {
                    *new_ids.entry(Hashed(x.hash, &x.point)).or_insert_with(|| {
                        fresh.push((k, s));
                        VertexId::new(base + fresh.len() - 1)
                    })
                }));
            }
            ids.push(row);
        }
    }
    table.vertices.reserve(fresh.len());
    for (k, s) in fresh {
        let x = points[k][s].take().expect("a new crossing point");
        table.vertices.push(Vertex {
            point: x.point,
            labels: Vec::new(),
            around: Vec::new(),
            structural: true,
        });
    }
    let mut extra: Vec<Vec<VertexId>> = vec![Vec::new(); circles.len()];
    for (&(ca, cb), row) in circle_pairs.iter().zip(ids) {
        for id in row.into_iter().flatten() {
            extra[ca as usize].push(id);
            extra[cb as usize].push(id);
        }
    }
    extra
}

/// A crossing point found by [`crossings`]: the vertex already there if any, else the
/// point's hash (computed with the points, on all threads).
struct Crossing {
    point: Vec3,
    known: Option<VertexId>,
    hash: u64,
}

/// A point keyed by its precomputed hash (equality is still the points').
#[derive(PartialEq, Eq)]
struct Hashed<'a>(u64, &'a Vec3);

impl Hash for Hashed<'_> {
    fn hash<H: Hasher>(&self, h: &mut H) {
        h.write_u64(self.0);
    }
}

/// The hasher of [`Hashed`] keys: passes their precomputed hash through.
#[derive(Clone, Copy, Default)]
struct PassHash;

impl BuildHasher for PassHash {
    type Hasher = PassHasher;
    fn build_hasher(&self) -> PassHasher {
        PassHasher(0)
    }
}

/// See [`PassHash`].
struct PassHasher(u64);

impl Hasher for PassHasher {
    fn finish(&self) -> u64 {
        self.0
    }
    fn write(&mut self, bytes: &[u8]) {
        for &b in bytes {
            self.0 = self.0.rotate_left(8) ^ u64::from(b);
        }
    }
    fn write_u64(&mut self, x: u64) {
        self.0 = x;
    }
}

/// Step 4 (points): the input points that are not arc end points, added to `extra` of
/// every circle on whose arcs they lie.
fn points_on_arcs<P>(
    circles: &[Vec3],
    rings: &[Ring],
    runs: &Runs,
    lone: &[VertexId],
    table: &VertexTable<P>,
    extra: &mut [Vec<VertexId>],
) {
    if lone.is_empty() {
        return;
    }
    let pboxes: Vec<Aabb<f64>> = lone
        .iter()
        .map(|&id| point_bbox(&table.vertices[id.index()].point))
        .collect();
    let pairs = sweep_pairs_between(
        &runs.boxes,
        &by_low_x(&runs.boxes),
        &pboxes,
        &by_low_x(&pboxes),
    );
    for (i, k) in pairs {
        let c = runs.circle[i] as usize;
        let id = lone[k];
        let p = &table.vertices[id.index()].point;
        if dot_sign(&circles[c], p) == Sign::Zero && rings[c].covers(&circles[c], p, table) {
            extra[c].push(id);
        }
    }
}

/// Step 5: each circle cut at all its points (in circle order); every covered gap is an
/// edge carrying the labels of the arcs covering it.
fn cut_circles<L: Clone + Send + Sync, P: Sync>(
    circles: &[Vec3],
    rings: &mut [Ring],
    mut extra: Vec<Vec<VertexId>>,
    canon: &[Canon<L>],
    ends: &[[VertexId; 2]],
    vertices: &[Vertex<P>],
    par: bool,
) -> Vec<Edge<L>> {
    let cut = |(c, (ring, extra)): (usize, (&mut Ring, &mut Vec<VertexId>))| {
        if !extra.is_empty() {
            ring.order.append(extra);
            ring.sort(&circles[c], vertices);
        }
        let mut edges = Vec::new();
        ring.emit_edges(c as u32, canon, ends, &mut edges);
        edges
    };
    if !par {
        let mut edges: Vec<Edge<L>> = Vec::new();
        for (c, ring) in rings.iter_mut().enumerate() {
            edges.append(&mut cut((c, (ring, &mut extra[c]))));
        }
        return edges;
    }
    let per_circle: Vec<Vec<Edge<L>>> = rings
        .par_iter_mut()
        .zip(extra.par_iter_mut())
        .enumerate()
        .map(cut)
        .collect();
    let mut edges = Vec::with_capacity(per_circle.iter().map(Vec::len).sum());
    for mut e in per_circle {
        edges.append(&mut e);
    }
    edges
}

/// Step 5 (vertices): a vertex is real when it is an input point (set in step 2), an end
/// point of a real arc, or where real edges of two different circles meet; a vertex that
/// exists only because a structural arc crosses or ends on a real arc stays structural.
fn mark_real_vertices<L, P>(
    vertices: &mut [Vertex<P>],
    edges: &[Edge<L>],
    canon: &[Canon<L>],
    ends: &[[VertexId; 2]],
) {
    for (i, c) in canon.iter().enumerate() {
        if c.label.is_some() {
            vertices[ends[i][0].index()].structural = false;
            vertices[ends[i][1].index()].structural = false;
        }
    }
    let mut real_circle: Vec<Option<u32>> = vec![None; vertices.len()];
    for e in edges.iter().filter(|e| !e.structural) {
        for v in [e.from.index(), e.to.index()] {
            match real_circle[v] {
                None => real_circle[v] = Some(e.circle),
                Some(c) if c != e.circle => vertices[v].structural = false,
                _ => {}
            }
        }
    }
}

/// Step 6: the rotation system. Every vertex's outgoing half-edges sorted
/// counter-clockwise; returns `next`: for each half-edge, the outgoing half-edge at its
/// target just before its twin (clockwise), so that the face on the left is followed.
fn rotation_system<L: Sync, P: Send + Sync>(
    vertices: &mut [Vertex<P>],
    edges: &[Edge<L>],
    circles: &[Vec3],
    par: bool,
) -> Vec<HalfEdge> {
    // Each vertex's half-edges in the order of their ids (the order the sort starts
    // from), in lists of the exact length.
    let mut degree = vec![0u32; vertices.len()];
    for edge in edges {
        degree[edge.from.index()] += 1;
        degree[edge.to.index()] += 1;
    }
    for (v, &d) in vertices.iter_mut().zip(&degree) {
        v.around.reserve_exact(d as usize);
    }
    drop(degree);
    for (e, edge) in edges.iter().enumerate() {
        let e = EdgeId::new(e);
        vertices[edge.from.index()].around.push(e.forward());
        vertices[edge.to.index()].around.push(e.backward());
    }
    let sort = |v: &mut Vertex<P>| sort_around(&v.point, &mut v.around, edges, circles);
    if par {
        vertices.par_iter_mut().for_each(sort);
    } else {
        vertices.iter_mut().for_each(sort);
    }
    let mut pos_in_around = vec![0u32; edges.len() * 2];
    for v in vertices.iter() {
        for (k, &h) in v.around.iter().enumerate() {
            pos_in_around[h.index()] = k as u32;
        }
    }
    let vertices = &*vertices;
    let next = |h: usize| {
        let twin = HalfEdge::new(h).twin();
        let edge = &edges[twin.edge().index()];
        let w = if twin.is_forward() {
            edge.from
        } else {
            edge.to
        };
        let around = &vertices[w.index()].around;
        let k = pos_in_around[twin.index()] as usize;
        around[(k + around.len() - 1) % around.len()]
    };
    if par {
        (0..edges.len() * 2).into_par_iter().map(next).collect()
    } else {
        (0..edges.len() * 2).map(next).collect()
    }
}

/// Sorts outgoing half-edges at `v` counter-clockwise, seen from outside.
///
/// Half-edge `h` leaves along tangent `σ (n × v)` (σ = +1 for forward half-edges).
/// For two of them, `det(v, t1, t2) = σ1 σ2 |v|² det(n1, n2, v)` and
/// `t1 · t2 = σ1 σ2 |v|² (n1 · n2)`, so the comparisons need only the circle normals.
fn sort_around<L>(v: &Vec3, around: &mut [HalfEdge], edges: &[Edge<L>], circles: &[Vec3]) {
    if around.len() < 2 {
        return;
    }
    let normal = |h: HalfEdge| &circles[edges[h.edge().index()].circle as usize];
    let sigma = |h: HalfEdge| {
        if h.is_forward() {
            Sign::Positive
        } else {
            Sign::Negative
        }
    };
    let cross_sign =
        |a: HalfEdge, b: HalfEdge| sigma(a) * sigma(b) * det3_sign(normal(a), normal(b), v);
    let dot_sgn = |a: HalfEdge, b: HalfEdge| sigma(a) * sigma(b) * dot_sign(normal(a), normal(b));
    let r = around[0];
    // Half 0: angle from the reference in [0, π); half 1: [π, 2π).
    let half = |h: HalfEdge| -> u8 {
        if h == r {
            return 0;
        }
        match cross_sign(r, h) {
            Sign::Positive => 0,
            Sign::Negative => 1,
            Sign::Zero => {
                if dot_sgn(r, h) == Sign::Positive {
                    0
                } else {
                    1
                }
            }
        }
    };
    let mut keyed: Vec<(u8, HalfEdge)> = around.iter().map(|&h| (half(h), h)).collect();
    keyed.sort_by(|&(ha, a), &(hb, b)| {
        ha.cmp(&hb).then_with(|| {
            if a == b {
                return std::cmp::Ordering::Equal;
            }
            if a == r {
                return std::cmp::Ordering::Less;
            }
            if b == r {
                return std::cmp::Ordering::Greater;
            }
            match cross_sign(a, b) {
                Sign::Positive => std::cmp::Ordering::Less,
                Sign::Negative => std::cmp::Ordering::Greater,
                Sign::Zero => std::cmp::Ordering::Equal,
            }
        })
    });
    for (slot, (_, h)) in around.iter_mut().zip(keyed) {
        *slot = h;
    }
}

/// Step 7: the boundary cycles of `next`, numbered by their smallest half-edge; returns
/// each half-edge's cycle and each cycle's smallest half-edge.
fn trace_cycles(next: &[HalfEdge]) -> (Vec<CycleId>, Vec<HalfEdge>) {
    let none = CycleId::new(u32::MAX as usize);
    let mut cycle_of = vec![none; next.len()];
    let mut cycles = Vec::new();
    for h in (0..next.len()).map(HalfEdge::new) {
        if cycle_of[h.index()] != none {
            continue;
        }
        let c = CycleId::new(cycles.len());
        cycles.push(h);
        let mut g = h;
        loop {
            cycle_of[g.index()] = c;
            g = next[g.index()];
            if g == h {
                break;
            }
        }
    }
    (cycle_of, cycles)
}

/// Step 8: faces, the cycles joined across structural edges (numbered by their first
/// cycle); returns each cycle's face and each face's cycles. A sphere with no edges has
/// one face with no cycle.
fn join_faces<L>(
    edges: &[Edge<L>],
    cycle_of: &[CycleId],
    cycle_count: usize,
) -> (Vec<FaceId>, Vec<Vec<CycleId>>) {
    let mut uf = UnionFind::new(cycle_count);
    for (e, edge) in edges.iter().enumerate() {
        if edge.structural {
            let e = EdgeId::new(e);
            uf.union(
                cycle_of[e.forward().index()].index(),
                cycle_of[e.backward().index()].index(),
            );
        }
    }
    // The face of each root cycle, numbered in the order of the first cycle reaching it.
    let none = FaceId::new(u32::MAX as usize);
    let mut face_of_root: Vec<FaceId> = vec![none; cycle_count];
    let mut faces: Vec<Vec<CycleId>> = Vec::new();
    let mut face_of_cycle = vec![none; cycle_count];
    for (c, slot) in face_of_cycle.iter_mut().enumerate() {
        let root = uf.find(c);
        if face_of_root[root] == none {
            faces.push(Vec::new());
            face_of_root[root] = FaceId::new(faces.len() - 1);
        }
        let f = face_of_root[root];
        faces[f.index()].push(CycleId::new(c));
        *slot = f;
    }
    if cycle_count == 0 {
        faces.push(Vec::new());
    }
    (face_of_cycle, faces)
}

/// The points of one circle in counter-clockwise order around its normal, starting
/// from a reference point, and the coverage of the gaps between them by its arcs.
#[derive(Default)]
struct Ring {
    arcs: Vec<usize>,
    /// Vertex ids, sorted counter-clockwise, without repeats.
    order: Vec<VertexId>,
    /// Position of each vertex id in `order`.
    pos: HashMap<VertexId, usize>,
    /// The half circle of each point of `order`: 0 for the reference point `order[0]`
    /// and the points less than a half turn after it, else 1.
    half: Vec<u8>,
    /// `covered[k]`: some arc covers the open gap from `order[k]` to `order[k + 1]`
    /// (cyclically).
    covered: Vec<bool>,
}

impl Ring {
    /// Sorts `order` counter-clockwise from its first point (the smallest id) and removes
    /// repeats.
    fn sort<P>(&mut self, n: &Vec3, vertices: &[Vertex<P>]) {
        self.order.sort_unstable();
        self.order.dedup();
        if self.order.is_empty() {
            return;
        }
        let point = |v: VertexId| &vertices[v.index()].point;
        let r = point(self.order[0]).clone();
        let half =
            |q: &Vec3| -> u8 { u8::from(!(q == &r || det3_sign(n, &r, q) == Sign::Positive)) };
        let mut keyed: Vec<(u8, VertexId)> =
            self.order.iter().map(|&v| (half(point(v)), v)).collect();
        keyed.sort_by(|a, b| {
            a.0.cmp(&b.0)
                .then_with(|| match det3_sign(n, point(a.1), point(b.1)) {
                    Sign::Positive => std::cmp::Ordering::Less,
                    Sign::Negative => std::cmp::Ordering::Greater,
                    Sign::Zero => std::cmp::Ordering::Equal,
                })
        });
        self.half = keyed.iter().map(|&(h, _)| h).collect();
        self.order = keyed.into_iter().map(|(_, v)| v).collect();
        self.pos = self
            .order
            .iter()
            .enumerate()
            .map(|(k, &v)| (v, k))
            .collect();
    }

    /// The gap indices an arc covers, as (first gap, one past the last), cyclically.
    fn span(&self, ends: &[VertexId; 2]) -> (usize, usize) {
        (self.pos[&ends[0]], self.pos[&ends[1]])
    }

    fn cover(&mut self, ends: &[[VertexId; 2]]) {
        let len = self.order.len();
        let mut diff = vec![0i64; len + 1];
        for &a in &self.arcs {
            let (s, e) = self.span(&ends[a]);
            if s < e {
                diff[s] += 1;
                diff[e] -= 1;
            } else {
                diff[s] += 1;
                diff[len] -= 1;
                diff[0] += 1;
                diff[e] -= 1;
            }
        }
        let mut acc = 0;
        self.covered = (0..len)
            .map(|k| {
                acc += diff[k];
                acc > 0
            })
            .collect();
    }

    /// Calls `f` with the box of every maximal covered run of the circle, and its end
    /// points when it is shorter than a half circle.
    fn runs<P>(
        &self,
        n: &Vec3,
        vertices: &[Vertex<P>],
        mut f: impl FnMut(Aabb<f64>, Option<[VertexId; 2]>),
    ) {
        let len = self.order.len();
        let point = |k: usize| &vertices[self.order[k % len].index()].point;
        let gap_box = |k: usize| {
            Arc {
                normal: n.clone(),
                start: point(k).clone(),
                end: point(k + 1).clone(),
            }
            .bbox()
        };
        // Start after an uncovered gap so runs are not split at the reference point.
        let Some(first) = (0..len).find(|&k| !self.covered[k]) else {
            // The whole circle is covered: one run.
            let b = (1..len).fold(gap_box(0), |b, k| b.union(&gap_box(k)));
            f(b, None);
            return;
        };
        let short = |a: usize, b: usize| -> Option<[VertexId; 2]> {
            (det3_sign(n, point(a), point(b)) == Sign::Positive)
                .then_some([self.order[a], self.order[b]])
        };
        // cur: (box, first point index of the run).
        let mut cur: Option<(Aabb<f64>, usize)> = None;
        for step in 1..=len {
            let k = (first + step) % len;
            if self.covered[k] {
                let b = gap_box(k);
                match &mut cur {
                    Some((c, _)) => *c = c.union(&b),
                    None => cur = Some((b, k)),
                }
            } else if let Some((c, start)) = cur.take() {
                f(c, short(start, k));
            }
        }
        if let Some((c, start)) = cur {
            f(c, short(start, first));
        }
    }

    /// Whether `q` (a point of this circle) lies on a closed arc of the circle.
    fn covers<P>(&self, n: &Vec3, q: &Vec3, table: &VertexTable<P>) -> bool {
        if let Some(id) = table.ids.get(q) {
            if self.pos.contains_key(id) {
                return true; // an end point of an arc of this circle
            }
        }
        let len = self.order.len();
        let r = &table.vertices[self.order[0].index()].point;
        let half = |x: &Vec3| -> u8 { u8::from(!(x == r || det3_sign(n, r, x) == Sign::Positive)) };
        let hq = half(q);
        // Number of points strictly before q in the counter-clockwise order (the points'
        // halves are those `sort` found).
        let is_before = |k: usize| {
            let hx = self.half[k];
            hx < hq
                || (hx == hq
                    && det3_sign(n, &table.vertices[self.order[k].index()].point, q)
                        == Sign::Positive)
        };
        let (mut before, mut end) = (0, len);
        while before < end {
            let mid = before + (end - before) / 2;
            if is_before(mid) {
                before = mid + 1;
            } else {
                end = mid;
            }
        }
        let gap = if before == 0 { len - 1 } else { before - 1 };
        self.covered[gap]
    }

    /// Edges of this circle: one per covered gap, with the labels of the covering arcs.
    fn emit_edges<L: Clone>(
        &mut self,
        circle: u32,
        canon: &[Canon<L>],
        ends: &[[VertexId; 2]],
        edges: &mut Vec<Edge<L>>,
    ) {
        let len = self.order.len();
        let mut starts: Vec<Vec<usize>> = vec![Vec::new(); len];
        let mut active: Vec<usize> = Vec::new();
        for &a in &self.arcs {
            let (s, e) = self.span(&ends[a]);
            if s > e {
                active.push(a); // wraps past the reference point: active from gap 0
            }
            starts[s].push(a);
        }
        for (k, starting) in starts.iter().enumerate() {
            // Arcs ending at point k stop; arcs starting at point k begin.
            active.retain(|&a| self.pos[&ends[a][1]] != k);
            active.extend(starting.iter().copied());
            if active.is_empty() {
                continue;
            }
            let mut labels = Vec::new();
            let mut structural = true;
            for &a in &active {
                if let Some(l) = &canon[a].label {
                    labels.push(l.clone());
                    structural = false;
                }
            }
            edges.push(Edge {
                circle,
                from: self.order[k],
                to: self.order[(k + 1) % len],
                labels,
                structural,
            });
        }
    }
}

/// Vertices keyed by their primitive point.
struct VertexTable<P> {
    ids: HashMap<Vec3, VertexId>,
    vertices: Vec<Vertex<P>>,
}

impl<P> Default for VertexTable<P> {
    fn default() -> Self {
        VertexTable {
            ids: HashMap::default(),
            vertices: Vec::new(),
        }
    }
}

impl<P> VertexTable<P> {
    /// The id of the vertex at primitive point `p`, created (structural until an edge or
    /// point makes it real) when new.
    fn get_or_insert(&mut self, p: &Vec3) -> VertexId {
        if let Some(&id) = self.ids.get(p) {
            return id;
        }
        self.vertices.push(Vertex {
            point: p.clone(),
            labels: Vec::new(),
            around: Vec::new(),
            structural: true,
        });
        let id = VertexId::new(self.vertices.len() - 1);
        self.ids.insert(p.clone(), id);
        id
    }
}

/// Pairs of boxes that overlap, each `(smaller index, larger)`, ordered by the later box
/// of the pair in the order of low x, then by the earlier one.
///
/// The order matters: the crossings' vertices are numbered in the order the pairs come,
/// and the numbering decides each circle's reference point, hence the order of the edges,
/// half-edges, cycles and faces that plans and pictures follow. The kernel's sweep
/// reports a pair when its earlier box is swept (by the earlier box, then the later);
/// a stable counting sort by the later box's rank puts them in this order in linear time.
#[cfg(test)]
fn candidate_pairs(boxes: &[Aabb<f64>], par: bool) -> Vec<(usize, usize)> {
    candidate_pairs_with(boxes, par, |i, j| Some((i, j))).1
}

/// [`candidate_pairs`] mapped through `keep` (called with the smaller index first) as
/// they are found, the pairs it drops left out, and the number of all pairs.
///
/// With `par`, the sweep and `keep` run on all threads in slices of the order (the
/// pairs of each slice come as the sequential sweep finds them, and the slices in order).
fn candidate_pairs_with<T: Send>(
    boxes: &[Aabb<f64>],
    par: bool,
    keep: impl Fn(usize, usize) -> Option<T> + Sync,
) -> (usize, Vec<T>) {
    let order = by_low_x(boxes);
    let mut rank = vec![0u32; boxes.len()];
    for (r, &i) in order.iter().enumerate() {
        rank[i as usize] = r as u32;
    }
    // The kept pairs with their later box's rank, in the order of the sweep.
    let sweep = |xs: std::ops::Range<usize>| {
        let mut count = 0;
        let mut found: Vec<(u32, T)> = Vec::new();
        for x in xs {
            let _ = sweep_step(boxes, &order, x, |i, j| {
                count += 1;
                if let Some(t) = keep(i.min(j) as usize, i.max(j) as usize) {
                    found.push((rank[j as usize], t));
                }
                ControlFlow::<()>::Continue(())
            });
        }
        (count, found)
    };
    let (count, found) = if par {
        let slice = order
            .len()
            .div_ceil(64 * rayon::current_num_threads())
            .max(1);
        let per_slice: Vec<(usize, Vec<(u32, T)>)> = (0..order.len().div_ceil(slice))
            .into_par_iter()
            .map(|k| sweep(k * slice..((k + 1) * slice).min(order.len())))
            .collect();
        let count = per_slice.iter().map(|s| s.0).sum();
        let mut found = Vec::with_capacity(per_slice.iter().map(|s| s.1.len()).sum());
        for (_, mut f) in per_slice {
            found.append(&mut f);
        }
        (count, found)
    } else {
        sweep(0..order.len())
    };
    // start[r]: where the pairs whose later box has rank r go.
    let mut start = vec![0usize; boxes.len() + 1];
    for &(r, _) in &found {
        start[r as usize + 1] += 1;
    }
    for r in 0..boxes.len() {
        start[r + 1] += start[r];
    }
    let mut out: Vec<Option<T>> = std::iter::repeat_with(|| None).take(found.len()).collect();
    for (r, t) in found {
        let slot = &mut start[r as usize];
        out[*slot] = Some(t);
        *slot += 1;
    }
    (
        count,
        out.into_iter()
            .map(|t| t.expect("every slot filled"))
            .collect(),
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The sort and sweep the arrangement used before the kernel's: each pair reported
    /// when its later box is swept, against the earlier boxes still active in order.
    fn pairs_by_later_box(boxes: &[Aabb<f64>]) -> Vec<(usize, usize)> {
        let mut order: Vec<usize> = (0..boxes.len()).collect();
        order.sort_by(|&a, &b| boxes[a].min[0].total_cmp(&boxes[b].min[0]));
        let mut out = Vec::new();
        let mut active: Vec<usize> = Vec::new();
        for &i in &order {
            let lo = boxes[i].min[0];
            active.retain(|&j| boxes[j].max[0] >= lo);
            for &j in &active {
                if boxes[i].overlaps(&boxes[j]) {
                    out.push((j.min(i), j.max(i)));
                }
            }
            active.push(i);
        }
        out
    }

    #[test]
    fn candidate_pairs_come_in_the_order_of_their_later_box() {
        // Boxes on a coarse grid (many equal low x, equal ends and touching faces).
        let mut rng = apart_testkit::solids::Lcg(12345);
        let mut next = |m: u64| rng.below(m);
        for n in [0, 1, 2, 5, 20, 200] {
            for _ in 0..20 {
                let boxes: Vec<Aabb<f64>> = (0..n)
                    .map(|_| {
                        let lo = [0, 1, 2].map(|_| next(8) as f64 / 4.0 - 1.0);
                        let len = [0, 1, 2].map(|_| next(4) as f64 / 4.0);
                        Aabb {
                            min: lo,
                            max: [0, 1, 2].map(|k| lo[k] + len[k]),
                        }
                    })
                    .collect();
                let expected = pairs_by_later_box(&boxes);
                assert_eq!(candidate_pairs(&boxes, false), expected);
                assert_eq!(candidate_pairs(&boxes, true), expected);
            }
        }
    }
}
