//! The arrangement against brute force, on random arcs between small integer points
//! (many arcs share circles, overlap, end on each other and cross at end points).

use apart_kernel::spherical::ArcPosition;
use apart_kernel::Vec3;
use apart_sphere::{Arc, ArcLabel, Arrangement, EdgeId, InputArc, InputPoint};
use proptest::prelude::*;

#[derive(Clone, Debug, PartialEq)]
struct Id(usize, bool);

impl ArcLabel for Id {
    fn flipped(&self) -> Id {
        Id(self.0, !self.1)
    }
}

fn arcs() -> impl Strategy<Value = Vec<Arc>> {
    prop::collection::vec(
        (
            prop::array::uniform3(-2i64..=2),
            prop::array::uniform3(-2i64..=2),
        ),
        1..25,
    )
    .prop_map(|v| {
        v.into_iter()
            .filter_map(|(a, b)| Arc::between(&Vec3::from(a), &Vec3::from(b)))
            .collect()
    })
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(200))]

    #[test]
    fn edges_match_brute_force(input in arcs(), pts in prop::collection::vec(prop::array::uniform3(-2i64..=2), 0..4)) {
        prop_assume!(!input.is_empty());
        let points: Vec<InputPoint<()>> = pts.iter().map(|&p| Vec3::from(p)).filter(|p| !p.is_zero()).map(|point| InputPoint { point, label: () }).collect();
        let labelled: Vec<InputArc<Id>> = input.iter().enumerate().map(|(k, a)| InputArc { arc: a.clone(), label: Some(Id(k, false)) }).collect();
        let (arr, _) = Arrangement::build(labelled, points.clone());
        // Connected (structural joins included): V - E + (boundary cycles) = 2.
        let (v, e, f) = (arr.vertices().len() as i64, arr.edges().len() as i64, arr.cycle_count() as i64);
        prop_assert_eq!(v - e + f, 2);
        // Real vertices: input points, end points, and meetings of real edges of two circles.
        for vert in arr.vertices() {
            let is_end = input.iter().any(|a| a.start.primitive() == vert.point || a.end.primitive() == vert.point);
            let is_point = points.iter().any(|p| p.point.primitive() == vert.point);
            let circles: std::collections::HashSet<u32> = vert.around.iter().map(|&h| arr.edge(h.edge())).filter(|e| !e.structural).map(|e| e.circle).collect();
            prop_assert_eq!(!vert.structural, is_end || is_point || circles.len() >= 2, "vertex {:?}", vert.point);
        }
        for (k, edge) in arr.edges().iter().enumerate() {
            let arc = arr.edge_arc(EdgeId::new(k));
            let mid = arc.interior_point();
            // Input arcs containing the edge's midpoint (open or closed: an edge is cut at
            // every end point, so the midpoint is never an end point of an input arc).
            let mut want: Vec<usize> = input
                .iter()
                .enumerate()
                .filter(|(_, a)| matches!(a.locate(&mid), Some(ArcPosition::Interior)))
                .map(|(k, _)| k)
                .collect();
            let mut got: Vec<usize> = edge.labels.iter().map(|l| l.0).collect();
            want.sort();
            got.sort();
            prop_assert_eq!(&got, &want, "edge {:?}", arc);
            prop_assert_eq!(edge.structural, want.is_empty());
            // No vertex lies inside an edge.
            for vert in arr.vertices() {
                prop_assert_ne!(arc.locate(&vert.point), Some(ArcPosition::Interior));
            }
            // Label orientation: flipped exactly when the input arc runs against the edge.
            for l in &edge.labels {
                let same = apart_kernel::predicates::dot_sign(&input[l.0].normal, &arc.normal) == apart_kernel::Sign::Positive;
                prop_assert_eq!(l.1, !same);
            }
        }
        // Every input end point and input point is a vertex.
        for a in &input {
            for p in [&a.start, &a.end] {
                prop_assert!(arr.vertices().iter().any(|v| v.point == p.primitive()));
            }
        }
        for p in &points {
            prop_assert!(arr.vertices().iter().any(|v| v.point == p.point.primitive()));
        }
    }
}
