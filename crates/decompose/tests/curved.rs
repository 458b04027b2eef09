//! Tessellated curved parts (apart-testkit's `curved`, snapped as the loader does):
//! decomposed and verified exactly, with an upper bound on the pieces.

mod common;

use apart_decompose::{decompose, verify, Options};
use apart_testkit::curved as gen;
use common::part;

#[test]
fn socket_of_about_2000_triangles() {
    let n = gen::plug_and_socket_segments(3300);
    let s = part(&gen::plug_and_socket(3300), "socket");
    assert_eq!(s.tris.len(), 12 * n - 4);
    for parallel in [false, true] {
        let d = decompose(
            &s.points,
            &s.tris,
            &Options {
                parallel,
                ..Options::default()
            },
        )
        .unwrap();
        // The floor's two rings and the walls' vertical edges.
        assert_eq!(d.reflex_edges, 4 * n);
        // The disc under the hole and one wedge per wall facet in each of its two steps
        // (no two neighbouring wedges have a convex union).
        assert!(d.pieces.len() <= 2 * n + 1, "{} pieces", d.pieces.len());
        verify(&s.points, &s.tris, &d.pieces).unwrap();
    }
}

#[test]
fn sleeve_and_block() {
    // A tube of 96 segments (a through hole) and the block of a pin in a blind hole.
    let n = 96;
    let tube = gen::lathe(&[[5.0, 10.0], [5.0, 0.0], [8.0, 0.0], [8.0, 10.0]], n, 0.0);
    let s = part(&[("tube".into(), tube)], "tube");
    let d = decompose(&s.points, &s.tris, &Options::default()).unwrap();
    assert_eq!(d.reflex_edges, n);
    assert!(d.pieces.len() <= n, "{} pieces", d.pieces.len());
    verify(&s.points, &s.tris, &d.pieces).unwrap();
    let b = part(&gen::pin_in_hole(n, n, 0.0), "block");
    let d = decompose(&b.points, &b.tris, &Options::default()).unwrap();
    assert_eq!(d.reflex_edges, 2 * n);
    assert!(d.pieces.len() <= n + 1, "{} pieces", d.pieces.len());
    verify(&b.points, &b.tris, &d.pieces).unwrap();
}
