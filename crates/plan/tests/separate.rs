//! Two-part separation: free regions, sliding arcs and isolated directions.

mod common;

use apart_kernel::Vec3;
use apart_plan::{separate, BlockingRegions};
use common::oracle::Oracle;
use std::f64::consts::PI;

fn sep(parts: &[apart_plan::Part], a: usize, b: usize) -> apart_plan::Separation {
    let regions = BlockingRegions::compute(parts).unwrap();
    let s = separate(&regions, a, b);
    // Every reported direction really separates (oracle).
    let oracle = Oracle::new(parts);
    for f in &s.faces {
        assert!(oracle.free(&[a], &[b], &f.direction));
    }
    for arc in &s.sliding {
        assert!(oracle.free(&[a], &[b], &arc.interior_point()));
    }
    for d in &s.isolated {
        assert!(oracle.free(&[a], &[b], d));
    }
    s
}

#[test]
fn cube_lifted_off_another() {
    let s = sep(&common::stacked_cubes(), 1, 0);
    assert_eq!(s.faces.len(), 1);
    assert!(
        (s.area_fraction() - 0.5).abs() < 1e-9,
        "{}",
        s.area_fraction()
    );
    assert!(s.sliding.is_empty() && s.isolated.is_empty());
    let (d, c) = s.best().unwrap();
    assert!(d.unit_f64()[2] > 0.999, "{d:?}");
    assert!((c - 90.0).abs() < 1e-3);
    // The other way round: the lower hemisphere.
    let s = sep(&common::stacked_cubes(), 0, 1);
    assert!((s.area_fraction() - 0.5).abs() < 1e-9);
    assert!(s.best().unwrap().0.unit_f64()[2] < -0.999);
}

#[test]
fn peg_and_dovetail_have_isolated_directions() {
    let s = sep(&common::peg_in_hole(), 1, 0);
    assert!(s.faces.is_empty() && s.sliding.is_empty());
    assert_eq!(s.isolated, vec![Vec3::new(0, 0, 1)]);
    assert_eq!(s.area_fraction(), 0.0);
    let s = sep(&common::dovetail(), 1, 0);
    assert_eq!(s.isolated, vec![Vec3::new(1, 0, 0)]);
}

#[test]
fn box_in_a_channel_slides_along_an_arc() {
    // Floor below and walls on both sides; the top and both ends are open.
    let channel = vec![
        common::cuboid([0, -2, -1], [10, 2, 0]),
        common::cuboid([0, -2, 0], [10, -1, 2]),
        common::cuboid([0, 1, 0], [10, 2, 2]),
    ];
    let slider = vec![common::cuboid([2, -1, 0], [4, 1, 1])];
    let parts = vec![
        common::part("channel", channel),
        common::part("slider", slider),
    ];
    let s = sep(&parts, 1, 0);
    assert!(s.faces.is_empty());
    assert!(s.isolated.is_empty());
    // The half circle y = 0, z >= 0, from +x over +z to -x.
    assert!(!s.sliding.is_empty());
    let mut angle = 0.0;
    for arc in &s.sliding {
        assert_eq!(
            arc.normal.primitive().to_strings()[1].trim_start_matches('-'),
            "1"
        );
        let (a, b) = (arc.start.unit_f64(), arc.end.unit_f64());
        angle += (a[0] * b[0] + a[1] * b[1] + a[2] * b[2])
            .clamp(-1.0, 1.0)
            .acos();
        assert!(a[2] >= 0.0 && b[2] >= 0.0);
    }
    assert!((angle - PI).abs() < 1e-9, "{angle}");
}

#[test]
fn octant_area() {
    // A cube nested in a corner of three walls leaves through the open octant.
    let walls = vec![
        common::cuboid([-1, -1, -1], [4, 4, 0]),
        common::cuboid([-1, -1, 0], [0, 4, 4]),
        common::cuboid([0, -1, 0], [4, 0, 4]),
    ];
    let cube = vec![common::cuboid([0, 0, 0], [1, 1, 1])];
    let parts = vec![common::part("walls", walls), common::part("cube", cube)];
    let s = sep(&parts, 1, 0);
    assert_eq!(s.faces.len(), 1);
    assert!(
        (s.area_fraction() - 0.125).abs() < 1e-9,
        "{}",
        s.area_fraction()
    );
    let (d, c) = s.best().unwrap();
    let u = d.unit_f64();
    assert!(
        u.iter().all(|x| (x - 1.0 / 3f64.sqrt()).abs() < 1e-3),
        "{u:?}"
    );
    // The octant's centre is arcsin(1/sqrt(3)) = 35.26° from each boundary plane.
    assert!(
        (c - (1.0 / 3f64.sqrt()).asin().to_degrees()).abs() < 1e-3,
        "{c}"
    );
}
