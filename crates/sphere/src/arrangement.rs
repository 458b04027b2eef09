//! The exact arrangement of great-circle arcs on the sphere.
//!
//! Built in one batch, with no sweep and hence no sweep-order predicates:
//! 1. every arc is put on its circle's canonical orientation (labels flipped to match);
//! 2. all pairs of arcs whose floating-point boxes meet are intersected exactly (two
//!    circles meet at `±(n1 × n2)`; overlapping arcs of one circle meet at end points);
//! 3. each arc is cut at the points found on it, sorted along the arc, and identical
//!    pieces from different arcs are merged into one edge carrying all their labels;
//! 4. the edges leaving each vertex are sorted counter-clockwise (seen from outside);
//! 5. boundary cycles are traced (faces on the left of half-edges).
//!
//! Degeneracy is the normal case: overlapping arcs, many arcs through one vertex and end
//! points on other arcs all reduce to exact point equality of primitive vectors.
//!
//! A face of the sphere may have several boundary cycles. When the graph is not
//! connected, the builder adds *structural* arcs joining its components and builds
//! again; cycles separated only by structural edges form one face, and a vertex or edge
//! that exists only because of structural arcs is marked as such.

use crate::arc::{point_bbox, Arc};
use apart_kernel::bvh::{by_low_x, sweep_pairs, sweep_pairs_between};
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::spherical::circle_intersection;
use apart_kernel::{Aabb, Sign, Vec3};
use rustc_hash::FxHashMap as HashMap;
use std::ops::ControlFlow;

/// Data attached to an input arc and merged onto the edges it covers.
pub trait ArcLabel: Clone {
    /// The label as seen from the opposite orientation of the arc (normal negated).
    fn flipped(&self) -> Self;
}

/// An arc to insert; `label: None` marks a structural arc (no data, only topology).
#[derive(Clone, Debug)]
pub struct InputArc<L> {
    /// The arc.
    pub arc: Arc,
    /// Its data, oriented like `arc`.
    pub label: Option<L>,
}

/// A point to insert as a vertex, with data.
#[derive(Clone, Debug)]
pub struct InputPoint<P> {
    /// The point (any non-zero integer vector).
    pub point: Vec3,
    /// Its data.
    pub label: P,
}

/// A vertex of the arrangement.
#[derive(Clone, Debug)]
pub struct Vertex<P> {
    /// The point, a primitive integer vector.
    pub point: Vec3,
    /// Data of the input points at this position.
    pub labels: Vec<P>,
    /// Outgoing half-edges in counter-clockwise order seen from outside the sphere.
    pub around: Vec<u32>,
    /// True when the vertex exists only because of structural arcs.
    pub structural: bool,
}

/// An edge: an open minor arc between two vertices.
#[derive(Clone, Debug)]
pub struct Edge<L> {
    /// Index of its circle in [`Arrangement::circles`].
    pub circle: u32,
    /// The edge runs counter-clockwise around the circle's normal from `from` to `to`.
    pub from: u32,
    /// See `from`.
    pub to: u32,
    /// Data of the input arcs covering it, oriented like the circle's normal.
    pub labels: Vec<L>,
    /// True when only structural arcs cover it.
    pub structural: bool,
}

/// The arrangement: vertices, edges, half-edges (two per edge: `2e` runs from `from` to
/// `to`, `2e + 1` back), boundary cycles and faces.
#[derive(Clone, Debug)]
pub struct Arrangement<L, P> {
    circles: Vec<Vec3>,
    vertices: Vec<Vertex<P>>,
    edges: Vec<Edge<L>>,
    next: Vec<u32>,
    cycle_of: Vec<u32>,
    cycles: Vec<u32>,
    face_of_cycle: Vec<u32>,
    faces: Vec<Vec<u32>>,
}

/// Statistics of a build.
#[derive(Clone, Copy, Debug, Default)]
pub struct BuildStats {
    /// Input arcs.
    pub arcs: usize,
    /// Candidate arc pairs from the broad phase.
    pub candidate_pairs: usize,
    /// Structural arcs added to connect components.
    pub structural_arcs: usize,
}

struct Canon<L> {
    circle: u32,
    start: Vec3,
    end: Vec3,
    label: Option<L>,
}

impl<L: ArcLabel, P: Clone> Arrangement<L, P> {
    /// Builds the arrangement of `arcs` and `points`.
    pub fn build(
        arcs: Vec<InputArc<L>>,
        points: Vec<InputPoint<P>>,
    ) -> (Arrangement<L, P>, BuildStats) {
        let mut stats = BuildStats {
            arcs: arcs.len(),
            ..Default::default()
        };
        let first = build_once(&arcs, &points, &mut stats);
        let extra = connecting_arcs(&first);
        if extra.is_empty() {
            return (first, stats);
        }
        stats.structural_arcs = extra.len();
        let mut all = arcs;
        all.extend(extra.into_iter().map(|arc| InputArc { arc, label: None }));
        let second = build_once(&all, &points, &mut stats);
        debug_assert!(
            connecting_arcs(&second).is_empty(),
            "structural arcs left the graph disconnected"
        );
        (second, stats)
    }

    /// Canonical circle normals (first non-zero component positive).
    pub fn circles(&self) -> &[Vec3] {
        &self.circles
    }

    /// The vertices.
    pub fn vertices(&self) -> &[Vertex<P>] {
        &self.vertices
    }

    /// The edges.
    pub fn edges(&self) -> &[Edge<L>] {
        &self.edges
    }

    /// Number of half-edges (twice the edges).
    pub fn half_edge_count(&self) -> usize {
        self.edges.len() * 2
    }

    /// Origin vertex of half-edge `h`.
    pub fn origin(&self, h: u32) -> u32 {
        let e = &self.edges[(h / 2) as usize];
        if h % 2 == 0 {
            e.from
        } else {
            e.to
        }
    }

    /// Target vertex of half-edge `h`.
    pub fn target(&self, h: u32) -> u32 {
        self.origin(h ^ 1)
    }

    /// The next half-edge around the face on the left of `h`.
    pub fn next(&self, h: u32) -> u32 {
        self.next[h as usize]
    }

    /// The boundary cycle containing half-edge `h`.
    pub fn cycle_of(&self, h: u32) -> u32 {
        self.cycle_of[h as usize]
    }

    /// Number of boundary cycles.
    pub fn cycle_count(&self) -> usize {
        self.cycles.len()
    }

    /// One half-edge of cycle `c`.
    pub fn cycle_start(&self, c: u32) -> u32 {
        self.cycles[c as usize]
    }

    /// The half-edges of cycle `c` in order.
    pub fn cycle_half_edges(&self, c: u32) -> Vec<u32> {
        let start = self.cycles[c as usize];
        let mut out = vec![start];
        let mut h = self.next[start as usize];
        while h != start {
            out.push(h);
            h = self.next[h as usize];
        }
        out
    }

    /// The face of cycle `c`.
    pub fn face_of_cycle(&self, c: u32) -> u32 {
        self.face_of_cycle[c as usize]
    }

    /// The face on the left of half-edge `h`.
    pub fn face_of(&self, h: u32) -> u32 {
        self.face_of_cycle[self.cycle_of[h as usize] as usize]
    }

    /// The faces, each a list of boundary cycles (structural edges included). A sphere
    /// with no edges has one face with no cycle.
    pub fn faces(&self) -> &[Vec<u32>] {
        &self.faces
    }

    /// True when half-edge `h` runs counter-clockwise around its circle's normal (its
    /// left side is the circle's positive side).
    pub fn is_forward(h: u32) -> bool {
        h % 2 == 0
    }

    /// The half-edge `h` as an arc (oriented along `h`).
    pub fn half_edge_arc(&self, h: u32) -> Arc {
        let e = &self.edges[(h / 2) as usize];
        let n = &self.circles[e.circle as usize];
        let (a, b) = (
            &self.vertices[e.from as usize].point,
            &self.vertices[e.to as usize].point,
        );
        if h % 2 == 0 {
            Arc {
                normal: n.clone(),
                start: a.clone(),
                end: b.clone(),
            }
        } else {
            Arc {
                normal: n.neg(),
                start: b.clone(),
                end: a.clone(),
            }
        }
    }

    /// The edge `e` as an arc counter-clockwise around its circle's canonical normal.
    pub fn edge_arc(&self, e: u32) -> Arc {
        self.half_edge_arc(2 * e)
    }

    /// The real boundary of face `f` as closed loops of real half-edges (face on the
    /// left), one loop per boundary component: structural edges are ignored, so a face
    /// with holes has several loops.
    pub fn boundary_loops(&self, f: u32) -> Vec<Vec<u32>> {
        let mut hs: Vec<u32> = Vec::new();
        for &c in &self.faces[f as usize] {
            hs.extend(
                self.cycle_half_edges(c)
                    .into_iter()
                    .filter(|&h| !self.edges[(h / 2) as usize].structural),
            );
        }
        let mut seen: rustc_hash::FxHashSet<u32> = rustc_hash::FxHashSet::default();
        let mut loops = Vec::new();
        for &h0 in &hs {
            if !seen.insert(h0) {
                continue;
            }
            let mut lp = vec![h0];
            let mut h = self.real_next(h0);
            while h != h0 {
                seen.insert(h);
                lp.push(h);
                h = self.real_next(h);
            }
            loops.push(lp);
        }
        loops
    }

    /// The real half-edge following real half-edge `h` around the face on its left when
    /// structural edges are ignored.
    fn real_next(&self, h: u32) -> u32 {
        let w = self.target(h);
        let around = &self.vertices[w as usize].around;
        let k = around
            .iter()
            .position(|&g| g == h ^ 1)
            .expect("twin at target");
        for step in 1..=around.len() {
            let g = around[(k + around.len() - step) % around.len()];
            if !self.edges[(g / 2) as usize].structural {
                return g;
            }
        }
        unreachable!("a real half-edge has a real twin")
    }

    /// Number of real (non-structural) vertices, edges and faces, for statistics.
    pub fn real_counts(&self) -> (usize, usize, usize) {
        let v = self.vertices.iter().filter(|v| !v.structural).count();
        let e = self.edges.iter().filter(|e| !e.structural).count();
        (v, e, self.faces.len())
    }
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

fn build_once<L: ArcLabel, P: Clone>(
    arcs: &[InputArc<L>],
    points: &[InputPoint<P>],
    stats: &mut BuildStats,
) -> Arrangement<L, P> {
    // 1. Canonical circles and orientations.
    let mut circle_ids: HashMap<Vec3, u32> = HashMap::default();
    let mut circles: Vec<Vec3> = Vec::new();
    let canon: Vec<Canon<L>> = arcs
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

    // 2. Vertices at end points and input points.
    let mut table = VertexTable::<P>::default();
    let ends: Vec<[u32; 2]> = canon
        .iter()
        .map(|c| [table.get_or_insert(&c.start), table.get_or_insert(&c.end)])
        .collect();
    let endpoint_count = table.vertices.len();
    // Points that are not arc end points must be located on arcs; the others are found
    // by the arc-arc tests (an end point inside another arc is a crossing of the two).
    let point_ids: Vec<u32> = points
        .iter()
        .map(|ip| {
            let id = table.get_or_insert(&ip.point.primitive());
            let v = &mut table.vertices[id as usize];
            v.labels.push(ip.label.clone());
            v.structural = false;
            id
        })
        .collect();

    // 3. Per circle: its end points in counter-clockwise order and which of the gaps
    //    between consecutive points its arcs cover.
    let mut rings: Vec<Ring> = circles.iter().map(|_| Ring::default()).collect();
    for (i, c) in canon.iter().enumerate() {
        let ring = &mut rings[c.circle as usize];
        ring.arcs.push(i);
        ring.order.push(ends[i][0]);
        ring.order.push(ends[i][1]);
    }
    for (c, ring) in rings.iter_mut().enumerate() {
        ring.sort(&circles[c], &table.vertices);
        ring.cover(&ends);
    }

    // 4. Crossings: each pair of circles with arcs whose boxes meet is intersected once;
    //    a crossing point counts when an arc of each circle covers it.
    // Boxes of the covered runs of each circle (overlapping arcs collapse into one run).
    let mut run_circle: Vec<u32> = Vec::new();
    let mut run_boxes: Vec<Aabb<f64>> = Vec::new();
    let mut run_ends: Vec<Option<[u32; 2]>> = Vec::new();
    for (c, ring) in rings.iter().enumerate() {
        ring.runs(&circles[c], &table.vertices, |b, ends| {
            run_circle.push(c as u32);
            run_boxes.push(b);
            run_ends.push(ends);
        });
    }
    // A run shorter than a half circle meets another circle only if its end points are
    // not strictly on one side of it (two cheap dot products before any construction).
    let apart = |run: usize, other: &Vec3, vertices: &[Vertex<P>]| -> bool {
        run_ends[run].is_some_and(|[a, b]| {
            let s = dot_sign(other, &vertices[a as usize].point);
            s != Sign::Zero && s == dot_sign(other, &vertices[b as usize].point)
        })
    };
    let pairs = candidate_pairs(&run_boxes);
    stats.candidate_pairs += pairs.len();
    let mut seen: rustc_hash::FxHashSet<(u32, u32)> = rustc_hash::FxHashSet::default();
    let mut extra: Vec<Vec<u32>> = vec![Vec::new(); circles.len()];
    for (i, j) in pairs {
        let (ca, cb) = (run_circle[i], run_circle[j]);
        if ca == cb {
            continue;
        }
        let (na, nb) = (&circles[ca as usize], &circles[cb as usize]);
        if apart(i, nb, &table.vertices)
            || apart(j, na, &table.vertices)
            || !seen.insert((ca.min(cb), ca.max(cb)))
        {
            continue;
        }
        let Some(p) = circle_intersection(na, nb) else {
            continue;
        };
        for q in [p.neg(), p] {
            let (ra, rb) = (&rings[ca as usize], &rings[cb as usize]);
            if ra.covers(na, &q, &table) && rb.covers(nb, &q, &table) {
                let id = table.get_or_insert(&q);
                extra[ca as usize].push(id);
                extra[cb as usize].push(id);
            }
        }
    }
    // Input points (other than arc end points) lying on arcs.
    let lone: Vec<u32> = point_ids
        .iter()
        .copied()
        .filter(|&id| id as usize >= endpoint_count)
        .collect();
    if !lone.is_empty() {
        let pboxes: Vec<Aabb<f64>> = lone
            .iter()
            .map(|&id| point_bbox(&table.vertices[id as usize].point))
            .collect();
        let pairs = sweep_pairs_between(
            &run_boxes,
            &by_low_x(&run_boxes),
            &pboxes,
            &by_low_x(&pboxes),
        );
        for (i, k) in pairs {
            let c = run_circle[i] as usize;
            let id = lone[k];
            let p = table.vertices[id as usize].point.clone();
            if dot_sign(&circles[c], &p) == Sign::Zero && rings[c].covers(&circles[c], &p, &table) {
                extra[c].push(id);
            }
        }
    }

    // 5. Cut each circle at all its points; every covered gap is an edge carrying the
    //    labels of the arcs covering it.
    let mut vertices = table.vertices;
    let mut edges: Vec<Edge<L>> = Vec::new();
    for (c, ring) in rings.iter_mut().enumerate() {
        if !extra[c].is_empty() {
            ring.order.append(&mut extra[c]);
            ring.sort(&circles[c], &vertices);
        }
        ring.emit_edges(c as u32, &canon, &ends, &mut edges);
    }
    // A vertex is real when it is an input point (set above), an end point of a real
    // arc, or where real edges of two different circles meet; a vertex that exists only
    // because a structural arc crosses or ends on a real arc stays structural.
    for (i, c) in canon.iter().enumerate() {
        if c.label.is_some() {
            vertices[ends[i][0] as usize].structural = false;
            vertices[ends[i][1] as usize].structural = false;
        }
    }
    let mut real_circle: Vec<Option<u32>> = vec![None; vertices.len()];
    for e in edges.iter().filter(|e| !e.structural) {
        for v in [e.from as usize, e.to as usize] {
            match real_circle[v] {
                None => real_circle[v] = Some(e.circle),
                Some(c) if c != e.circle => vertices[v].structural = false,
                _ => {}
            }
        }
    }

    // 5. Rotation system.
    for (e, edge) in edges.iter().enumerate() {
        vertices[edge.from as usize].around.push(2 * e as u32);
        vertices[edge.to as usize].around.push(2 * e as u32 + 1);
    }
    for v in vertices.iter_mut() {
        sort_around(&v.point, &mut v.around, &edges, &circles);
    }
    let mut pos_in_around = vec![0u32; edges.len() * 2];
    for v in &vertices {
        for (k, &h) in v.around.iter().enumerate() {
            pos_in_around[h as usize] = k as u32;
        }
    }
    let origin = |h: u32| -> u32 {
        let e = &edges[(h / 2) as usize];
        if h % 2 == 0 {
            e.from
        } else {
            e.to
        }
    };
    // next(h) = the outgoing half-edge at h's target just before twin(h) (clockwise).
    let mut next = vec![0u32; edges.len() * 2];
    for h in 0..(edges.len() * 2) as u32 {
        let twin = h ^ 1;
        let w = origin(twin);
        let around = &vertices[w as usize].around;
        let k = pos_in_around[twin as usize] as usize;
        next[h as usize] = around[(k + around.len() - 1) % around.len()];
    }

    // 6. Cycles.
    let mut cycle_of = vec![u32::MAX; edges.len() * 2];
    let mut cycles = Vec::new();
    for h in 0..(edges.len() * 2) as u32 {
        if cycle_of[h as usize] != u32::MAX {
            continue;
        }
        let c = cycles.len() as u32;
        cycles.push(h);
        let mut g = h;
        loop {
            cycle_of[g as usize] = c;
            g = next[g as usize];
            if g == h {
                break;
            }
        }
    }

    // 7. Faces: cycles joined across structural edges.
    let mut uf = UnionFind::new(cycles.len());
    for (e, edge) in edges.iter().enumerate() {
        if edge.structural {
            uf.union(cycle_of[2 * e] as usize, cycle_of[2 * e + 1] as usize);
        }
    }
    let mut face_ids: HashMap<usize, u32> = HashMap::default();
    let mut faces: Vec<Vec<u32>> = Vec::new();
    let mut face_of_cycle = vec![0u32; cycles.len()];
    for (c, slot) in face_of_cycle.iter_mut().enumerate() {
        let root = uf.find(c);
        let f = *face_ids.entry(root).or_insert_with(|| {
            faces.push(Vec::new());
            (faces.len() - 1) as u32
        });
        faces[f as usize].push(c as u32);
        *slot = f;
    }
    if cycles.is_empty() {
        faces.push(Vec::new());
    }
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

/// The points of one circle in counter-clockwise order around its normal, starting
/// from a reference point, and the coverage of the gaps between them by its arcs.
#[derive(Default)]
struct Ring {
    arcs: Vec<usize>,
    /// Vertex ids, sorted counter-clockwise, without repeats.
    order: Vec<u32>,
    /// Position of each vertex id in `order`.
    pos: HashMap<u32, usize>,
    /// `covered[k]`: some arc covers the open gap from `order[k]` to `order[k + 1]`
    /// (cyclically).
    covered: Vec<bool>,
}

impl Ring {
    /// Sorts `order` counter-clockwise from its first point and removes repeats.
    fn sort<P>(&mut self, n: &Vec3, vertices: &[Vertex<P>]) {
        self.order.sort_unstable();
        self.order.dedup();
        if self.order.is_empty() {
            return;
        }
        let r = vertices[self.order[0] as usize].point.clone();
        let half =
            |q: &Vec3| -> u8 { u8::from(!(q == &r || det3_sign(n, &r, q) == Sign::Positive)) };
        let mut keyed: Vec<(u8, u32)> = self
            .order
            .iter()
            .map(|&v| (half(&vertices[v as usize].point), v))
            .collect();
        keyed.sort_by(|a, b| {
            a.0.cmp(&b.0).then_with(|| {
                match det3_sign(
                    n,
                    &vertices[a.1 as usize].point,
                    &vertices[b.1 as usize].point,
                ) {
                    Sign::Positive => std::cmp::Ordering::Less,
                    Sign::Negative => std::cmp::Ordering::Greater,
                    Sign::Zero => std::cmp::Ordering::Equal,
                }
            })
        });
        self.order = keyed.into_iter().map(|(_, v)| v).collect();
        self.pos = self
            .order
            .iter()
            .enumerate()
            .map(|(k, &v)| (v, k))
            .collect();
    }

    /// The gap indices an arc covers, as (first gap, one past the last), cyclically.
    fn span(&self, ends: &[u32; 2]) -> (usize, usize) {
        (self.pos[&ends[0]], self.pos[&ends[1]])
    }

    fn cover(&mut self, ends: &[[u32; 2]]) {
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
        mut f: impl FnMut(Aabb<f64>, Option<[u32; 2]>),
    ) {
        let len = self.order.len();
        let gap_box = |k: usize| {
            let (a, b) = (
                &vertices[self.order[k] as usize].point,
                &vertices[self.order[(k + 1) % len] as usize].point,
            );
            Arc {
                normal: n.clone(),
                start: a.clone(),
                end: b.clone(),
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
        let short = |a: usize, b: usize| -> Option<[u32; 2]> {
            let (pa, pb) = (self.order[a], self.order[b]);
            (det3_sign(
                n,
                &vertices[pa as usize].point,
                &vertices[pb as usize].point,
            ) == Sign::Positive)
                .then_some([pa, pb])
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
        let r = &table.vertices[self.order[0] as usize].point;
        let half = |x: &Vec3| -> u8 { u8::from(!(x == r || det3_sign(n, r, x) == Sign::Positive)) };
        let hq = half(q);
        // Number of points strictly before q in the counter-clockwise order.
        let before = self.order.partition_point(|&v| {
            let x = &table.vertices[v as usize].point;
            let hx = half(x);
            hx < hq || (hx == hq && det3_sign(n, x, q) == Sign::Positive)
        });
        let gap = if before == 0 { len - 1 } else { before - 1 };
        self.covered[gap]
    }

    /// Edges of this circle: one per covered gap, with the labels of the covering arcs.
    fn emit_edges<L: Clone>(
        &mut self,
        circle: u32,
        canon: &[Canon<L>],
        ends: &[[u32; 2]],
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
    ids: HashMap<Vec3, u32>,
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
    fn get_or_insert(&mut self, p: &Vec3) -> u32 {
        if let Some(&id) = self.ids.get(p) {
            return id;
        }
        self.vertices.push(Vertex {
            point: p.clone(),
            labels: Vec::new(),
            around: Vec::new(),
            structural: true,
        });
        let id = (self.vertices.len() - 1) as u32;
        self.ids.insert(p.clone(), id);
        id
    }
}

/// Sorts outgoing half-edges at `v` counter-clockwise, seen from outside.
///
/// Half-edge `h` leaves along tangent `σ (n × v)` (σ = +1 for forward half-edges).
/// For two of them, `det(v, t1, t2) = σ1 σ2 |v|² det(n1, n2, v)` and
/// `t1 · t2 = σ1 σ2 |v|² (n1 · n2)`, so the comparisons need only the circle normals.
fn sort_around<L>(v: &Vec3, around: &mut [u32], edges: &[Edge<L>], circles: &[Vec3]) {
    if around.len() < 2 {
        return;
    }
    let normal = |h: u32| &circles[edges[(h / 2) as usize].circle as usize];
    let sigma = |h: u32| {
        if h % 2 == 0 {
            Sign::Positive
        } else {
            Sign::Negative
        }
    };
    let cross_sign = |a: u32, b: u32| sigma(a) * sigma(b) * det3_sign(normal(a), normal(b), v);
    let dot_sgn = |a: u32, b: u32| sigma(a) * sigma(b) * dot_sign(normal(a), normal(b));
    let r = around[0];
    // Half 0: angle from the reference in [0, π); half 1: [π, 2π).
    let half = |h: u32| -> u8 {
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
    let mut keyed: Vec<(u8, u32)> = around.iter().map(|&h| (half(h), h)).collect();
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

/// Pairs of boxes that overlap, each `(smaller index, larger)`, ordered by the later box
/// of the pair in the order of low x, then by the earlier one.
///
/// The order matters: the crossings' vertices are numbered in the order the pairs come,
/// and the numbering decides each circle's reference point, hence the order of the edges,
/// half-edges, cycles and faces that plans and pictures follow. The kernel's sweep
/// reports a pair when its earlier box is swept (by the earlier box, then the later);
/// a stable counting sort by the later box's rank puts them in this order in linear time.
fn candidate_pairs(boxes: &[Aabb<f64>]) -> Vec<(usize, usize)> {
    let mut rank = vec![0u32; boxes.len()];
    for (r, &i) in by_low_x(boxes).iter().enumerate() {
        rank[i as usize] = r as u32;
    }
    let mut found: Vec<(u32, u32)> = Vec::new();
    let _ = sweep_pairs(boxes, |earlier, later| {
        found.push((earlier as u32, later as u32));
        ControlFlow::<()>::Continue(())
    });
    // start[r]: where the pairs whose later box has rank r go.
    let mut start = vec![0usize; boxes.len() + 1];
    for &(_, later) in &found {
        start[rank[later as usize] as usize + 1] += 1;
    }
    for r in 0..boxes.len() {
        start[r + 1] += start[r];
    }
    let mut out = vec![(0, 0); found.len()];
    for &(a, b) in &found {
        let slot = &mut start[rank[b as usize] as usize];
        out[*slot] = (a.min(b) as usize, a.max(b) as usize);
        *slot += 1;
    }
    out
}

/// Structural arcs that connect the components of `arr` (empty when connected).
fn connecting_arcs<L, P>(arr: &Arrangement<L, P>) -> Vec<Arc> {
    let n = arr.vertices.len();
    if n <= 1 {
        return Vec::new();
    }
    let mut uf = UnionFind::new(n);
    for e in &arr.edges {
        uf.union(e.from as usize, e.to as usize);
    }
    let mut comp_ids: HashMap<usize, usize> = HashMap::default();
    let mut comps: Vec<Vec<usize>> = Vec::new();
    for v in 0..n {
        let root = uf.find(v);
        let c = *comp_ids.entry(root).or_insert_with(|| {
            comps.push(Vec::new());
            comps.len() - 1
        });
        comps[c].push(v);
    }
    if comps.len() == 1 {
        return Vec::new();
    }
    // Largest component first; each later one joins its nearest vertex among the
    // earlier ones (so the joins form a tree).
    comps.sort_by_key(|c| std::cmp::Reverse(c.len()));
    let unit: Vec<[f64; 3]> = arr.vertices.iter().map(|v| v.point.unit_f64()).collect();
    let mut out = Vec::new();
    let mut connected: Vec<usize> = comps[0].clone();
    for comp in comps.iter().skip(1) {
        let mut best: Option<(f64, usize, usize)> = None;
        for &a in comp {
            for &b in &connected {
                let d = unit[a][0] * unit[b][0] + unit[a][1] * unit[b][1] + unit[a][2] * unit[b][2];
                if best.is_none_or(|(bd, _, _)| d > bd) {
                    let (pa, pb) = (&arr.vertices[a].point, &arr.vertices[b].point);
                    if Arc::between(pa, pb).is_some() {
                        best = Some((d, a, b));
                    }
                }
            }
            if comp.len() * connected.len() > 4_000_000 {
                break; // enough candidates for a huge input; any join is correct
            }
        }
        match best {
            Some((_, a, b)) => {
                out.push(Arc::between(&arr.vertices[a].point, &arr.vertices[b].point).unwrap())
            }
            None => {
                // Every candidate pair is antipodal (e.g. two isolated opposite points):
                // join through a point perpendicular to both.
                let (pa, pb) = (
                    &arr.vertices[comp[0]].point,
                    &arr.vertices[connected[0]].point,
                );
                let m = crate::polygon::perpendicular(pa);
                out.push(Arc::between(pa, &m).unwrap());
                out.push(Arc::between(&m, pb).unwrap());
            }
        }
        connected.extend(comp.iter().copied());
    }
    out
}

/// Disjoint sets with path halving.
pub(crate) struct UnionFind {
    parent: Vec<usize>,
}

impl UnionFind {
    pub(crate) fn new(n: usize) -> UnionFind {
        UnionFind {
            parent: (0..n).collect(),
        }
    }

    pub(crate) fn find(&mut self, mut x: usize) -> usize {
        while self.parent[x] != x {
            self.parent[x] = self.parent[self.parent[x]];
            x = self.parent[x];
        }
        x
    }

    pub(crate) fn union(&mut self, a: usize, b: usize) {
        let (ra, rb) = (self.find(a), self.find(b));
        if ra != rb {
            self.parent[ra] = rb;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[derive(Clone, Debug, PartialEq)]
    struct L(i32);
    impl ArcLabel for L {
        fn flipped(&self) -> L {
            L(-self.0)
        }
    }

    fn arc(a: [i64; 3], b: [i64; 3]) -> InputArc<L> {
        InputArc {
            arc: Arc::between(&Vec3::from(a), &Vec3::from(b)).unwrap(),
            label: Some(L(1)),
        }
    }

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
        let mut s = 12345u64;
        let mut next = |m: u64| {
            s = s
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (s >> 33) % m
        };
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
                assert_eq!(candidate_pairs(&boxes), pairs_by_later_box(&boxes));
            }
        }
    }

    fn euler<Lb: ArcLabel, P: Clone>(a: &Arrangement<Lb, P>) -> i64 {
        a.vertices().len() as i64 - a.edges().len() as i64 + a.faces().len() as i64
    }

    #[test]
    fn octahedron_of_coordinate_circles() {
        // The three coordinate great circles, each as four quarter arcs.
        let axes = [
            [1, 0, 0],
            [0, 1, 0],
            [0, 0, 1],
            [-1, 0, 0],
            [0, -1, 0],
            [0, 0, -1],
        ];
        let mut arcs = Vec::new();
        for (i, a) in axes.iter().enumerate() {
            for b in axes.iter().skip(i + 1) {
                if Arc::between(&Vec3::from(*a), &Vec3::from(*b)).is_some() {
                    arcs.push(arc(*a, *b));
                }
            }
        }
        assert_eq!(arcs.len(), 12);
        let (arr, _) = Arrangement::<L, ()>::build(arcs, vec![]);
        assert_eq!(arr.vertices().len(), 6);
        assert_eq!(arr.edges().len(), 12);
        assert_eq!(arr.faces().len(), 8);
        assert_eq!(euler(&arr), 2);
        for f in arr.faces() {
            assert_eq!(f.len(), 1);
            assert_eq!(arr.cycle_half_edges(f[0]).len(), 3);
        }
    }

    #[test]
    fn overlapping_arcs_and_crossings() {
        // Two overlapping arcs on the equator, one meridian arc crossing both, one arc
        // ending on the equator.
        let arcs = vec![
            arc([1, 0, 0], [0, 1, 0]),
            arc([1, -1, 0], [1, 1, 0]),
            arc([1, 1, -1], [1, 1, 1]),
            arc([2, 1, 0], [2, 1, 5]),
        ];
        let (arr, _) = Arrangement::<L, ()>::build(arcs, vec![]);
        // Vertices: (1,-1,0) (1,0,0) (2,1,0) (1,1,0) (0,1,0) (1,1,-1) (1,1,1) (2,1,5)
        assert_eq!(arr.vertices().len(), 8);
        // Equator pieces: (1,-1)-(1,0), (1,0)-(2,1), (2,1)-(1,1), (1,1)-(0,1): 4;
        // meridian: 2; the spur: 1.
        assert_eq!(arr.edges().len(), 7);
        let shared = arr.edges().iter().filter(|e| e.labels.len() == 2).count();
        assert_eq!(shared, 2);
        assert_eq!(euler(&arr), 2);
        assert_eq!(arr.faces().len(), 1);
    }

    #[test]
    fn disconnected_components_share_a_face() {
        // Two small triangles far apart: three faces (inside each, and the outside with
        // two boundary cycles).
        let tri = |c: [i64; 3], d: [[i64; 3]; 3]| -> Vec<InputArc<L>> {
            let p: Vec<[i64; 3]> = d
                .iter()
                .map(|o| [c[0] * 10 + o[0], c[1] * 10 + o[1], c[2] * 10 + o[2]])
                .collect();
            vec![arc(p[0], p[1]), arc(p[1], p[2]), arc(p[2], p[0])]
        };
        let mut arcs = tri([0, 0, 1], [[1, 0, 0], [0, 1, 0], [-1, -1, 0]]);
        arcs.extend(tri([0, 0, -1], [[1, 0, 0], [-1, -1, 0], [0, 1, 0]]));
        let (arr, stats) = Arrangement::<L, ()>::build(
            arcs,
            vec![InputPoint {
                point: Vec3::new(1, 0, 0),
                label: (),
            }],
        );
        assert!(stats.structural_arcs >= 2);
        assert_eq!(arr.faces().len(), 3);
        let loops: Vec<usize> = (0..3).map(|f| arr.boundary_loops(f).len()).collect();
        assert_eq!(loops.iter().filter(|&&n| n == 2).count(), 1, "{loops:?}");
        assert_eq!(loops.iter().filter(|&&n| n == 1).count(), 2, "{loops:?}");
        let (v, e, f) = arr.real_counts();
        // Real: 6 triangle corners + the isolated point; 6 edges; V - E + F = 1 + C.
        assert_eq!((v, e, f), (7, 6, 3));
    }

    #[test]
    fn many_arcs_through_one_vertex() {
        let mut arcs = Vec::new();
        for (x, y) in [
            (1, 0),
            (1, 1),
            (0, 1),
            (-1, 1),
            (-1, 0),
            (-1, -1),
            (0, -1),
            (1, -1),
        ] {
            arcs.push(arc([0, 0, 1], [x, y, 0]));
        }
        let (arr, _) = Arrangement::<L, ()>::build(arcs, vec![]);
        let pole = arr
            .vertices()
            .iter()
            .find(|v| v.point == Vec3::new(0, 0, 1))
            .unwrap();
        assert_eq!(pole.around.len(), 8);
        // Counter-clockwise seen from above: the directions' angles increase.
        let angles: Vec<f64> = pole
            .around
            .iter()
            .map(|&h| {
                let t = arr.vertices()[arr.target(h) as usize].point.unit_f64();
                t[1].atan2(t[0])
            })
            .collect();
        let k = angles
            .iter()
            .enumerate()
            .min_by(|a, b| a.1.total_cmp(b.1))
            .unwrap()
            .0;
        for i in 1..8 {
            assert!(angles[(k + i) % 8] > angles[(k + i - 1) % 8]);
        }
    }
}
