//! Hostile and careless assembly inputs: folder entries that are not regular
//! files, mesh files outside the assembly's folder, thousands of equal part names,
//! relations between parts that snapping changes, every accepted grid size, and parts
//! that the grid collapses. Each must end with a clear error naming the file and the
//! part, or with the right answer; known answers are worked out by hand in each test.

use apart_assembly::{load, LoadError, LoadOptions, Loaded, Problem, Severity, Tolerance};
use apart_formats::{off, Polygons, RawObject};
use apart_testkit::solids::{cuboid_corners, CUBOID_QUADS};
use apart_testkit::Scratch;
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

fn tmp(name: &str) -> Scratch {
    Scratch::new(&format!("hostile-{}", name))
}

/// The box `lo..hi` with outward quadrilateral faces.
fn boxed(lo: [f64; 3], hi: [f64; 3]) -> RawObject {
    let vertices = cuboid_corners(lo, hi);
    let faces = Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>());
    RawObject {
        name: None,
        vertices,
        faces,
    }
}

fn write_off(path: &Path, o: &RawObject) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut f = std::fs::File::create(path).unwrap();
    off::write(&mut f, &o.vertices, &o.faces).unwrap();
}

fn unit_cube(path: &Path, at: f64) {
    write_off(path, &boxed([at, 0.0, 0.0], [at + 1.0, 1.0, 1.0]));
}

/// Runs `load` on another thread so that a reader blocked on a named pipe fails the
/// test instead of hanging it (the bound is generous: this is not a timing test).
fn load_guarded(path: &Path, opts: LoadOptions) -> Result<Loaded, LoadError> {
    let (tx, rx) = mpsc::channel();
    let path = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(load(&path, &opts));
    });
    rx.recv_timeout(Duration::from_secs(300))
        .expect("load blocked on a folder entry")
}

fn errors_of<'a>(l: &'a Loaded, part: &str) -> Vec<&'a Problem> {
    l.problems
        .iter()
        .filter(|p| p.is_error() && p.part.as_deref() == Some(part))
        .collect()
}

fn mkfifo(path: &Path) {
    let ok = std::process::Command::new("mkfifo")
        .arg(path)
        .status()
        .expect("mkfifo runs")
        .success();
    assert!(ok, "mkfifo {}", path.display());
}

#[cfg(unix)]
#[test]
fn folder_entries_that_are_not_regular_files_are_never_opened() {
    let d = tmp("special");
    unit_cube(&d.join("good.off"), 0.0);
    mkfifo(&d.join("pipe.off"));
    mkfifo(&d.join("pipe-without-extension"));
    std::os::unix::fs::symlink("/dev/zero", d.join("zero.stl")).unwrap();
    let _socket = std::os::unix::net::UnixListener::bind(d.join("socket.ply")).unwrap();
    // A folder with a mesh extension is a folder of pieces, and is empty here.
    std::fs::create_dir_all(d.join("folder.obj")).unwrap();
    // A named pipe among a part's pieces.
    unit_cube(&d.join("held/p0.off"), 3.0);
    mkfifo(&d.join("held/p1.off"));

    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    let names: Vec<&str> = l.assembly.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["good", "held", "pipe", "socket", "zero"]);
    assert!(errors_of(&l, "good").is_empty(), "{:?}", l.problems);
    let one = |part: &str| {
        let e = errors_of(&l, part);
        assert_eq!(e.len(), 1, "{part}: {:?}", l.problems);
        e[0].clone()
    };
    let pipe = one("pipe");
    assert_eq!(pipe.file.as_deref(), Some(d.join("pipe.off").as_path()));
    assert_eq!(
        pipe.message,
        "is a named pipe (FIFO), not a regular file; only regular files are read as meshes"
    );
    let socket = one("socket");
    assert!(socket
        .message
        .starts_with("is a socket, not a regular file"));
    let held = one("held");
    assert_eq!(held.file.as_deref(), Some(d.join("held/p1.off").as_path()));
    assert!(held.message.starts_with("is a named pipe (FIFO)"));
    // The link leads outside the folder: refused before anything else is asked.
    let zero = one("zero");
    assert!(
        zero.message.starts_with("lies outside the assembly folder")
            && zero.message.contains("/dev/zero")
            && zero.message.contains("--allow-outside"),
        "{zero}"
    );
    // Allowed outside, /dev/zero is still a device, never read.
    let opts = LoadOptions {
        allow_outside: true,
        ..LoadOptions::default()
    };
    let l = load_guarded(&d, opts).unwrap();
    let zero = errors_of(&l, "zero");
    assert_eq!(zero.len(), 1, "{:?}", l.problems);
    assert_eq!(
        zero[0].message,
        "is a character device, not a regular file; only regular files are read as meshes"
    );

    // Named directly, a pipe or a pipe posing as the manifest is an error at once.
    for path in [d.join("pipe.off"), d.join("pipe-without-extension")] {
        let e = load_guarded(&path, LoadOptions::default()).unwrap_err();
        assert!(matches!(e, LoadError::NotAFile { .. }), "{e}");
        assert!(e.to_string().contains("is a named pipe (FIFO)"), "{e}");
    }
    let m = tmp("special-manifest");
    mkfifo(&m.join("assembly.json"));
    let e = load_guarded(&m, LoadOptions::default()).unwrap_err();
    assert_eq!(
        e.to_string(),
        format!(
            "{}: is a named pipe (FIFO), not a regular file or a folder; only regular files are read",
            m.join("assembly.json").display()
        )
    );
}

#[cfg(unix)]
#[test]
fn manifest_paths_must_stay_inside_the_assembly_folder() {
    let base = tmp("outside");
    let d = base.join("asm");
    unit_cube(&d.join("inside.off"), 0.0);
    unit_cube(&base.join("up.off"), 2.0);
    let elsewhere = tmp("outside-elsewhere");
    unit_cube(&elsewhere.join("abs.off"), 4.0);
    unit_cube(&elsewhere.join("target.off"), 6.0);
    unit_cube(&elsewhere.join("piece.off"), 8.0);
    std::fs::create_dir_all(d.join("sub")).unwrap();
    std::os::unix::fs::symlink(elsewhere.join("target.off"), d.join("link.off")).unwrap();
    std::os::unix::fs::symlink(&elsewhere, d.join("linked-folder")).unwrap();
    // A link that stays inside is fine.
    std::os::unix::fs::symlink(d.join("inside.off"), d.join("alias.off")).unwrap();
    let abs = elsewhere.join("abs.off");
    std::fs::write(
        d.join("assembly.json"),
        format!(
            r#"{{"parts": [
                {{"name": "in", "mesh": "inside.off"}},
                {{"name": "alias", "mesh": "./sub/../alias.off", "transform": {{"translation": [0, 0, 9]}}}},
                {{"name": "up", "mesh": "../up.off"}},
                {{"name": "abs", "mesh": "{}"}},
                {{"name": "link", "mesh": "link.off"}},
                {{"name": "via", "mesh": "cube.off", "pieces": ["linked-folder/piece.off"]}},
                {{"name": "missing", "mesh": "../../nowhere/x.off"}}
            ]}}"#,
            abs.display()
        ),
    )
    .unwrap();
    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    assert!(errors_of(&l, "in").is_empty() && errors_of(&l, "alias").is_empty());
    for (part, file) in [
        ("up", d.join("../up.off")),
        ("abs", abs.clone()),
        ("link", d.join("link.off")),
        ("via", d.join("linked-folder/piece.off")),
        ("missing", d.join("../../nowhere/x.off")),
    ] {
        let e: Vec<_> = errors_of(&l, part)
            .into_iter()
            .filter(|p| p.message.starts_with("lies outside"))
            .collect();
        assert_eq!(e.len(), 1, "{part}: {:?}", l.problems);
        assert_eq!(e[0].file.as_deref(), Some(file.as_path()), "{part}");
        assert!(
            e[0].message
                .starts_with(&format!("lies outside the assembly folder {}", d.display()))
                && e[0]
                    .message
                    .ends_with("must be inside it (--allow-outside lifts this)"),
            "{}",
            e[0]
        );
    }
    // The link is followed to say where it leads.
    let link = &errors_of(&l, "link")[0].message;
    assert!(
        link.contains(&format!(
            "it resolves to {}",
            elsewhere
                .join("target.off")
                .canonicalize()
                .unwrap()
                .display()
        )),
        "{link}"
    );

    // With the option, every file that exists is read ("via" then only lacks cube.off).
    let opts = LoadOptions {
        allow_outside: true,
        ..LoadOptions::default()
    };
    let l = load_guarded(&d, opts).unwrap();
    for part in ["in", "alias", "up", "abs", "link"] {
        assert!(errors_of(&l, part).is_empty(), "{part}: {:?}", l.problems);
    }
    assert!(errors_of(&l, "via")
        .iter()
        .all(|p| p.file.as_deref() == Some(d.join("cube.off").as_path())));
    assert!(errors_of(&l, "missing")[0].message.contains("cannot read"));
}

#[cfg(unix)]
#[test]
fn manifest_naming_a_device_is_refused_even_when_outside_is_allowed() {
    let d = tmp("device");
    unit_cube(&d.join("a.off"), 0.0);
    std::fs::write(
        d.join("assembly.json"),
        r#"{"parts": [{"name": "a", "mesh": "a.off"}, {"name": "z", "mesh": "/dev/zero"}]}"#,
    )
    .unwrap();
    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    assert!(errors_of(&l, "z")[0]
        .message
        .starts_with("lies outside the assembly folder"));
    let opts = LoadOptions {
        allow_outside: true,
        ..LoadOptions::default()
    };
    let l = load_guarded(&d, opts).unwrap();
    let z = errors_of(&l, "z");
    assert_eq!(z.len(), 1, "{:?}", l.problems);
    assert_eq!(z[0].file.as_deref(), Some(Path::new("/dev/zero")));
    assert!(z[0].message.starts_with("is a character device"));
}

/// A manifest that is a symbolic link to one elsewhere, and a piece folder that is a
/// link to a folder elsewhere, are not read (nor listed) unless outside files are allowed.
#[cfg(unix)]
#[test]
fn a_linked_manifest_or_piece_folder_leading_outside_is_not_read() {
    let elsewhere = tmp("linked-elsewhere");
    unit_cube(&elsewhere.join("far.off"), 0.0);
    unit_cube(&elsewhere.join("secret-name.off"), 0.0);
    std::fs::write(
        elsewhere.join("assembly.json"),
        r#"{"parts": [{"name": "far", "mesh": "far.off"}]}"#,
    )
    .unwrap();
    // The manifest of a folder, and a manifest named directly.
    let d = tmp("linked-manifest");
    unit_cube(&d.join("a.off"), 0.0);
    std::os::unix::fs::symlink(elsewhere.join("assembly.json"), d.join("assembly.json")).unwrap();
    for path in [d.to_path_buf(), d.join("assembly.json")] {
        let e = load_guarded(&path, LoadOptions::default()).err().unwrap();
        let e = e.to_string();
        assert!(
            e.contains("assembly.json: lies outside the assembly folder")
                && e.contains("--allow-outside"),
            "{e}"
        );
    }
    let opts = LoadOptions {
        allow_outside: true,
        ..LoadOptions::default()
    };
    assert!(load_guarded(&d, opts).is_ok());

    // A piece folder linked outside: an error of its part, and nothing in it is named.
    let d = tmp("linked-pieces");
    unit_cube(&d.join("a.off"), 0.0);
    unit_cube(&d.join("b.off"), 1.0);
    std::os::unix::fs::symlink(&*elsewhere, d.join("a")).unwrap();
    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    let e = errors_of(&l, "a");
    assert_eq!(e.len(), 1, "{:?}", l.problems);
    assert!(
        e[0].message.contains("lies outside the assembly folder"),
        "{}",
        e[0]
    );
    let all = format!("{:?}{:?}", l.problems, l.skipped);
    assert!(!all.contains("secret-name"), "{all}");
    assert!(errors_of(&l, "b").is_empty());
    // Only the linked folder: the error says why rather than "no parts".
    let d = tmp("linked-only");
    std::os::unix::fs::symlink(&*elsewhere, d.join("a")).unwrap();
    let e = load_guarded(&d, LoadOptions::default())
        .err()
        .unwrap()
        .to_string();
    assert!(
        e.contains("lies outside the assembly folder") && !e.contains("secret"),
        "{e}"
    );
    let opts = LoadOptions {
        allow_outside: true,
        ..LoadOptions::default()
    };
    let l = load_guarded(&d, opts).unwrap();
    assert_eq!(l.assembly.parts.len(), 1);
}

/// A transform with both a matrix and a translation, or with a key apart does not know,
/// would lose part of what was meant: it is an error naming the keys.
#[test]
fn conflicting_or_unknown_transform_keys_are_errors() {
    for (transform, expect) in [
        (
            r#"{"matrix": [1,0,0,5, 0,1,0,0, 0,0,1,0, 0,0,0,1], "translation": [1, 0, 0]}"#,
            "both \"matrix\" and",
        ),
        (
            r#"{"rotation": {"quaternion": [0, 0, 0, 1], "axis": [0, 0, 1], "angle_deg": 90}}"#,
            "both \"quaternion\" and",
        ),
        (
            r#"{"translation": [1, 0, 0], "scale": 2}"#,
            "unknown key \"scale\"",
        ),
        (
            r#"{"rotation": {"axis": [0, 0, 1], "angle_deg": 90, "center": [1, 1, 1]}}"#,
            "unknown key \"center\"",
        ),
    ] {
        let d = tmp("transform-keys");
        unit_cube(&d.join("a.off"), 0.0);
        std::fs::write(
            d.join("assembly.json"),
            format!(r#"{{"parts": [{{"name": "a", "mesh": "a.off", "transform": {transform}}}]}}"#),
        )
        .unwrap();
        let e = load_guarded(&d, LoadOptions::default())
            .err()
            .unwrap()
            .to_string();
        assert!(
            e.contains("assembly.json") && e.contains(expect),
            "{transform}: {e}"
        );
    }
}

/// An ASCII STL of one tetrahedron per name, the k-th at x = 2k.
fn stl_of_tetrahedra(names: &[&str]) -> String {
    let mut s = String::new();
    for (k, name) in names.iter().enumerate() {
        let x = 2.0 * k as f64;
        let v = [
            [x, 0.0, 0.0],
            [x + 1.0, 0.0, 0.0],
            [x, 1.0, 0.0],
            [x, 0.0, 1.0],
        ];
        s.push_str(&format!("solid {name}\n"));
        for f in [[0, 2, 1], [0, 1, 3], [0, 3, 2], [1, 2, 3]] {
            s.push_str(" facet normal 0 0 0\n  outer loop\n");
            for i in f {
                let p = v[i];
                s.push_str(&format!("   vertex {} {} {}\n", p[0], p[1], p[2]));
            }
            s.push_str("  endloop\n endfacet\n");
        }
        s.push_str(&format!("endsolid {name}\n"));
    }
    s
}

#[test]
fn thousands_of_equal_names_are_made_unique_in_linear_time() {
    let d = tmp("names");
    // Small cases keep the names they always had: the first free "-k" from 2 on.
    let p = d.join("few.stl");
    std::fs::write(&p, stl_of_tetrahedra(&["a", "a", "a-2", "a", "b"])).unwrap();
    let l = load(&p, &LoadOptions::default()).unwrap();
    let names: Vec<&str> = l.assembly.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["a", "a-2", "a-2-2", "a-3", "b"]);
    assert!(l.is_valid(), "{:?}", l.problems);

    // 5000 solids named "same" (cubic before: 1500 hung).
    let p = d.join("many.stl");
    std::fs::write(&p, stl_of_tetrahedra(&["same"; 5000])).unwrap();
    let l = load(&p, &LoadOptions::default()).unwrap();
    assert!(l.is_valid());
    assert_eq!(l.assembly.parts.len(), 5000);
    assert_eq!(l.assembly.parts[0].name, "same");
    for (k, part) in l.assembly.parts.iter().enumerate().skip(1) {
        assert_eq!(part.name, format!("same-{}", k + 1));
    }
}

#[test]
fn a_renamed_part_keeps_its_own_problems() {
    // "a.off" holds two separate cubes: parts "a_1" and "a_2". The file "a_1.off" (with
    // a coordinate that is not a number) then becomes "a_1-2", and its error must name
    // it, not the good part "a_1".
    let d = tmp("rename");
    let mut two = boxed([0.0; 3], [1.0; 3]);
    two.append(&boxed([3.0, 0.0, 0.0], [4.0, 1.0, 1.0]));
    write_off(&d.join("a.off"), &two);
    let mut bad = boxed([6.0, 0.0, 0.0], [7.0, 1.0, 1.0]);
    bad.vertices[5][1] = f64::NAN;
    write_off(&d.join("a_1.off"), &bad);
    let l = load(&d, &LoadOptions::default()).unwrap();
    let names: Vec<&str> = l.assembly.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["a_1", "a_2", "a_1-2"]);
    assert!(errors_of(&l, "a_1").is_empty(), "{:?}", l.problems);
    assert!(!errors_of(&l, "a_1-2").is_empty(), "{:?}", l.problems);
    let note = l
        .problems
        .iter()
        .find(|p| p.message.starts_with("renamed"))
        .unwrap();
    assert_eq!(note.part.as_deref(), Some("a_1-2"));
    assert_eq!(
        note.message,
        "renamed from \"a_1\" to \"a_1-2\": another part has that name"
    );
}

/// Two unit-footprint boxes near (1e6, 1e6, 1e6): "a" below, "b" on top of it starting
/// at z = 1e6 + 1 + `gap` (a negative gap is an overlap); "b" is narrower when `narrow`.
fn stacked(name: &str, gap: f64, narrow: bool) -> Scratch {
    let d = tmp(name);
    let b = 1e6;
    write_off(&d.join("a.off"), &boxed([b; 3], [b + 1.0; 3]));
    let (lo, hi) = if narrow {
        (b + 0.25, b + 0.75)
    } else {
        (b, b + 1.0)
    };
    write_off(
        &d.join("b.off"),
        &boxed([lo, lo, b + 1.0 + gap], [hi, hi, b + 2.0]),
    );
    d
}

fn warnings(l: &Loaded) -> Vec<&Problem> {
    l.problems
        .iter()
        .filter(|p| p.severity == Severity::Warning)
        .collect()
}

#[test]
fn snapping_never_changes_a_relation_between_parts_silently() {
    // Default 30-bit grid: coordinates below 2^20 give a step of 2^-10 (about 9.8e-4),
    // so a gap or overlap of 1e-9 or 1e-4 snaps to an exact touch at z = 1e6 + 1.
    let h = 2f64.powi(-10);
    for narrow in [false, true] {
        // 1e-9 apart: they touch after snapping. The input's own rounding at 1e6 (an
        // ulp is 1.2e-10) makes the gap 1.048e-9.
        let l = load(&stacked("gap", 1e-9, narrow), &LoadOptions::default()).unwrap();
        assert_eq!(l.assembly.grid.step(), h);
        assert!(l.is_valid(), "{:?}", l.problems);
        let w = warnings(&l);
        assert_eq!(w.len(), 1, "{w:?}");
        assert_eq!(w[0].part.as_deref(), Some("a"));
        assert!(w[0].element.as_deref().unwrap().starts_with("near ("));
        assert_eq!(
            w[0].message,
            "snapping to the grid (step 9.766e-4) closed a gap of 1.048e-9 between part \"a\" and part \"b\": they touch after snapping; --grid-bits 52 (step 2.328e-10) keeps the gap"
        );
        // Overlapping by 1e-9 and by 1e-4: they only touch after snapping.
        for (depth, text, bits) in [
            (1e-9, "1.048e-9", "--grid-bits 52 (step 2.328e-10)"),
            (1e-4, "1.000e-4", "--grid-bits 36 (step 1.526e-5)"),
        ] {
            let l = load(&stacked("overlap", -depth, narrow), &LoadOptions::default()).unwrap();
            assert!(l.is_valid(), "{:?}", l.problems);
            let w = warnings(&l);
            assert_eq!(w.len(), 1, "{w:?}");
            assert_eq!(
                w[0].message,
                format!(
                    "snapping to the grid (step 9.766e-4) removed an overlap of depth {text} between part \"a\" and part \"b\": they only touch after snapping; {bits} keeps the overlap (reported as an error), and --tolerance {text} then accepts it as contact"
                )
            );
            // The suggested grid keeps the overlap, and reports it.
            let n: u32 = bits[12..14].parse().unwrap();
            let opts = LoadOptions {
                grid_bits: n,
                ..LoadOptions::default()
            };
            let l = load(&stacked("overlap-fine", -depth, narrow), &opts).unwrap();
            assert!(!l.is_valid());
            assert!(l.problems.iter().any(|p| p.is_error()
                && p.part.as_deref() == Some("a")
                && p.message.starts_with("overlaps part \"b\"")));
            assert!(warnings(&l).is_empty(), "{:?}", l.problems);
        }
        // On the finest grid the 1e-9 gap stays a gap: no warning.
        let opts = LoadOptions {
            grid_bits: 52,
            ..LoadOptions::default()
        };
        let l = load(&stacked("gap-fine", 1e-9, narrow), &opts).unwrap();
        assert!(l.is_valid() && l.problems.is_empty(), "{:?}", l.problems);
        // Exact contact and a clear gap are unchanged by snapping: no warning.
        for gap in [0.0, 0.5] {
            let l = load(&stacked("same", gap, narrow), &LoadOptions::default()).unwrap();
            assert!(l.is_valid() && l.problems.is_empty(), "{:?}", l.problems);
        }
    }
}

#[test]
fn snapping_that_opens_a_gap_is_reported() {
    // "a": the block 0..4 x 0..4 whose top rises from z = 1 at x = 0 to z = 1.14 at
    // x = 4. "b": the box 0..1 x 1..2 x 1.035..2, whose bottom edge at x = 1 lies on a's
    // top (1 + 0.14 / 4 = 1.035, to within the rounding of the decimals): they touch
    // along it. On a 7-bit grid (step 1/16, coordinates below 4 < 2^3), 1.14 snaps to
    // 18/16, so a's top is at 1 + 2/64 = 1.03125 at x = 1, while 1.035 snaps to 17/16:
    // after snapping b floats 1/32 above a.
    let d = tmp("opened");
    let mut a = boxed([0.0; 3], [4.0, 4.0, 1.0]);
    for v in [5, 7] {
        a.vertices[v][2] = 1.14;
    }
    write_off(&d.join("a.off"), &a);
    write_off(&d.join("b.off"), &boxed([0.0, 1.0, 1.035], [1.0, 2.0, 2.0]));
    let opts = LoadOptions {
        grid_bits: 7,
        ..LoadOptions::default()
    };
    let l = load(&d, &opts).unwrap();
    assert_eq!(l.assembly.grid.step(), 1.0 / 16.0);
    assert!(l.is_valid(), "{:?}", l.problems);
    let w = warnings(&l);
    assert_eq!(w.len(), 1, "{:?}", l.problems);
    assert_eq!(w[0].part.as_deref(), Some("a"));
    assert_eq!(
        w[0].message,
        "snapping to the grid (step 0.0625) separated part \"a\" and part \"b\", which touched before snapping: they are apart after it; a larger --grid-bits (at most 52) makes the gap smaller"
    );
}

/// A triangular prism: the right triangle (0, 0), (4, 0), (0, 4), from z = 0 to 1.
const WEDGE_OFF: &str = "OFF\n6 5 0\n0 0 0\n4 0 0\n0 4 0\n0 0 1\n4 0 1\n0 4 1\n\
3 0 2 1\n3 3 4 5\n4 0 1 4 3\n4 0 3 5 2\n4 1 2 5 4\n";

#[test]
fn parts_the_snapping_check_finds_disjoint_are_not_reported_and_others_still_are() {
    // "a" is a wedge; "b" a box in the empty corner of a's bounding box, touching a's
    // slanted face along its edge x = y = 2 (its heights are off the grid, so the
    // snapping check runs and finds the two disjoint, while their boxes overlap); "c"
    // a box inside the wedge. Only a and c overlap, with or without a tolerance.
    let d = tmp("disjoint-after-snapping");
    std::fs::write(d.join("a.off"), WEDGE_OFF).unwrap();
    write_off(&d.join("b.off"), &boxed([2.0, 2.0, 0.3], [3.0, 3.0, 0.7]));
    write_off(&d.join("c.off"), &boxed([0.5, 0.5, 0.3], [1.5, 1.5, 0.8]));
    for tolerance in [Tolerance::None, Tolerance::Fixed(1e-3)] {
        let opts = LoadOptions {
            tolerance,
            ..LoadOptions::default()
        };
        let l = load(&d, &opts).unwrap();
        assert!(l.assembly.max_snap_displacement > 0.0);
        let errors: Vec<&Problem> = l.problems.iter().filter(|p| p.is_error()).collect();
        assert_eq!(errors.len(), 1, "{tolerance:?}: {:?}", l.problems);
        assert_eq!(errors[0].part.as_deref(), Some("a"));
        assert!(
            errors[0]
                .message
                .starts_with("overlaps part \"c\" by a depth of"),
            "{}",
            errors[0].message
        );
        assert!(warnings(&l).is_empty(), "{:?}", l.problems);
    }
}

#[test]
fn every_accepted_grid_size_works_and_others_are_refused_up_front() {
    let d = tmp("bits");
    // Binary fractions, so that the answer is exact on every grid from 4 bits on:
    // the largest coordinate 2.5 needs a step of 1/4 at 4 bits (10 < 16).
    write_off(&d.join("a.off"), &boxed([0.0; 3], [1.0; 3]));
    write_off(&d.join("b.off"), &boxed([1.0, 0.0, 0.0], [2.5, 0.5, 0.75]));
    for bits in apart_kernel::grid::MIN_BITS..=apart_kernel::grid::MAX_BITS {
        let opts = LoadOptions {
            grid_bits: bits,
            ..LoadOptions::default()
        };
        let l = load(&d, &opts).unwrap();
        assert!(l.is_valid(), "{bits} bits: {:?}", l.problems);
        let volume = l.assembly.part("b").unwrap().volume_units(&l.assembly.grid);
        assert_eq!(volume.to_string(), "9/16", "{bits} bits");
    }
    assert_eq!(apart_kernel::grid::MAX_BITS, 52);
    for bits in [0, 3, 53, 64, u32::MAX] {
        let opts = LoadOptions {
            grid_bits: bits,
            ..LoadOptions::default()
        };
        // Refused before any file is read: a path that does not exist is not asked about.
        let e = load(&d.join("no such folder"), &opts).unwrap_err();
        assert_eq!(
            e.to_string(),
            format!("cannot choose the grid: grid bits must be between 4 and 52, got {bits}")
        );
    }
}

#[test]
fn a_part_collapsed_by_the_grid_says_why_and_who_set_the_step() {
    // "big" reaches 1e12 < 2^40, so the 30-bit grid has a step of 2^10 = 1024 and the
    // millimetre cube "small" (beside it) snaps to one point.
    let d = tmp("collapse");
    write_off(&d.join("big.off"), &boxed([0.0; 3], [1e12; 3]));
    write_off(&d.join("small.off"), &boxed([-10.0; 3], [-9.999; 3]));
    let l = load(&d, &LoadOptions::default()).unwrap();
    assert_eq!(l.assembly.grid.step(), 1024.0);
    assert!(errors_of(&l, "big").is_empty(), "{:?}", l.problems);
    let e = errors_of(&l, "small");
    assert_eq!(e.len(), 1, "{:?}", l.problems);
    assert_eq!(e[0].file.as_deref(), Some(d.join("small.off").as_path()));
    assert_eq!(
        e[0].message,
        "empty mesh after snapping: every face has zero area on the grid of step 1024 (2^10), which is coarser than this part (0.001 x 0.001 x 0.001); the step is that coarse because part \"big\" has coordinates reaching 1.000e12 and every coordinate must stay below 2^30 steps; a larger --grid-bits (at most 52) makes the step finer"
    );
    // The suggestion works: at 52 bits the step is 2^-12 and the cube stays (4 steps).
    let opts = LoadOptions {
        grid_bits: 52,
        ..LoadOptions::default()
    };
    let l = load(&d, &opts).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);

    // A tiny part far out sets the step itself and collapses: its own message says so.
    let d = tmp("collapse-self");
    write_off(&d.join("far.off"), &boxed([1e12; 3], [1e12 + 1e-3; 3]));
    write_off(&d.join("near.off"), &boxed([0.0; 3], [2000.0; 3]));
    let l = load(&d, &LoadOptions::default()).unwrap();
    assert!(errors_of(&l, "near").is_empty(), "{:?}", l.problems);
    let e = errors_of(&l, "far");
    assert_eq!(e.len(), 1, "{:?}", l.problems);
    assert!(
        e[0].message
            .contains("because its own coordinates reach 1.000e12"),
        "{}",
        e[0]
    );
}

/// Writes a folder with a manifest of one part `a` (`mesh`, pieces `pieces`) and a
/// neighbour `b`, the unit cube at (3, 0, 0).
fn declared(name: &str, mesh: &RawObject, pieces: &[RawObject]) -> Scratch {
    let d = tmp(name);
    write_off(&d.join("a.off"), mesh);
    unit_cube(&d.join("b.off"), 3.0);
    let mut list = Vec::new();
    for (k, p) in pieces.iter().enumerate() {
        write_off(&d.join(format!("a/p{k}.off")), p);
        list.push(format!("\"a/p{k}.off\""));
    }
    std::fs::write(
        d.join("assembly.json"),
        format!(
            r#"{{"parts": [{{"name": "a", "mesh": "a.off", "pieces": [{}]}}, {{"name": "b", "mesh": "b.off"}}]}}"#,
            list.join(", ")
        ),
    )
    .unwrap();
    d
}

/// An L-shaped prism: [0,2]x[0,1] and [0,1]x[1,2], 1 high.
fn l_prism() -> RawObject {
    let p = |x: f64, y: f64, z: f64| [x, y, z];
    let outline = [(0., 0.), (2., 0.), (2., 1.), (1., 1.), (1., 2.), (0., 2.)];
    let mut vertices = Vec::new();
    for z in [0.0, 1.0] {
        for (x, y) in outline {
            vertices.push(p(x, y, z));
        }
    }
    let mut faces: Vec<Vec<u32>> = vec![(0..6).rev().collect(), (6..12).collect()];
    for k in 0..6u32 {
        let j = (k + 1) % 6;
        faces.push(vec![k, j, j + 6, k + 6]);
    }
    RawObject {
        name: None,
        vertices,
        faces: Polygons::from(faces),
    }
}

/// Declared pieces are checked against the part's mesh as solids, not by volume alone:
/// a piece elsewhere, a piece that the surface passes through, and a piece in the notch
/// of a non-convex part (volumes all adding up) are refused, naming the piece.
#[test]
fn declared_pieces_must_lie_within_their_part() {
    let cube = |lo: [f64; 3]| boxed(lo, [lo[0] + 1.0, lo[1] + 1.0, lo[2] + 1.0]);
    let cases = [
        (
            "piece-far",
            cube([0.0; 3]),
            vec![cube([10.0, 10.0, 10.0])],
            "a/p0.off",
            "lies outside the part's mesh",
        ),
        (
            "piece-crossing",
            boxed([0.0; 3], [2.0, 1.0, 1.0]),
            vec![cube([0.0; 3]), boxed([1.5, 0.0, 0.0], [2.5, 1.0, 1.0])],
            "a/p1.off",
            "passes through its interior",
        ),
        (
            "piece-notch",
            l_prism(),
            vec![
                boxed([0.0; 3], [1.0, 2.0, 1.0]),
                boxed([1.0, 1.0, 0.0], [2.0, 2.0, 1.0]),
            ],
            "a/p1.off",
            "lies outside the part's mesh",
        ),
    ];
    for (name, mesh, pieces, piece, expect) in cases {
        let d = declared(name, &mesh, &pieces);
        let l = load_guarded(&d, LoadOptions::default()).unwrap();
        assert!(!l.is_valid(), "{name}");
        let e = errors_of(&l, "a");
        assert_eq!(e.len(), 1, "{name}: {:?}", l.problems);
        assert!(e[0].message.contains(expect), "{name}: {}", e[0]);
        assert!(
            e[0].element
                .as_deref()
                .is_some_and(|el| el.ends_with(piece)),
            "{name}: {:?}",
            e[0]
        );
    }
    // The same meshes with pieces that make them up are accepted.
    for (name, mesh, pieces) in [
        (
            "piece-good-bar",
            boxed([0.0; 3], [2.0, 1.0, 1.0]),
            vec![cube([0.0; 3]), cube([1.0, 0.0, 0.0])],
        ),
        (
            "piece-good-l",
            l_prism(),
            vec![
                boxed([0.0; 3], [2.0, 1.0, 1.0]),
                boxed([0.0, 1.0, 0.0], [1.0, 2.0, 1.0]),
            ],
        ),
    ] {
        let d = declared(name, &mesh, &pieces);
        let l = load_guarded(&d, LoadOptions::default()).unwrap();
        assert!(l.is_valid(), "{name}: {:?}", l.problems);
    }
}

/// Thousands of copies of one piece: the overlaps are listed up to a bound, quickly,
/// rather than every pair.
#[test]
fn many_copies_of_one_piece_are_refused_without_a_quadratic_list() {
    let d = tmp("piece-copies");
    unit_cube(&d.join("a.off"), 0.0);
    unit_cube(&d.join("p.off"), 0.0);
    let list = vec!["\"p.off\""; 10_000].join(", ");
    std::fs::write(
        d.join("assembly.json"),
        format!(r#"{{"parts": [{{"name": "a", "mesh": "a.off", "pieces": [{list}]}}]}}"#),
    )
    .unwrap();
    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    let e = errors_of(&l, "a");
    assert!(e.len() <= 25, "{}", e.len());
    assert!(e.iter().any(|p| p.message.contains("the pieces overlap")));
    assert!(e.iter().any(|p| p.message.contains("the list stops at")));
}

/// Thousands of copies of one part on each other: the overlaps are listed up to a
/// bound, and a tolerance refuses to measure millions of overlapping pairs, both
/// quickly (listing every pair took 91 s and 2 GB for 3,000 copies).
#[test]
fn many_copies_of_one_part_are_refused_without_a_quadratic_list() {
    let d = tmp("part-copies");
    unit_cube(&d.join("a.off"), 0.0);
    let parts: Vec<String> = (0..2500)
        .map(|k| format!(r#"{{"name": "p{k}", "mesh": "a.off"}}"#))
        .collect();
    std::fs::write(
        d.join("assembly.json"),
        format!(r#"{{"parts": [{}]}}"#, parts.join(", ")),
    )
    .unwrap();
    let l = load_guarded(&d, LoadOptions::default()).unwrap();
    let errors: Vec<&Problem> = l.problems.iter().filter(|p| p.is_error()).collect();
    assert_eq!(errors.len(), 101, "{}", errors.len());
    assert!(
        errors[0].message.starts_with("overlaps part \"p1\""),
        "{}",
        errors[0]
    );
    assert_eq!(errors[0].part.as_deref(), Some("p0"));
    assert!(errors[100].message.contains("the list stops at 100"));
    let opts = LoadOptions {
        tolerance: Tolerance::Fixed(0.01),
        ..LoadOptions::default()
    };
    let l = load_guarded(&d, opts).unwrap();
    assert!(!l.is_valid());
    assert!(l.problems.iter().any(|p| p.is_error()
        && p.message
            .starts_with("more than 200000 pairs of parts overlap")));
}
