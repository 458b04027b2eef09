//! Bad input is an error value, never a panic.

use apart_decompose::{decompose, verify, DecomposeError, Options, VerifyError};
use apart_kernel::Vec3;
use apart_pieces::Polytope;

fn tetra() -> (Vec<Vec3>, Vec<[u32; 3]>) {
    let pts = vec![
        Vec3::new(0, 0, 0),
        Vec3::new(4, 0, 0),
        Vec3::new(0, 4, 0),
        Vec3::new(0, 0, 4),
    ];
    (pts, vec![[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]])
}

#[test]
fn open_inverted_and_degenerate_meshes_are_rejected() {
    let (pts, tris) = tetra();
    let o = Options::default();
    assert!(matches!(
        decompose(&pts, &tris[..3], &o),
        Err(DecomposeError::NotClosed { .. })
    ));
    let inverted: Vec<[u32; 3]> = tris.iter().map(|t| [t[0], t[2], t[1]]).collect();
    assert_eq!(
        decompose(&pts, &inverted, &o).unwrap_err(),
        DecomposeError::NotPositive
    );
    let mut flat = tris.clone();
    flat[0] = [0, 1, 1];
    assert!(matches!(
        decompose(&pts, &flat, &o),
        Err(DecomposeError::DegenerateTriangle { triangle: 0 })
    ));
    let mut bad = tris.clone();
    bad[3] = [1, 2, 9];
    assert!(matches!(
        decompose(&pts, &bad, &o),
        Err(DecomposeError::BadIndex { triangle: 3 })
    ));
    assert_eq!(decompose(&pts, &[], &o).unwrap_err(), DecomposeError::Empty);
    let mut far = pts.clone();
    far[1] = Vec3::new(1 << 41, 0, 0);
    assert!(matches!(
        decompose(&far, &tris, &o),
        Err(DecomposeError::CoordinateTooLarge { point: 1 })
    ));
}

#[test]
fn verify_rejects_wrong_pieces() {
    let (pts, tris) = tetra();
    let whole = Polytope::from_triangles(&pts, &tris).unwrap();
    verify(&pts, &tris, std::slice::from_ref(&whole)).unwrap();
    // The piece twice: overlap (and too much volume).
    assert!(verify(&pts, &tris, &[whole.clone(), whole.clone()]).is_err());
    // A piece sticking out, of the right volume: the tetrahedron moved by one unit.
    let moved = whole.translated(&Vec3::new(1, 0, 0));
    assert!(matches!(
        verify(&pts, &tris, &[moved]),
        Err(VerifyError::CrossesBoundary { .. })
    ));
    // A piece of the right volume entirely outside.
    let away = whole.translated(&Vec3::new(100, 0, 0));
    assert_eq!(
        verify(&pts, &tris, &[away]),
        Err(VerifyError::Outside { piece: 0 })
    );
    assert!(matches!(
        verify(&pts, &tris, &[]),
        Err(VerifyError::VolumeMismatch { .. })
    ));
}
