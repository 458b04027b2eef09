//! `MotionSpace::is_minimal_moving_set` (one set, by reachability inside it) against the
//! enumeration of every minimal moving set of a cell (`minimal_moving_sets`), on every
//! face, edge and vertex status of random boxes in parts, for every subset of the parts.

mod common;

use apart_plan::{BlockingRegions, MotionSpace};

#[test]
fn one_set_agrees_with_the_enumeration() {
    let mut cells = 0;
    let mut minimal = 0;
    for (n, k, seed) in [(8, 4, 3), (12, 5, 11), (16, 6, 29)] {
        let parts = common::random_box_parts(n, k, seed);
        let regions = BlockingRegions::compute(&parts).unwrap();
        let all: Vec<usize> = (0..parts.len()).collect();
        let ms = MotionSpace::build(&regions, &all);
        let st = ms.statuses();
        for status in st.faces.iter().chain(&st.edges).chain(&st.vertices) {
            cells += 1;
            let listed = ms.minimal_moving_sets(status);
            for mask in 1u32..(1 << k) - 1 {
                let set: Vec<usize> = (0..k).filter(|&p| mask >> p & 1 == 1).collect();
                let is = ms.is_minimal_moving_set(status, &set);
                assert_eq!(
                    is,
                    listed.contains(&set),
                    "set {set:?}, minimal sets {listed:?}"
                );
                minimal += usize::from(is);
            }
        }
    }
    // The instances are not trivial: many cells, and minimal sets of several sizes.
    assert!(
        cells > 100 && minimal > cells,
        "{cells} cells, {minimal} minimal"
    );
}
