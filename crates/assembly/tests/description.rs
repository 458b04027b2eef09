//! Assemblies described in memory: arrays and files as parts and pieces, loaded as the
//! manifest they stand for would be, with problems that name a file only when there
//! is one.

use apart_assembly::{
    load, load_description, DescribedPart, Description, LoadError, LoadOptions, MeshSource,
};
use apart_formats::transform::Affine;
use apart_formats::{off, Polygons};
use apart_kernel::{Int, Rational};
use apart_testkit::solids::{cuboid_corners, CUBOID_QUADS};
use apart_testkit::Scratch;
use std::path::{Path, PathBuf};

/// A box as arrays of vertices and triangles (outward).
fn box_arrays(lo: [f64; 3], hi: [f64; 3]) -> MeshSource {
    let triangles = CUBOID_QUADS
        .iter()
        .flat_map(|q| [[q[0], q[1], q[2]], [q[0], q[2], q[3]]])
        .collect();
    MeshSource::Arrays {
        vertices: cuboid_corners(lo, hi),
        triangles,
    }
}

/// Writes a box as an OFF file.
fn write_box(path: &Path, lo: [f64; 3], hi: [f64; 3]) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let quads = Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>());
    let mut f = std::fs::File::create(path).unwrap();
    off::write(&mut f, &cuboid_corners(lo, hi), &quads).unwrap();
}

fn described(parts: Vec<DescribedPart>) -> Description {
    Description {
        name: "described".into(),
        parts,
    }
}

#[test]
fn arrays_and_files_make_one_assembly() {
    let d = Scratch::new("description-mixed");
    let file = d.join("elsewhere/b.off");
    write_box(&file, [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    let desc = described(vec![
        DescribedPart::new("a", box_arrays([0.0; 3], [1.0; 3])),
        DescribedPart::new("b", MeshSource::File(file.clone())),
    ]);
    let l = load_description(desc, &LoadOptions::default()).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);
    let a = &l.assembly;
    assert_eq!(a.name, "described");
    assert_eq!(a.parts[0].name, "a");
    assert_eq!(a.parts[0].source, PathBuf::new());
    assert_eq!(a.parts[1].source, file);
    for p in &a.parts {
        assert_eq!(p.volume_units(&a.grid), Rational::from_int(Int::from(1)));
        // Two parts: both decomposed (convex boxes: their one piece).
        assert_eq!(p.pieces.len(), 1);
    }
}

#[test]
fn a_description_loads_as_its_manifest() {
    // The same three parts, one with declared pieces and a transform, from a manifest
    // and from arrays: the same parts, volumes, boxes and problems, but for the files.
    let d = Scratch::new("description-manifest");
    write_box(&d.join("a.off"), [0.0; 3], [1.0, 1.0, 0.5]);
    write_box(&d.join("b.off"), [0.0; 3], [2.0, 1.0, 1.0]);
    write_box(&d.join("b/0.off"), [0.0; 3], [1.0, 1.0, 1.0]);
    write_box(&d.join("b/1.off"), [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]);
    // Overlaps "a" by a quarter: an error naming both.
    write_box(&d.join("c.off"), [0.5, 0.0, 0.0], [1.5, 1.0, 1.0]);
    std::fs::write(
        d.join("assembly.json"),
        r#"{"name": "described", "parts": [
            {"name": "a", "mesh": "a.off"},
            {"name": "b", "mesh": "b.off", "pieces": ["b/0.off", "b/1.off"],
             "transform": {"translation": [0, 3, 0]}},
            {"name": "c", "mesh": "c.off"}]}"#,
    )
    .unwrap();
    let from_manifest = load(&d, &LoadOptions::default()).unwrap();
    let mut b = DescribedPart::new("b", box_arrays([0.0; 3], [2.0, 1.0, 1.0]));
    b.pieces = vec![
        box_arrays([0.0; 3], [1.0, 1.0, 1.0]),
        box_arrays([1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
    ];
    b.transform = Affine::translation([0.0, 3.0, 0.0]);
    let desc = described(vec![
        DescribedPart::new("a", box_arrays([0.0; 3], [1.0, 1.0, 0.5])),
        b,
        DescribedPart::new("c", box_arrays([0.5, 0.0, 0.0], [1.5, 1.0, 1.0])),
    ]);
    let from_arrays = load_description(desc, &LoadOptions::default()).unwrap();
    let (m, a) = (&from_manifest.assembly, &from_arrays.assembly);
    assert_eq!(m.grid, a.grid);
    assert_eq!(m.parts.len(), a.parts.len());
    for (pm, pa) in m.parts.iter().zip(&a.parts) {
        assert_eq!(pm.name, pa.name);
        assert_eq!(pm.volume, pa.volume);
        assert_eq!(pm.bbox, pa.bbox);
        assert_eq!(pm.pieces.len(), pa.pieces.len());
        assert_eq!(pm.declared_pieces, pa.declared_pieces);
        assert!(pa.source.as_os_str().is_empty());
        assert!(pa.piece_sources.iter().all(|p| p.as_os_str().is_empty()));
    }
    let low = m.part("b").unwrap().bbox.unwrap().min;
    assert_eq!(low.map(|c| m.grid.to_units(c)), [0.0, 3.0, 0.0]);
    let strip = |l: &apart_assembly::Loaded| -> Vec<String> {
        l.problems
            .iter()
            .map(|p| {
                let mut p = p.clone();
                p.file = None;
                p.to_string()
            })
            .collect()
    };
    assert_eq!(strip(&from_manifest), strip(&from_arrays));
    assert!(!from_arrays.is_valid());
    assert!(from_arrays.problems.iter().all(|p| p.file.is_none()));
}

#[test]
fn problems_name_the_part_and_element_and_a_file_as_given() {
    let d = Scratch::new("description-problems");
    // A face refers to a vertex that is not there; a piece that is not convex (a box
    // with a corner pushed in) given as arrays; a file that does not parse, named relatively.
    let bad = MeshSource::Arrays {
        vertices: vec![[0.0; 3], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]],
        triangles: vec![[0, 1, 7]],
    };
    let mut pieces = DescribedPart::new("p", box_arrays([5.0; 3], [7.0, 6.0, 6.0]));
    let mut dented = match box_arrays([5.0; 3], [6.0; 3]) {
        MeshSource::Arrays {
            vertices,
            triangles,
        } => (vertices, triangles),
        _ => unreachable!(),
    };
    dented.0[7] = [5.5; 3]; // one corner pushed in: no longer convex
    pieces.pieces = vec![
        box_arrays([5.0; 3], [6.0; 3]),
        MeshSource::Arrays {
            vertices: dented.0,
            triangles: dented.1,
        },
    ];
    std::fs::write(d.join("broken.off"), "OFF\n3 1 0\n0 0 0\n1 0\n").unwrap();
    let relative = d.join("broken.off");
    let desc = described(vec![
        DescribedPart::new("bad", bad),
        pieces,
        DescribedPart::new("broken", MeshSource::File(relative.clone())),
    ]);
    let l = load_description(desc, &LoadOptions::default()).unwrap();
    let of = |part: &str| -> Vec<&apart_assembly::Problem> {
        l.problems
            .iter()
            .filter(|p| p.part.as_deref() == Some(part) && p.is_error())
            .collect()
    };
    let bad = of("bad");
    assert!(!bad.is_empty());
    assert!(bad.iter().all(|p| p.file.is_none()), "{bad:?}");
    assert!(
        bad.iter().any(|p| p.message.contains("vertex 7")),
        "{bad:?}"
    );
    let p = of("p");
    assert!(!p.is_empty());
    assert!(p.iter().all(|x| x.file.is_none()), "{p:?}");
    assert!(
        p.iter().any(|x| x
            .element
            .as_deref()
            .is_some_and(|e| e.starts_with("piece 1"))),
        "{p:?}"
    );
    let broken = of("broken");
    assert_eq!(broken.len(), 1, "{broken:?}");
    assert_eq!(broken[0].file.as_deref(), Some(relative.as_path()));
}

#[test]
fn a_description_breaking_the_manifest_rules_is_refused() {
    let part = |n: &str| DescribedPart::new(n, box_arrays([0.0; 3], [1.0; 3]));
    for (parts, words) in [
        (vec![], "no parts"),
        (vec![part("a"), part("a")], "two parts are named \"a\""),
        (vec![part("")], "non-empty name"),
    ] {
        match load_description(described(parts), &LoadOptions::default()) {
            Err(e @ LoadError::Description(_)) => {
                assert!(e.to_string().contains(words), "{e}")
            }
            other => panic!("{other:?}"),
        }
    }
    // The grid bits are checked first, as for a path.
    let opts = LoadOptions {
        grid_bits: 3,
        ..LoadOptions::default()
    };
    assert!(matches!(
        load_description(described(vec![part("a")]), &opts),
        Err(LoadError::Grid(_))
    ));
}
