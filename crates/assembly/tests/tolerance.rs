//! A stated tolerance on tessellated fits that interpenetrate by a known depth: a pin of
//! n segments in a hole of the same radius turned by half a segment pokes out by
//! `r (1 - cos(π/n))` (closed form in apart-testkit), so overlaps, depths and the
//! tolerance that makes the assembly valid are all known in advance.

use apart_assembly::{load, LoadOptions, Tolerance};
use apart_testkit::curved::{pin_in_hole, pin_in_hole_depth, write_off_dir, PIN_RADIUS};
use apart_testkit::Scratch;
use std::f64::consts::PI;

fn write(n: usize, m: usize, phase: f64, tag: &str) -> Scratch {
    let dir = Scratch::new(&format!("tol-{tag}"));
    write_off_dir(&pin_in_hole(n, m, phase), &dir).unwrap();
    dir
}

fn with(tolerance: Tolerance) -> LoadOptions {
    LoadOptions {
        tolerance,
        ..LoadOptions::default()
    }
}

#[test]
fn turned_pin_overlaps_by_the_known_depth_and_a_tolerance_of_half_accepts_it() {
    let n = 64;
    let phase = PI / n as f64;
    let depth = pin_in_hole_depth(n, n, phase, PIN_RADIUS);
    assert!(depth > 0.001);
    let dir = write(n, n, phase, "turned");

    // No tolerance: an overlap error that states the depth.
    let plain = load(&dir, &LoadOptions::default()).unwrap();
    assert!(!plain.is_valid());
    let err = plain
        .problems
        .iter()
        .find(|p| p.is_error() && p.message.starts_with("overlaps part"))
        .expect("an overlap error");
    assert!(err.message.contains("depth"), "{}", err.message);

    // Half the depth (and a little): valid, every piece shrunk, the tolerance stated.
    let ok = load(&dir, &with(Tolerance::Fixed(depth / 2.0 * 1.01))).unwrap();
    assert!(ok.is_valid(), "{:?}", ok.problems);
    let t = ok
        .assembly
        .tolerance
        .clone()
        .expect("a tolerance was applied");
    assert_eq!(t.accepted_overlaps, 1);
    // Snapping moves each vertex by at most max_snap_displacement per coordinate, so the
    // measured depth may differ from the closed form by a few of them.
    let snap = ok.assembly.max_snap_displacement;
    assert!(
        (t.deepest_overlap - depth).abs() <= 4.0 * snap + 1e-12,
        "{} vs {depth} (snap {snap})",
        t.deepest_overlap
    );
    for p in &ok.assembly.parts {
        assert_eq!(p.pieces.len(), p.unshrunk_pieces.len());
        // Every shrunk piece lies inside its original piece.
        for (s, o) in p.pieces.iter().zip(&p.unshrunk_pieces) {
            assert!(s.volume() < o.volume());
        }
    }

    // A quarter of the depth is not enough: the error names the depth and a witness.
    let short = load(&dir, &with(Tolerance::Fixed(depth / 4.0))).unwrap();
    assert!(!short.is_valid());
    let err = short.problems.iter().find(|p| p.is_error()).unwrap();
    assert!(
        err.message.contains("deeper than the tolerance"),
        "{}",
        err.message
    );
    assert!(
        err.message.contains("strictly inside both"),
        "{}",
        err.message
    );

    // Auto: the smallest tolerance, between half the depth and a little more.
    let auto = load(&dir, &with(Tolerance::Auto)).unwrap();
    assert!(auto.is_valid(), "{:?}", auto.problems);
    let t = auto.assembly.tolerance.clone().unwrap();
    assert!(t.auto);
    assert!(
        t.eps >= depth / 2.0 && t.eps <= depth / 2.0 * 1.05,
        "{} for depth {depth}",
        t.eps
    );
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn matching_tessellation_needs_no_tolerance_and_auto_says_so() {
    let dir = write(20, 20, 0.0, "matching");
    let plain = load(&dir, &LoadOptions::default()).unwrap();
    assert!(plain.is_valid(), "{:?}", plain.problems);
    let auto = load(&dir, &with(Tolerance::Auto)).unwrap();
    assert!(auto.is_valid());
    assert!(auto.assembly.tolerance.is_none());
    let _ = std::fs::remove_dir_all(&dir);
}

#[test]
fn overlaps_beyond_the_auto_limit_stay_errors() {
    // A pin of 6 segments in a hole of 6 turned by half a segment pokes out by
    // r (1 - cos 30°) ≈ 0.4: far beyond 1e-3 of the assembly's size (16).
    let dir = write(6, 6, PI / 6.0, "coarse");
    let auto = load(&dir, &with(Tolerance::Auto)).unwrap();
    assert!(!auto.is_valid());
    assert!(auto
        .problems
        .iter()
        .any(|p| p.is_error() && p.message.contains("beyond the limit")));
    let _ = std::fs::remove_dir_all(&dir);
}

/// An overlap between parts carries its kind naming the other part (the CLI excuses a
/// part's overlaps by it), with or without a tolerance too small to accept it.
#[test]
fn overlaps_carry_their_kind_and_the_other_part() {
    use apart_assembly::Problem;
    use apart_mesh::ProblemKind;
    let n = 64;
    let phase = PI / n as f64;
    let depth = pin_in_hole_depth(n, n, phase, PIN_RADIUS);
    let dir = write(n, n, phase, "kind");
    let overlap = |p: &Problem| match &p.kind {
        ProblemKind::Overlap { other } => {
            assert!(
                p.message.starts_with(&format!("overlaps part \"{other}\"")),
                "{p:?}"
            );
            true
        }
        _ => false,
    };
    for opts in [LoadOptions::default(), with(Tolerance::Fixed(depth / 4.0))] {
        let l = load(&dir, &opts).unwrap();
        let by_text = l
            .problems
            .iter()
            .filter(|p| p.message.starts_with("overlaps part \""))
            .count();
        assert!(by_text > 0, "{:?}", l.problems);
        assert_eq!(l.problems.iter().filter(|p| overlap(p)).count(), by_text);
    }
}

/// A stated tolerance finer than the input's grid (integer coordinates get the unit
/// grid) refines the grid: the shipped Split Star and peg in the hole take tolerances
/// down to 1e-9 of their size with every piece kept, each shrunk by at least the
/// tolerance and by little more.
#[test]
fn tolerances_finer_than_the_integer_grid_are_honoured() {
    let root = std::path::Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples");
    for name in ["split-star", "peg-in-the-hole"] {
        let plain = load(&root.join(name), &LoadOptions::default()).unwrap();
        assert!(plain.is_valid(), "{name}");
        assert_eq!(
            plain.assembly.grid.exp, 0,
            "{name}: integer input, unit grid"
        );
        let size = plain
            .assembly
            .parts
            .iter()
            .filter_map(|p| p.bbox)
            .flat_map(|b| (0..3).map(move |k| (b.max[k] - b.min[k]) as f64))
            .fold(0.0, f64::max);
        for eps in [1e-2, 1e-3, 1e-6, 1e-9 * size] {
            let l = load(&root.join(name), &with(Tolerance::Fixed(eps))).unwrap();
            assert!(l.is_valid(), "{name} at {eps}: {:#?}", l.problems);
            let a = &l.assembly;
            let t = a.tolerance.as_ref().unwrap();
            assert_eq!(t.eps, eps);
            assert_eq!(t.vanished_pieces, 0, "{name} at {eps}");
            // At least eps, and at most a few grid steps more (the grid is finer than
            // eps / 64, or the finest that 30 bits allow).
            let h = a.grid.step();
            assert!(
                h <= eps / 64.0 || h <= 4.0 * size / 2f64.powi(30),
                "{name}: h {h}"
            );
            assert!(
                t.max_shift >= eps && t.max_shift <= eps + 4.0 * h,
                "{name}: {} vs {eps}",
                t.max_shift
            );
            for (p, q) in a.parts.iter().zip(&plain.assembly.parts) {
                assert_eq!(p.pieces.len(), p.unshrunk_pieces.len(), "{name}/{}", p.name);
                assert!(!q.pieces.is_empty());
            }
        }
    }
}
