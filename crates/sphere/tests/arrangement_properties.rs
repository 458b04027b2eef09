//! Properties of the arrangement on random and degenerate inputs, each checked by brute
//! force written here with the kernel's exact predicates only:
//! - Euler's formula, for the whole graph (structural joins included: connected) and for
//!   the real graph (`V − E + F = 1 + C`, `C` its connected components);
//! - the face cycles: twins, `next` and `prev`, origins and targets, every half-edge in
//!   exactly one cycle and every cycle in exactly one face, the rotation at each vertex
//!   counter-clockwise and with one half-edge per direction that an input arc leaves in;
//! - every input arc covered exactly, by one chain of edges carrying its label;
//! - face, edge and vertex labels of overlaid triangles and points against a classifier
//!   of which inputs contain a point, at random exact points and at a point of every face.
//!
//! The degenerate inputs are bundles around a random point `c`: arcs ending at `c` and
//! passing through it on many great circles, repeated and reversed arcs, arcs overlapping
//! on one circle, arcs ending on other arcs, and the same around the antipode `−c`.

use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::spherical::{arc_position, circle_intersection, ArcPosition};
use apart_kernel::{Sign, Vec3};
use apart_sphere::overlay::{cell_statuses, PointStatus, SideLabel};
use apart_sphere::{Arc, ArcLabel, Arrangement, BitSet, EdgeId, HalfEdge, InputArc, InputPoint};
use proptest::prelude::*;
use std::collections::{HashMap, HashSet};

/// Input arc `k`, flipped when its edge runs against it.
#[derive(Clone, Debug, PartialEq)]
struct Id(usize, bool);

impl ArcLabel for Id {
    fn flipped(&self) -> Id {
        Id(self.0, !self.1)
    }
}

// ---------------------------------------------------------------------------------
// Brute force, with exact kernel predicates only.

/// Whether `p` lies on the closed arc `a`.
fn on_arc(a: &Arc, p: &Vec3) -> bool {
    dot_sign(&a.normal, p) == Sign::Zero
        && arc_position(&a.normal, &a.start, &a.end, p) != ArcPosition::Outside
}

/// Whether two closed minor arcs share a point.
fn arcs_meet(a: &Arc, b: &Arc) -> bool {
    match circle_intersection(&a.normal, &b.normal) {
        None => {
            on_arc(a, &b.start) || on_arc(a, &b.end) || on_arc(b, &a.start) || on_arc(b, &a.end)
        }
        Some(p) => [p.neg(), p].iter().any(|q| on_arc(a, q) && on_arc(b, q)),
    }
}

/// The primitive directions in which the input arcs leave `p` (tangents at `p`).
fn directions_at(arcs: &[Arc], p: &Vec3) -> HashSet<Vec3> {
    let mut out = HashSet::new();
    for a in arcs {
        if dot_sign(&a.normal, p) != Sign::Zero {
            continue;
        }
        let ahead = a.normal.cross(p).primitive(); // counter-clockwise around the normal
        match arc_position(&a.normal, &a.start, &a.end, p) {
            ArcPosition::Outside => {}
            ArcPosition::Start => {
                out.insert(ahead);
            }
            ArcPosition::End => {
                out.insert(ahead.neg());
            }
            ArcPosition::Interior => {
                out.insert(ahead.neg());
                out.insert(ahead);
            }
        }
    }
    out
}

/// Connected components of a graph on `n` nodes.
fn components(n: usize, links: impl Iterator<Item = (usize, usize)>) -> usize {
    let mut parent: Vec<usize> = (0..n).collect();
    fn find(p: &mut [usize], mut x: usize) -> usize {
        while p[x] != x {
            x = p[x];
        }
        x
    }
    for (a, b) in links {
        let (ra, rb) = (find(&mut parent, a), find(&mut parent, b));
        parent[ra] = rb;
    }
    (0..n).filter(|&x| find(&mut parent, x) == x).count()
}

/// A counter-clockwise spherical triangle (`det(p0, p1, p2) > 0`): its open interior is
/// `{x : det(p_i, p_i+1, x) > 0 for all i}`.
#[derive(Clone, Debug)]
struct Triangle([Vec3; 3]);

impl Triangle {
    fn new(a: Vec3, b: Vec3, c: Vec3) -> Option<Triangle> {
        match det3_sign(&a, &b, &c) {
            Sign::Positive => Some(Triangle([a, b, c])),
            Sign::Negative => Some(Triangle([a, c, b])),
            Sign::Zero => None,
        }
    }

    fn normals(&self) -> [Vec3; 3] {
        let p = &self.0;
        [0, 1, 2].map(|i| p[i].cross(&p[(i + 1) % 3]))
    }

    /// Whether `x + εy` is in the open triangle for every small enough `ε > 0`.
    fn contains_perturbed(&self, x: &Vec3, y: &Vec3) -> bool {
        self.normals().iter().all(|n| match dot_sign(n, x) {
            Sign::Positive => true,
            Sign::Negative => false,
            Sign::Zero => dot_sign(n, y) == Sign::Positive,
        })
    }

    fn arcs(&self) -> [Arc; 3] {
        let p = &self.0;
        [0, 1, 2].map(|i| Arc::between(&p[i], &p[(i + 1) % 3]).unwrap())
    }
}

/// Which inputs contain `x + εy`: triangle `t` is map `t`, point `k` map `T + k`.
fn classify(triangles: &[Triangle], points: &[Vec3], x: &Vec3, y: &Vec3) -> BitSet {
    let mut s = BitSet::new(triangles.len() + points.len());
    for (t, tri) in triangles.iter().enumerate() {
        s.set(t, tri.contains_perturbed(x, y));
    }
    for (k, p) in points.iter().enumerate() {
        // A point has measure zero: only an unperturbed query can be on it.
        s.set(
            triangles.len() + k,
            y.is_zero() && p.primitive() == x.primitive(),
        );
    }
    s
}

// ---------------------------------------------------------------------------------
// The checks.

/// Euler's formula, the face cycles and the rotation system of `arr` built from `arcs`
/// (all real) and `points`.
fn check_structure<L: ArcLabel, P: Clone>(
    arr: &Arrangement<L, P>,
    arcs: &[Arc],
    points: &[Vec3],
) -> Result<(), TestCaseError> {
    let (v, e) = (arr.vertices().len(), arr.edges().len());
    // The whole graph is connected (structural arcs join its components).
    prop_assert_eq!(
        components(
            v,
            arr.edges().iter().map(|e| (e.from.index(), e.to.index()))
        ),
        v.min(1)
    );
    let cells = if e == 0 { 1 } else { arr.cycle_count() };
    prop_assert_eq!(v as i64 - e as i64 + cells as i64, 1 + v.min(1) as i64);
    // The real graph: real vertices and those on real edges, real edges, faces.
    let real_v: Vec<usize> = (0..v)
        .filter(|&x| {
            !arr.vertices()[x].structural
                || arr.vertices()[x]
                    .around
                    .iter()
                    .any(|&h| !arr.edge(h.edge()).structural)
        })
        .collect();
    let slot: HashMap<usize, usize> = real_v.iter().enumerate().map(|(k, &x)| (x, k)).collect();
    let real_e: Vec<_> = arr.edges().iter().filter(|e| !e.structural).collect();
    let c = components(
        real_v.len(),
        real_e
            .iter()
            .map(|e| (slot[&e.from.index()], slot[&e.to.index()])),
    );
    prop_assert_eq!(
        real_v.len() as i64 - real_e.len() as i64 + arr.faces().len() as i64,
        1 + c as i64,
        "V - E + F = 1 + C on the real graph"
    );
    let (rv, re, rf) = arr.real_counts();
    prop_assert_eq!((re, rf), (real_e.len(), arr.faces().len()));
    prop_assert!(rv <= real_v.len());

    // Half-edges, twins, next and prev.
    prop_assert_eq!(arr.half_edge_count(), 2 * e);
    let mut next_hit = vec![false; 2 * e];
    for h in arr.half_edges() {
        let t = h.twin();
        prop_assert_ne!(t, h);
        prop_assert_eq!(t.twin(), h);
        prop_assert_eq!(t.edge(), h.edge());
        prop_assert_ne!(t.is_forward(), h.is_forward());
        prop_assert_eq!(arr.origin(t), arr.target(h));
        prop_assert_ne!(arr.origin(h), arr.target(h), "an edge is a minor arc");
        let n = arr.next(h);
        prop_assert_eq!(arr.origin(n), arr.target(h));
        prop_assert_eq!(arr.prev(n), h);
        prop_assert_eq!(arr.next(arr.prev(h)), h);
        prop_assert_eq!(arr.face(n), arr.face(h), "next stays in the face");
        prop_assert!(
            !std::mem::replace(&mut next_hit[n.index()], true),
            "next is a permutation"
        );
        // The half-edge as an arc: from its origin to its target, left side = its face.
        let a = arr.half_edge_arc(h);
        prop_assert_eq!(&a.start, &arr.vertex(arr.origin(h)).point);
        prop_assert_eq!(&a.end, &arr.vertex(arr.target(h)).point);
        prop_assert_eq!(det3_sign(&a.normal, &a.start, &a.end), Sign::Positive);
        prop_assert_eq!(a.normal.neg(), arr.half_edge_arc(t).normal);
    }
    // Every half-edge in exactly one cycle, every cycle in exactly one face.
    let mut in_cycle = vec![0usize; 2 * e];
    for c in (0..arr.cycle_count()).map(apart_sphere::CycleId::new) {
        let hs = arr.cycle_half_edges(c);
        prop_assert!(hs.contains(&arr.cycle_start(c)));
        for &h in &hs {
            in_cycle[h.index()] += 1;
            prop_assert_eq!(arr.cycle(h), c);
            prop_assert_eq!(arr.face(h), arr.face_of_cycle(c));
        }
    }
    prop_assert!(in_cycle.iter().all(|&k| k == 1));
    let mut cycle_faces = vec![0usize; arr.cycle_count()];
    for f in arr.face_ids() {
        for &c in arr.face_cycles(f) {
            cycle_faces[c.index()] += 1;
            prop_assert_eq!(arr.face_of_cycle(c), f);
        }
    }
    prop_assert!(cycle_faces.iter().all(|&k| k == 1));
    prop_assert_eq!(arr.faces().len(), arr.face_ids().count());
    // Structural edges lie inside faces: their two sides are one face.
    for h in arr.half_edges() {
        if arr.edge(h.edge()).structural {
            prop_assert_eq!(arr.face(h), arr.face(h.twin()));
        }
    }

    // The rotation at every vertex: exactly its outgoing half-edges, counter-clockwise
    // (seen from outside), one real half-edge per direction an input arc leaves in.
    let mut around_hit = vec![false; 2 * e];
    for x in arr.vertex_ids() {
        let vert = arr.vertex(x);
        let p = &vert.point;
        for &h in &vert.around {
            prop_assert_eq!(arr.origin(h), x);
            prop_assert!(!std::mem::replace(&mut around_hit[h.index()], true));
        }
        let tangent = |h: HalfEdge| arr.half_edge_arc(h).normal.cross(p);
        let k = vert.around.len();
        if k >= 2 {
            let r = tangent(vert.around[0]);
            let half = |t: &Vec3| match det3_sign(p, &r, t) {
                Sign::Positive => 0,
                Sign::Negative => 1,
                Sign::Zero => u8::from(dot_sign(&r, t) != Sign::Positive),
            };
            for w in vert.around.windows(2) {
                let (a, b) = (tangent(w[0]), tangent(w[1]));
                let (ha, hb) = (half(&a), half(&b));
                prop_assert!(
                    ha < hb || (ha == hb && det3_sign(p, &a, &b) == Sign::Positive),
                    "counter-clockwise around {:?}",
                    p
                );
            }
        }
        let real: HashSet<Vec3> = vert
            .around
            .iter()
            .filter(|&&h| !arr.edge(h.edge()).structural)
            .map(|&h| tangent(h).primitive())
            .collect();
        prop_assert_eq!(
            real.len(),
            vert.around
                .iter()
                .filter(|&&h| !arr.edge(h.edge()).structural)
                .count()
        );
        prop_assert_eq!(real, directions_at(arcs, p), "directions at {:?}", p);
        // Real vertices: end points, input points, and where arcs of two circles meet.
        // (Each circle through p counted by both its normals.)
        let circles: HashSet<Vec3> = arcs
            .iter()
            .filter(|a| on_arc(a, p))
            .flat_map(|a| [a.normal.primitive(), a.normal.primitive().neg()])
            .collect();
        let is_end = arcs
            .iter()
            .any(|a| a.start.primitive() == *p || a.end.primitive() == *p);
        let is_point = points.iter().any(|q| q.primitive() == *p);
        prop_assert_eq!(!vert.structural, is_end || is_point || circles.len() >= 4);
    }
    prop_assert!(around_hit.iter().all(|&b| b));
    // No vertex inside an edge; two edges meet at most at common end points.
    let inside = |a: &Arc, p: &Vec3| {
        dot_sign(&a.normal, p) == Sign::Zero
            && arc_position(&a.normal, &a.start, &a.end, p) == ArcPosition::Interior
    };
    let edge_arcs: Vec<Arc> = arr.edge_ids().map(|x| arr.edge_arc(x)).collect();
    for a in &edge_arcs {
        for vert in arr.vertices() {
            prop_assert!(!inside(a, &vert.point), "{:?} inside {:?}", vert.point, a);
        }
    }
    for (i, a) in edge_arcs.iter().enumerate() {
        for b in &edge_arcs[i + 1..] {
            let common: Vec<Vec3> = match circle_intersection(&a.normal, &b.normal) {
                // One circle: no interior point of one on the other.
                None => {
                    prop_assert!(
                        !on_arc(b, &a.interior_point()) && !on_arc(a, &b.interior_point())
                    );
                    vec![]
                }
                Some(p) => vec![p.neg(), p],
            };
            for q in common.iter().map(Vec3::primitive) {
                if on_arc(a, &q) && on_arc(b, &q) {
                    let ends = |x: &Arc| x.start == q || x.end == q;
                    prop_assert!(ends(a) && ends(b), "{:?} and {:?} cross", a, b);
                }
            }
        }
    }
    Ok(())
}

/// Every input arc is covered exactly: the edges labelled with it form one chain along
/// it from its start to its end, each edge once.
fn check_cover(arr: &Arrangement<Id, ()>, arcs: &[Arc]) -> Result<(), TestCaseError> {
    let mut labelled = vec![0usize; arcs.len()];
    for edge in arr.edges() {
        let mut once = HashSet::new();
        for l in &edge.labels {
            labelled[l.0] += 1;
            prop_assert!(once.insert(l.0), "one label per input arc and edge");
        }
    }
    for (k, a) in arcs.iter().enumerate() {
        let n = a.normal.primitive();
        let (start, end) = (a.start.primitive(), a.end.primitive());
        let mut v = arr
            .vertex_ids()
            .find(|&x| arr.vertex(x).point == start)
            .expect("the start is a vertex");
        let mut steps = 0;
        while arr.vertex(v).point != end {
            let along: Vec<HalfEdge> = arr
                .vertex(v)
                .around
                .iter()
                .copied()
                .filter(|&h| {
                    arr.edge(h.edge()).labels.iter().any(|l| l.0 == k)
                        && arr.half_edge_arc(h).normal == n
                })
                .collect();
            prop_assert_eq!(
                along.len(),
                1,
                "one edge of arc {} leaves {:?}",
                k,
                arr.vertex(v).point
            );
            let h = along[0];
            let sub = arr.half_edge_arc(h);
            prop_assert!(
                on_arc(a, &sub.start) && on_arc(a, &sub.end) && on_arc(a, &sub.interior_point())
            );
            v = arr.target(h);
            steps += 1;
            prop_assert!(steps <= arr.edges().len());
        }
        prop_assert_eq!(steps, labelled[k], "arc {} is its chain", k);
    }
    Ok(())
}

/// A point strictly inside face `f` near its boundary half-edge `h`: `k·m + n` for the
/// midpoint `m` of `h` and its left normal `n`, `k` large enough that the arc from `m`
/// meets no other edge and no vertex.
fn face_point<L, P>(arr: &Arrangement<L, P>, h: HalfEdge) -> Vec3 {
    let a = arr.half_edge_arc(h);
    let m = a.interior_point();
    let mut k = apart_kernel::Int::from(4);
    loop {
        let x = m.scale(&k).add(&a.normal);
        if visible(arr, &x, &m, h.edge()) {
            return x;
        }
        k = &k * apart_kernel::Int::from(16);
    }
}

/// Whether the arc from `x` to `m` (a point inside edge `e`) meets no edge but `e` and
/// no vertex.
fn visible<L, P>(arr: &Arrangement<L, P>, x: &Vec3, m: &Vec3, e: EdgeId) -> bool {
    let Some(probe) = Arc::between(x, m) else {
        return false;
    };
    arr.edge_ids()
        .all(|g| g == e || !arcs_meet(&probe, &arr.edge_arc(g)))
        && arr.vertices().iter().all(|v| !on_arc(&probe, &v.point))
}

/// The face containing `x` (on no circle of `arr`): the side facing `x` of an edge whose
/// point `m` it sees. `None` when it sees none of the points tried.
fn locate<L, P>(arr: &Arrangement<L, P>, x: &Vec3) -> Option<apart_sphere::FaceId> {
    for e in arr.edge_ids() {
        let a = arr.edge_arc(e);
        for (i, j) in [(1, 1), (1, 3), (3, 1)] {
            let m = a.start.scale(&i.into()).add(&a.end.scale(&j.into()));
            if visible(arr, x, &m, e) {
                return Some(match dot_sign(&a.normal, x) {
                    Sign::Positive => arr.face(e.forward()),
                    _ => arr.face(e.backward()),
                });
            }
        }
    }
    None
}

/// Overlays `triangles` (open) and `points` and compares the statuses of every vertex,
/// edge and face (at a point of each and at the located `samples`) with [`classify`].
fn check_labels(
    triangles: &[Triangle],
    points: &[Vec3],
    samples: &[Vec3],
) -> Result<(), TestCaseError> {
    let mut arcs = Vec::new();
    let mut input = Vec::new();
    for (t, tri) in triangles.iter().enumerate() {
        for arc in tri.arcs() {
            arcs.push(arc.clone());
            let label = SideLabel {
                map: t as u32,
                pos: true,
                on: false,
                neg: false,
            };
            input.push(InputArc {
                arc,
                label: Some(label),
            });
        }
    }
    let pts = points
        .iter()
        .enumerate()
        .map(|(k, p)| InputPoint {
            point: p.clone(),
            label: PointStatus {
                map: (triangles.len() + k) as u32,
                on: true,
            },
        })
        .collect();
    let (arr, _) = Arrangement::build(input, pts);
    check_structure(&arr, &arcs, points)?;
    let maps = triangles.len() + points.len();
    let st = cell_statuses(&arr, maps, |x, y| classify(triangles, points, x, y));
    let zero = Vec3::ZERO;
    for v in arr.vertex_ids() {
        let p = &arr.vertex(v).point;
        prop_assert_eq!(
            &st.vertices[v.index()],
            &classify(triangles, points, p, &zero),
            "vertex {:?}",
            p
        );
    }
    for e in arr.edge_ids() {
        let m = arr.edge_arc(e).interior_point();
        prop_assert_eq!(
            &st.edges[e.index()],
            &classify(triangles, points, &m, &zero),
            "edge point {:?}",
            m
        );
    }
    for h in arr.half_edges() {
        let x = face_point(&arr, h);
        let f = arr.face(h);
        prop_assert_eq!(
            &st.faces[f.index()],
            &classify(triangles, points, &x, &zero),
            "face point {:?}",
            x
        );
    }
    for x in samples {
        if x.is_zero() || arr.circles().iter().any(|n| dot_sign(n, x) == Sign::Zero) {
            continue;
        }
        if let Some(f) = locate(&arr, x) {
            prop_assert_eq!(
                &st.faces[f.index()],
                &classify(triangles, points, x, &zero),
                "sample {:?}",
                x
            );
        }
    }
    Ok(())
}

/// Builds `arcs` (labelled by index) and `points`, then checks structure and cover.
fn check_arcs(arcs: &[Arc], points: &[Vec3]) -> Result<(), TestCaseError> {
    let input = arcs
        .iter()
        .enumerate()
        .map(|(k, a)| InputArc {
            arc: a.clone(),
            label: Some(Id(k, false)),
        })
        .collect();
    let pts = points
        .iter()
        .map(|p| InputPoint {
            point: p.clone(),
            label: (),
        })
        .collect();
    let (arr, _) = Arrangement::build(input, pts);
    check_structure(&arr, arcs, points)?;
    check_cover(&arr, arcs)
}

// ---------------------------------------------------------------------------------
// Inputs.

fn small_point(r: i64) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(-r..=r)
        .prop_filter("non-zero", |p| p != &[0, 0, 0])
        .prop_map(Vec3::from)
}

/// Random arcs between small integer points (shared circles, overlaps, ends on arcs).
fn random_arcs() -> impl Strategy<Value = Vec<Arc>> {
    prop::collection::vec((small_point(2), small_point(2)), 1..16)
        .prop_map(|v| v.iter().filter_map(|(a, b)| Arc::between(a, b)).collect())
}

/// A bundle of arcs around `c` and `−c`: ending there, passing through on many circles,
/// repeated, reversed, overlapping on one circle, and ending on each other.
fn bundle() -> impl Strategy<Value = (Vec3, Vec<Arc>)> {
    (
        small_point(2),
        prop::collection::vec((small_point(2), 1i64..=3, 0u8..6), 2..12),
    )
        .prop_map(|(c, spokes)| {
            let mut arcs = Vec::new();
            for (t, m, kind) in spokes {
                let mc = c.scale(&m.into());
                let (p, q) = (mc.add(&t), mc.sub(&t));
                let through = Arc::between(&p, &q); // passes through c
                let group = match kind {
                    0 => vec![Arc::between(&c, &t)], // ends at c
                    // Repeated, the other way round.
                    1 => vec![through.clone(), through.as_ref().map(Arc::reversed)],
                    2 => vec![Arc::between(&c.neg(), &t)], // ends at −c
                    3 => vec![Arc::between(&p.neg(), &q.neg())], // passes through −c
                    // Overlapping on one circle: part of the arc through c.
                    4 => vec![through, Arc::between(&c, &p)],
                    // On that circle beyond p: the two arcs meet end to end.
                    _ => vec![through, Arc::between(&t, &p)],
                };
                arcs.extend(group.into_iter().flatten());
            }
            (c, arcs)
        })
        .prop_filter("some arc", |(_, arcs)| !arcs.is_empty())
}

/// Triangles fanned around `c` (sharing it as a corner), triangles containing `c`, and
/// their images around `−c`.
fn triangle_bundle() -> impl Strategy<Value = (Vec3, Vec<Triangle>)> {
    (
        small_point(2),
        prop::collection::vec((small_point(2), small_point(2), 0u8..3), 1..6),
    )
        .prop_map(|(c, spec)| {
            let mut tris = Vec::new();
            for (a, b, kind) in spec {
                let t = match kind {
                    0 => Triangle::new(c.clone(), a, b),
                    1 => Triangle::new(
                        c.scale(&3.into()).add(&a),
                        c.scale(&3.into()).add(&b),
                        c.scale(&3.into()).sub(&a).sub(&b),
                    ),
                    _ => Triangle::new(c.neg(), a, b),
                };
                tris.extend(t);
            }
            (c, tris)
        })
        .prop_filter("some triangle", |(_, t)| !t.is_empty())
}

fn random_triangles() -> impl Strategy<Value = Vec<Triangle>> {
    prop::collection::vec((small_point(3), small_point(3), small_point(3)), 1..7).prop_map(|v| {
        v.into_iter()
            .filter_map(|(a, b, c)| Triangle::new(a, b, c))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(150))]

    #[test]
    fn random_arcs_have_consistent_cycles_and_are_covered(
        arcs in random_arcs(),
        points in prop::collection::vec(small_point(2), 0..4),
    ) {
        check_arcs(&arcs, &points)?;
    }

    #[test]
    fn bundles_through_one_point_have_consistent_cycles_and_are_covered(
        (c, arcs) in bundle(),
        extra in prop::collection::vec(small_point(2), 0..3),
    ) {
        // Input points at c and −c too (antipodal vertices).
        let mut points = vec![c.clone(), c.neg()];
        points.extend(extra);
        check_arcs(&arcs, &points)?;
        // Many circles through c: its real degree is that of the bundle.
        let input = arcs.iter().enumerate().map(|(k, a)| InputArc { arc: a.clone(), label: Some(Id(k, false)) }).collect();
        let (arr, _) = Arrangement::<Id, ()>::build(input, vec![]);
        if let Some(v) = arr.vertices().iter().find(|v| v.point == c.primitive()) {
            let real = v.around.iter().filter(|&&h| !arr.edge(h.edge()).structural).count();
            prop_assert_eq!(real, directions_at(&arcs, &c.primitive()).len());
        }
    }

    #[test]
    fn random_triangles_have_the_labels_of_brute_force(
        tris in random_triangles(),
        points in prop::collection::vec(small_point(3), 0..3),
        samples in prop::collection::vec(small_point(9), 12),
    ) {
        prop_assume!(!tris.is_empty());
        check_labels(&tris, &points, &samples)?;
    }

    #[test]
    fn triangle_bundles_have_the_labels_of_brute_force(
        (c, tris) in triangle_bundle(),
        samples in prop::collection::vec(small_point(9), 12),
    ) {
        check_labels(&tris, &[c.clone(), c.neg()], &samples)?;
    }
}

#[test]
fn many_great_circles_through_antipodal_points() {
    // Twelve half-meridians from the north pole to the south pole, each as two arcs
    // meeting end to end at the equator, on eight great circles through both poles.
    let n = Vec3::new(0, 0, 1);
    let mut arcs = Vec::new();
    for (x, y) in [
        (1, 0),
        (2, 1),
        (1, 1),
        (1, 2),
        (0, 1),
        (-1, 2),
        (-1, 1),
        (-2, 1),
        (-1, 0),
        (-2, -1),
        (-1, -1),
        (0, -1),
    ] {
        let q = Vec3::new(x, y, 0);
        arcs.push(Arc::between(&n, &q).unwrap());
        arcs.push(Arc::between(&q, &n.neg()).unwrap());
    }
    check_arcs(&arcs, &[n.clone(), n.neg()]).unwrap();
    // Twelve directions at each pole, twelve lunes.
    let (arr, _) = Arrangement::<Id, ()>::build(
        arcs.iter()
            .enumerate()
            .map(|(k, a)| InputArc {
                arc: a.clone(),
                label: Some(Id(k, false)),
            })
            .collect(),
        vec![],
    );
    let pole = arr.vertices().iter().find(|v| v.point == n).unwrap();
    assert_eq!(pole.around.len(), 12);
    assert_eq!(arr.faces().len(), 12);
    // Triangles fanned around the pole with the overlay's labels.
    let tris: Vec<Triangle> = [(1, 0), (0, 1), (-1, 0), (0, -1)]
        .windows(2)
        .filter_map(|w| {
            Triangle::new(
                n.clone(),
                Vec3::new(w[0].0, w[0].1, 0),
                Vec3::new(w[1].0, w[1].1, -1),
            )
        })
        .collect();
    let samples: Vec<Vec3> = (0..40)
        .map(|k| Vec3::new(k % 7 - 3, k % 5 - 2, k % 3 + 1))
        .collect();
    check_labels(&tris, &[n.clone(), n.neg()], &samples).unwrap();
}

#[test]
fn coincident_and_overlapping_arcs_on_one_circle() {
    // The equator covered by overlapping, repeated and reversed arcs, and arcs ending on it.
    let p = |x, y, z| Vec3::new(x, y, z);
    let arcs = vec![
        Arc::between(&p(1, 0, 0), &p(0, 1, 0)).unwrap(),
        Arc::between(&p(0, 1, 0), &p(1, 0, 0)).unwrap(),
        Arc::between(&p(1, -1, 0), &p(1, 1, 0)).unwrap(),
        Arc::between(&p(1, -1, 0), &p(1, 1, 0)).unwrap(),
        Arc::between(&p(2, 1, 0), &p(-1, 1, 0)).unwrap(),
        Arc::between(&p(-1, 0, 0), &p(0, -1, 0)).unwrap(),
        Arc::between(&p(1, 1, 0), &p(1, 1, 3)).unwrap(),
        Arc::between(&p(-1, -1, -2), &p(-1, -1, 0)).unwrap(),
    ];
    check_arcs(&arcs, &[p(0, 0, 1), p(-1, 0, 0)]).unwrap();
}
