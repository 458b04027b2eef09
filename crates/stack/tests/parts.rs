//! The test parts (apart-testkit's sheet-metal meshes as placement models) are closed,
//! decompose exactly, and have the volumes of their profiles.

mod common;

use apart_kernel::Vec3;
use apart_testkit::sheet_metal::{ChannelParams, TriangleParams};
use common::parts::{channel, cube, triangle_part};
use common::q;

fn mesh_volume6(points: &[Vec3], tris: &[[u32; 3]]) -> apart_kernel::Int {
    let mut v = apart_kernel::Int::ZERO;
    for t in tris {
        let [a, b, c] = t.map(|i| points[i as usize].clone());
        v += a.dot(&b.cross(&c));
    }
    v
}

#[test]
fn generated_parts_are_closed_and_decompose() {
    for part in [cube(2), channel(), triangle_part()] {
        let (pts, tris) = part.mesh.as_ref().unwrap();
        let v6 = mesh_volume6(pts, tris);
        assert!(v6 > apart_kernel::Int::ZERO, "{}", part.name);
        // The pieces' volume equals the mesh's (divergence theorem).
        assert_eq!(
            *part.volume(),
            apart_kernel::Rational::new(v6, apart_kernel::Int::from(6)),
            "{}",
            part.name
        );
        apart_decompose::verify(pts, tris, &part.pieces).unwrap();
    }
    // A profile thickened vertically by t has area t times its horizontal run.
    let c = ChannelParams::default();
    let run = 2 * c.splay + c.width;
    assert_eq!(*channel().volume(), q(c.thickness * run * c.length));
    let t = TriangleParams::default();
    let run = 2 * (t.hem / 3 + t.foot + t.run);
    assert_eq!(*triangle_part().volume(), q(t.thickness * run * t.length));
    assert_eq!(*cube(3).volume(), q(27));
}
