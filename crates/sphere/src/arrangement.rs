//! The exact arrangement of great-circle arcs on the sphere.
//!
//! Built in one batch, with no sweep and hence no sweep-order predicates (the steps
//! are the functions of `build`):
//! 1. every arc is put on its circle's canonical orientation (labels flipped to match);
//! 2. vertices are made at the arcs' end points and the input points;
//! 3. each circle's end points are sorted along it, and the gaps its arcs cover found;
//! 4. all pairs of circles whose covered runs have floating-point boxes that meet are
//!    intersected exactly (two circles meet at `±(n1 × n2)`; overlapping arcs of one
//!    circle meet at end points), and input points are located on the arcs;
//! 5. each circle is cut at the points found on it, sorted along it, and identical
//!    pieces from different arcs are merged into one edge carrying all their labels;
//! 6. the edges leaving each vertex are sorted counter-clockwise (seen from outside);
//! 7. boundary cycles are traced (faces on the left of half-edges);
//! 8. cycles separated only by structural edges are joined into faces.
//!
//! Degeneracy is the normal case: overlapping arcs, many arcs through one vertex and end
//! points on other arcs all reduce to exact point equality of primitive vectors.
//!
//! A face of the sphere may have several boundary cycles. When the graph is not
//! connected, the builder adds *structural* arcs joining its components and builds
//! again; cycles separated only by structural edges form one face, and a vertex or edge
//! that exists only because of structural arcs is marked as such.
//!
//! Cells are named by typed ids ([`VertexId`], [`EdgeId`], [`HalfEdge`], [`CycleId`],
//! [`FaceId`]); [`HalfEdge::twin`] and [`HalfEdge::edge`] hold the half-edge arithmetic.

mod build;
mod ids;

pub use ids::{CycleId, EdgeId, FaceId, HalfEdge, VertexId};

use crate::arc::Arc;
use apart_kernel::Vec3;
use build::build_once;
use rustc_hash::FxHashMap as HashMap;

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
    pub around: Vec<HalfEdge>,
    /// True when the vertex exists only because of structural arcs.
    pub structural: bool,
}

/// An edge: an open minor arc between two vertices.
#[derive(Clone, Debug)]
pub struct Edge<L> {
    /// Index of its circle in [`Arrangement::circles`].
    pub circle: u32,
    /// The edge runs counter-clockwise around the circle's normal from `from` to `to`.
    pub from: VertexId,
    /// See `from`.
    pub to: VertexId,
    /// Data of the input arcs covering it, oriented like the circle's normal.
    pub labels: Vec<L>,
    /// True when only structural arcs cover it.
    pub structural: bool,
}

/// The arrangement: vertices, edges, half-edges (two per edge, [`EdgeId::forward`] from
/// `from` to `to` and [`EdgeId::backward`]), boundary cycles and faces.
#[derive(Clone, Debug)]
pub struct Arrangement<L, P> {
    circles: Vec<Vec3>,
    vertices: Vec<Vertex<P>>,
    edges: Vec<Edge<L>>,
    next: Vec<HalfEdge>,
    cycle_of: Vec<CycleId>,
    cycles: Vec<HalfEdge>,
    face_of_cycle: Vec<FaceId>,
    faces: Vec<Vec<CycleId>>,
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

/// Builds of at least this many input arcs run their steps on all threads; smaller ones
/// (built by the thousands in other phases) stay on one thread, where rayon's overhead
/// would cost more than it gains. Both paths give the same arrangement, bit for bit.
const PARALLEL_ARCS: usize = 1024;

impl<L: ArcLabel + Send + Sync, P: Clone + Send + Sync> Arrangement<L, P> {
    /// Builds the arrangement of `arcs` and `points`.
    pub fn build(
        arcs: Vec<InputArc<L>>,
        points: Vec<InputPoint<P>>,
    ) -> (Arrangement<L, P>, BuildStats) {
        Self::build_with(arcs, points, None)
    }

    /// [`Arrangement::build`] with the parallel steps forced on or off (`None`: on for
    /// [`PARALLEL_ARCS`] input arcs or more).
    fn build_with(
        arcs: Vec<InputArc<L>>,
        points: Vec<InputPoint<P>>,
        parallel: Option<bool>,
    ) -> (Arrangement<L, P>, BuildStats) {
        let par = |n: usize| parallel.unwrap_or(n >= PARALLEL_ARCS);
        let mut stats = BuildStats {
            arcs: arcs.len(),
            ..Default::default()
        };
        let first = build_once(&arcs, &points, &mut stats, par(arcs.len()));
        let extra = connecting_arcs(&first);
        if extra.is_empty() {
            return (first, stats);
        }
        stats.structural_arcs = extra.len();
        let mut all = arcs;
        all.extend(extra.into_iter().map(|arc| InputArc { arc, label: None }));
        let second = build_once(&all, &points, &mut stats, par(all.len()));
        debug_assert!(
            connecting_arcs(&second).is_empty(),
            "structural arcs left the graph disconnected"
        );
        (second, stats)
    }
}

impl<L, P> Arrangement<L, P> {
    /// Canonical circle normals (first non-zero component positive).
    pub fn circles(&self) -> &[Vec3] {
        &self.circles
    }

    /// The vertices, indexed by [`VertexId::index`].
    pub fn vertices(&self) -> &[Vertex<P>] {
        &self.vertices
    }

    /// The edges, indexed by [`EdgeId::index`].
    pub fn edges(&self) -> &[Edge<L>] {
        &self.edges
    }

    /// Vertex `v`.
    #[inline]
    pub fn vertex(&self, v: VertexId) -> &Vertex<P> {
        &self.vertices[v.index()]
    }

    /// Edge `e`.
    #[inline]
    pub fn edge(&self, e: EdgeId) -> &Edge<L> {
        &self.edges[e.index()]
    }

    /// The ids of all vertices, in order.
    pub fn vertex_ids(&self) -> impl Iterator<Item = VertexId> {
        (0..self.vertices.len()).map(VertexId::new)
    }

    /// The ids of all edges, in order.
    pub fn edge_ids(&self) -> impl Iterator<Item = EdgeId> {
        (0..self.edges.len()).map(EdgeId::new)
    }

    /// All half-edges, in order (an edge's forward one, then its backward one).
    pub fn half_edges(&self) -> impl Iterator<Item = HalfEdge> {
        (0..self.edges.len() * 2).map(HalfEdge::new)
    }

    /// The ids of all faces, in order.
    pub fn face_ids(&self) -> impl Iterator<Item = FaceId> {
        (0..self.faces.len()).map(FaceId::new)
    }

    /// Number of half-edges (twice the edges).
    pub fn half_edge_count(&self) -> usize {
        self.edges.len() * 2
    }

    /// Origin vertex of half-edge `h`.
    #[inline]
    pub fn origin(&self, h: HalfEdge) -> VertexId {
        let e = self.edge(h.edge());
        if h.is_forward() {
            e.from
        } else {
            e.to
        }
    }

    /// Target vertex of half-edge `h`.
    #[inline]
    pub fn target(&self, h: HalfEdge) -> VertexId {
        self.origin(h.twin())
    }

    /// The next half-edge around the face on the left of `h`.
    #[inline]
    pub fn next(&self, h: HalfEdge) -> HalfEdge {
        self.next[h.index()]
    }

    /// The previous half-edge around the face on the left of `h` (`next(prev(h)) == h`):
    /// the twin of the half-edge after `h` counter-clockwise around its origin.
    pub fn prev(&self, h: HalfEdge) -> HalfEdge {
        let around = &self.vertex(self.origin(h)).around;
        let k = around
            .iter()
            .position(|&g| g == h)
            .expect("a half-edge leaves its origin");
        around[(k + 1) % around.len()].twin()
    }

    /// The boundary cycle containing half-edge `h`.
    #[inline]
    pub fn cycle(&self, h: HalfEdge) -> CycleId {
        self.cycle_of[h.index()]
    }

    /// Number of boundary cycles.
    pub fn cycle_count(&self) -> usize {
        self.cycles.len()
    }

    /// One half-edge of cycle `c`.
    pub fn cycle_start(&self, c: CycleId) -> HalfEdge {
        self.cycles[c.index()]
    }

    /// The half-edges of cycle `c` in order.
    pub fn cycle_half_edges(&self, c: CycleId) -> Vec<HalfEdge> {
        let start = self.cycle_start(c);
        let mut out = vec![start];
        let mut h = self.next(start);
        while h != start {
            out.push(h);
            h = self.next(h);
        }
        out
    }

    /// The face of cycle `c`.
    #[inline]
    pub fn face_of_cycle(&self, c: CycleId) -> FaceId {
        self.face_of_cycle[c.index()]
    }

    /// The face on the left of half-edge `h`.
    #[inline]
    pub fn face(&self, h: HalfEdge) -> FaceId {
        self.face_of_cycle(self.cycle(h))
    }

    /// The faces, each a list of boundary cycles (structural edges included). A sphere
    /// with no edges has one face with no cycle.
    pub fn faces(&self) -> &[Vec<CycleId>] {
        &self.faces
    }

    /// The boundary cycles of face `f` (structural edges included).
    pub fn face_cycles(&self, f: FaceId) -> &[CycleId] {
        &self.faces[f.index()]
    }

    /// The half-edge `h` as an arc (oriented along `h`).
    pub fn half_edge_arc(&self, h: HalfEdge) -> Arc {
        let e = self.edge(h.edge());
        let n = &self.circles[e.circle as usize];
        let (a, b) = (&self.vertex(e.from).point, &self.vertex(e.to).point);
        if h.is_forward() {
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
    pub fn edge_arc(&self, e: EdgeId) -> Arc {
        self.half_edge_arc(e.forward())
    }

    /// The real half-edges around face `f` (face on their left), cycle by cycle:
    /// structural ones are left out.
    pub fn real_half_edges(&self, f: FaceId) -> impl Iterator<Item = HalfEdge> + '_ {
        self.face_cycles(f)
            .iter()
            .flat_map(|&c| self.cycle_half_edges(c))
            .filter(|h| !self.edge(h.edge()).structural)
    }

    /// The real boundary of face `f` as closed loops of real half-edges (face on the
    /// left), one loop per boundary component: structural edges are ignored, so a face
    /// with holes has several loops.
    pub fn boundary_loops(&self, f: FaceId) -> Vec<Vec<HalfEdge>> {
        let mut hs: Vec<HalfEdge> = Vec::new();
        for &c in self.face_cycles(f) {
            hs.extend(
                self.cycle_half_edges(c)
                    .into_iter()
                    .filter(|&h| !self.edge(h.edge()).structural),
            );
        }
        let mut seen: rustc_hash::FxHashSet<HalfEdge> = rustc_hash::FxHashSet::default();
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
    fn real_next(&self, h: HalfEdge) -> HalfEdge {
        let around = &self.vertex(self.target(h)).around;
        let k = around
            .iter()
            .position(|&g| g == h.twin())
            .expect("twin at target");
        for step in 1..=around.len() {
            let g = around[(k + around.len() - step) % around.len()];
            if !self.edge(g.edge()).structural {
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

/// Structural arcs that connect the components of `arr` (empty when connected).
fn connecting_arcs<L, P>(arr: &Arrangement<L, P>) -> Vec<Arc> {
    let n = arr.vertices.len();
    if n <= 1 {
        return Vec::new();
    }
    // Each component with edges, its cycles traced on its own rotation system (that of a
    // graph on the sphere), has V - E + F = 2; an isolated vertex has 1. So with edges,
    // V - E + cycles = 2 holds exactly when the graph is connected: the common case,
    // decided without the union-find's pass over all edges.
    if !arr.edges.is_empty() && n + arr.cycles.len() == arr.edges.len() + 2 {
        return Vec::new();
    }
    let mut uf = UnionFind::new(n);
    for e in &arr.edges {
        uf.union(e.from.index(), e.to.index());
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
        let loops: Vec<usize> = arr
            .face_ids()
            .map(|f| arr.boundary_loops(f).len())
            .collect();
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
                let t = arr.vertex(arr.target(h)).point.unit_f64();
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

    /// Asserts that two arrangements are the same, cell by cell and in the same order.
    fn assert_identical<P: Clone + PartialEq + std::fmt::Debug>(
        a: &Arrangement<L, P>,
        b: &Arrangement<L, P>,
    ) {
        assert_eq!(a.circles, b.circles);
        assert_eq!(a.vertices.len(), b.vertices.len());
        for (v, w) in a.vertices.iter().zip(&b.vertices) {
            assert_eq!(v.point, w.point);
            assert_eq!(v.labels, w.labels);
            assert_eq!(v.around, w.around);
            assert_eq!(v.structural, w.structural);
        }
        assert_eq!(a.edges.len(), b.edges.len());
        for (e, f) in a.edges.iter().zip(&b.edges) {
            assert_eq!(
                (e.circle, e.from, e.to, e.structural),
                (f.circle, f.from, f.to, f.structural)
            );
            assert_eq!(e.labels, f.labels);
        }
        assert_eq!(a.next, b.next);
        assert_eq!(a.cycle_of, b.cycle_of);
        assert_eq!(a.cycles, b.cycles);
        assert_eq!(a.face_of_cycle, b.face_of_cycle);
        assert_eq!(a.faces, b.faces);
    }

    #[test]
    fn parallel_build_is_identical_to_sequential() {
        // Short arcs between small integer points (many arcs on one circle, overlapping,
        // sharing end points, ending on other arcs, crossing at end points), long arcs
        // through them, and input points at arc end points and midpoints (on the arcs)
        // and elsewhere. The short arcs leave the graph disconnected, so the second
        // build with structural arcs is compared too.
        let mut rng = apart_testkit::solids::Lcg(0x2545_f491_4f6c_dd1du64);
        let mut next = |m: i64| rng.below(m as u64) as i64;
        let mut point = |r: i64| loop {
            let p = [
                next(2 * r + 1) - r,
                next(2 * r + 1) - r,
                next(2 * r + 1) - r,
            ];
            if p != [0, 0, 0] {
                return p;
            }
        };
        let mut arcs = Vec::new();
        let mut points = Vec::new();
        let mut k = 0;
        while arcs.len() < PARALLEL_ARCS + 500 {
            let a = point(7);
            let long = k % 10 == 0;
            let d = point(if long { 7 } else { 2 });
            let b = [a[0] + d[0], a[1] + d[1], a[2] + d[2]];
            let Some(arc) = Arc::between(&Vec3::from(a), &Vec3::from(b)) else {
                continue;
            };
            k += 1;
            arcs.push(InputArc {
                arc,
                label: (k % 7 != 0).then_some(L(k)),
            });
            if k % 5 == 0 {
                let m = [a[0] + b[0], a[1] + b[1], a[2] + b[2]];
                points.push(InputPoint {
                    point: Vec3::from(m),
                    label: k,
                });
            }
            if k % 11 == 0 {
                points.push(InputPoint {
                    point: Vec3::from(a),
                    label: -k,
                });
            }
        }
        for _ in 0..50 {
            points.push(InputPoint {
                point: Vec3::from(point(9)),
                label: 0,
            });
        }
        let build = |par| Arrangement::build_with(arcs.clone(), points.clone(), par);
        let (seq, seq_stats) = build(Some(false));
        assert!(seq_stats.structural_arcs > 0, "{seq_stats:?}");
        assert!(
            seq.vertices().len() > 2 * arcs.len(),
            "{}",
            seq.vertices().len()
        );
        for par in [None, Some(true)] {
            let (arr, stats) = build(par);
            assert_eq!(
                (stats.candidate_pairs, stats.structural_arcs),
                (seq_stats.candidate_pairs, seq_stats.structural_arcs)
            );
            assert_identical(&seq, &arr);
        }
    }
}
