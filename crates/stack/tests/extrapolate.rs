//! Extrapolated obstacles equal freshly computed ones within each constant-topology
//! interval (paper 004 §IV, Appendix C), for random convex pieces turned about z.

use apart_kernel::{BigPlane, HPoint, Vec3};
use apart_pieces::Polytope;
use apart_stack::extrapolate::{rotate_z, Template};
use apart_stack::obstacle::ObstacleShape;
use apart_stack::orientation::ZRotation;
use proptest::prelude::*;
use std::collections::BTreeSet;

fn hull(points: &[(i64, i64, i64)]) -> Option<Polytope> {
    let pts: Vec<Vec3> = points.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect();
    Polytope::hull_of_points(&pts).ok()
}

fn boxp(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
    Polytope::cuboid(lo, hi).unwrap()
}

/// A canonical form of an obstacle: its vertex set and its facet set.
fn canonical(o: &ObstacleShape) -> (BTreeSet<String>, BTreeSet<String>) {
    let v = o
        .vertices
        .iter()
        .map(|v| {
            format!(
                "{:?}",
                HPoint::from_big(v.to_ints(), o.den.clone()).to_rationals()
            )
        })
        .collect();
    let f = o
        .halfspaces
        .iter()
        .map(|h: &BigPlane| format!("{:?} {:?}", h.n, h.c))
        .collect();
    (v, f)
}

/// Scans θ = k·step; keeps a template from the last fresh computation and extrapolates
/// while it is valid. Returns (extrapolations, fresh computations).
fn scan(fixed: &Polytope, moving: &Polytope, step: f64) -> (usize, usize) {
    let mut template: Option<Template> = None;
    let (mut ex, mut fresh) = (0, 0);
    let mut k = 0;
    while (k as f64) * step < 360.0 {
        let theta = ZRotation::nearest(k as f64 * step, 0.05);
        let truth = ObstacleShape::compute(fixed, &rotate_z(moving, theta)).unwrap();
        match template.as_ref().filter(|t| t.valid_at(theta)) {
            Some(t) => {
                let e = t.extrapolate(theta);
                assert_eq!(
                    canonical(&e),
                    canonical(&truth),
                    "at {} degrees",
                    theta.angle_deg()
                );
                ex += 1;
            }
            None => {
                template = Template::new(fixed, moving, theta, &truth);
                assert!(template.is_some());
                fresh += 1;
            }
        }
        k += 1;
    }
    (ex, fresh)
}

#[test]
fn boxes_extrapolate_between_quarter_turns() {
    // Two boxes: the structure changes only where facet normals line up (every 90°), so
    // a 5° scan extrapolates most orientations.
    let fixed = boxp([0, 0, 0], [7, 3, 2]);
    let moving = boxp([-2, -1, 0], [3, 2, 5]);
    let (ex, fresh) = scan(&fixed, &moving, 5.0);
    assert!(ex >= 50, "{ex} extrapolated, {fresh} fresh");
    assert!(fresh >= 4, "{fresh} fresh");
    let t = Template::new(
        &fixed,
        &moving,
        ZRotation::nearest(20.0, 0.05),
        &ObstacleShape::compute(&fixed, &rotate_z(&moving, ZRotation::nearest(20.0, 0.05)))
            .unwrap(),
    )
    .unwrap();
    let (lo, hi) = t.interval_deg();
    assert!(
        lo <= 0.0 + 1e-9 && hi >= 90.0 - 1e-9,
        "interval ({lo}, {hi})"
    );
}

proptest! {
    #![proptest_config(ProptestConfig { cases: 24, ..ProptestConfig::default() })]

    #[test]
    fn random_pieces(
        a in prop::collection::vec((-6i64..6, -6i64..6, -4i64..4), 5..9),
        b in prop::collection::vec((-6i64..6, -6i64..6, -4i64..4), 5..9),
        step in prop_oneof![Just(3.0f64), Just(7.5), Just(10.0)],
    ) {
        let (Some(fixed), Some(moving)) = (hull(&a), hull(&b)) else {
            return Ok(());
        };
        let (ex, fresh) = scan(&fixed, &moving, step);
        eprintln!("step {step}: {ex} extrapolated, {fresh} fresh");
        prop_assert!(ex + fresh > 0);
    }
}
