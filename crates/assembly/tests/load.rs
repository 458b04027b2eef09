//! Loading folders, multi-object files and manifests, written to temporary folders.
//! Expected values are computed by hand from the boxes written.

use apart_assembly::{load, LoadError, LoadOptions};
use apart_formats::{obj, off, stl, Polygons, RawObject};
use apart_kernel::progress::{phases, Progress};
use apart_kernel::{Int, Rational};
use apart_mesh::Severity;
use apart_testkit::solids::{cuboid_corners, CUBOID_QUADS};
use apart_testkit::Scratch;
use std::path::Path;
use std::sync::{Arc, Mutex};

fn tmp(name: &str) -> Scratch {
    Scratch::new(&format!("load-{}", name))
}

fn boxed(name: Option<&str>, lo: [f64; 3], hi: [f64; 3]) -> RawObject {
    let vertices = cuboid_corners(lo, hi);
    let faces = Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>());
    RawObject {
        name: name.map(str::to_string),
        vertices,
        faces,
    }
}

fn write_off(path: &Path, o: &RawObject) {
    std::fs::create_dir_all(path.parent().unwrap()).unwrap();
    let mut f = std::fs::File::create(path).unwrap();
    off::write(&mut f, &o.vertices, &o.faces).unwrap();
}

fn rat(n: i64, d: i64) -> Rational {
    Rational::new(Int::from(n), Int::from(d))
}

#[test]
fn folder_with_piece_folders() {
    let d = tmp("folder");
    write_off(&d.join("b.off"), &boxed(None, [0.0; 3], [1.0; 3]));
    // Part "a": pieces only (a sub-folder alone), two boxes making a 2 x 1 x 1 bar.
    write_off(
        &d.join("a/p1.off"),
        &boxed(None, [2.0, 0.0, 0.0], [3.0, 1.0, 1.0]),
    );
    write_off(
        &d.join("a/p0.off"),
        &boxed(None, [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
    );
    // Part "c": a mesh with its pieces, the mesh in half-units.
    write_off(
        &d.join("c.off"),
        &boxed(None, [0.0, 2.0, 0.0], [1.0, 2.5, 1.0]),
    );
    write_off(
        &d.join("c/only.off"),
        &boxed(None, [0.0, 2.0, 0.0], [1.0, 2.5, 1.0]),
    );
    std::fs::write(d.join("README.txt"), "not a part").unwrap();
    let l = load(&d, &LoadOptions::default()).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);
    let a = &l.assembly;
    let names: Vec<&str> = a.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["a", "b", "c"]);
    let pa = &a.parts[0];
    assert!(pa.mesh.is_none() && pa.declared_pieces && !pa.convex);
    assert_eq!(
        pa.piece_sources,
        vec![d.join("a/p0.off"), d.join("a/p1.off")]
    );
    assert_eq!(pa.volume_units(&a.grid), rat(2, 1));
    let pb = &a.parts[1];
    assert!(pb.convex && !pb.declared_pieces && pb.pieces.len() == 1);
    assert_eq!(pb.volume_units(&a.grid), rat(1, 1));
    assert_eq!(a.parts[2].volume_units(&a.grid), rat(1, 2));
    assert!(a.grid.exp < 0, "half-units need a fractional grid");
    assert_eq!(a.max_snap_displacement, 0.0);
}

#[test]
fn one_file_with_several_objects() {
    let d = tmp("obj");
    let p = d.join("two.obj");
    let mut f = std::fs::File::create(&p).unwrap();
    obj::write(
        &mut f,
        &[
            boxed(Some("left"), [0.0; 3], [1.0; 3]),
            boxed(Some("right"), [1.0, 0.0, 0.0], [2.0, 1.0, 1.0]),
        ],
    )
    .unwrap();
    drop(f);
    let l = load(&p, &LoadOptions::default()).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);
    let names: Vec<&str> = l.assembly.parts.iter().map(|p| p.name.as_str()).collect();
    assert_eq!(names, ["left", "right"]);
    assert_eq!(l.assembly.name, "two");
    // Overlapping objects of one file are two overlapping parts.
    let p = d.join("clash.obj");
    let mut f = std::fs::File::create(&p).unwrap();
    obj::write(
        &mut f,
        &[
            boxed(Some("x"), [0.0; 3], [2.0; 3]),
            boxed(Some("y"), [1.0; 3], [3.0; 3]),
        ],
    )
    .unwrap();
    drop(f);
    let l = load(&p, &LoadOptions::default()).unwrap();
    assert!(!l.is_valid());
    assert!(
        l.problems[0].message.contains("overlaps part \"y\""),
        "{:?}",
        l.problems
    );
}

#[test]
fn single_binary_stl_part() {
    let d = tmp("stl");
    let b = boxed(None, [0.0; 3], [0.25, 0.5, 1.0]);
    let tris: Vec<[u32; 3]> = b
        .faces
        .iter()
        .flat_map(|f| [[f[0], f[1], f[2]], [f[0], f[2], f[3]]])
        .collect();
    let p = d.join("plate.stl");
    let mut f = std::fs::File::create(&p).unwrap();
    stl::write(&mut f, &b.vertices, &tris).unwrap();
    drop(f);
    let l = load(&p, &LoadOptions::default()).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);
    let part = &l.assembly.parts[0];
    assert_eq!(part.name, "plate");
    assert_eq!(part.volume_units(&l.assembly.grid), rat(1, 8));
    assert_eq!(part.info.as_ref().unwrap().vertices, 8); // the soup was welded
}

#[test]
fn manifest_transforms_and_progress() {
    let d = tmp("manifest");
    write_off(&d.join("bar.off"), &boxed(None, [0.0; 3], [2.0, 1.0, 1.0]));
    std::fs::write(
        d.join("assembly.json"),
        r#"{"name": "bars", "parts": [
            {"name": "x", "mesh": "bar.off", "extra": [1, 2]},
            {"name": "y", "mesh": "bar.off", "transform": {"translation": [0, 0, 1], "rotation": {"axis": [0, 0, 1], "angle_deg": 90}}},
            {"name": "z", "mesh": "bar.off", "transform": {"translation": [0, 5, 0], "rotation": {"quaternion": [0, -0.7071067811865476, 0, 0.7071067811865476]}}},
            {"name": "m", "mesh": "bar.off", "transform": {"matrix": [-1, 0, 0, 0,  0, 1, 0, 0,  0, 0, 1, 2,  0, 0, 0, 1]}}
        ]}"#,
    )
    .unwrap();
    // Each report: the phase, done, total.
    type Reports = Arc<Mutex<Vec<(&'static str, usize, usize)>>>;
    let seen: Reports = Arc::default();
    let s = seen.clone();
    let opts = LoadOptions {
        progress: Progress::with_callback(move |phase, done, total| {
            s.lock().unwrap().push((phase, done, total))
        }),
        ..LoadOptions::default()
    };
    let l = load(&d, &opts).unwrap();
    assert!(l.is_valid(), "{:?}", l.problems);
    let a = &l.assembly;
    assert_eq!(a.name, "bars");
    let bbox = |name: &str| a.part(name).unwrap().bbox.unwrap();
    // Quarter turn about z then up by 1: x in [-1, 0], y in [0, 2], z in [1, 2].
    assert_eq!((bbox("y").min, bbox("y").max), ([-1, 0, 1], [0, 2, 2]));
    // Quarter turn about -y, (x, y, z) -> (-z, y, x), then y + 5.
    assert_eq!((bbox("z").min, bbox("z").max), ([-1, 5, 0], [0, 6, 2]));
    // Mirrored: still a valid outward solid (faces reversed), volume 2.
    assert_eq!((bbox("m").min, bbox("m").max), ([-2, 0, 2], [0, 1, 3]));
    assert_eq!(a.part("m").unwrap().volume_units(&a.grid), rat(2, 1));
    let seen = seen.lock().unwrap();
    for phase in [phases::READING, phases::VALIDATING, phases::OVERLAPS] {
        assert!(
            seen.iter().any(|&(s, d, _)| s == phase && d == 0),
            "{phase} not started"
        );
    }
    assert!(seen.contains(&(phases::VALIDATING, 4, 4)));
    // The one file is read once, for the four parts.
    assert!(seen.contains(&(phases::READING, 1, 1)));
}

#[test]
fn a_raised_stop_flag_stops_loading_with_an_error() {
    let d = tmp("stop");
    write_off(&d.join("a.off"), &boxed(None, [0.0; 3], [1.0; 3]));
    write_off(
        &d.join("b.off"),
        &boxed(None, [2.0, 0.0, 0.0], [3.0, 1.0, 1.0]),
    );
    // Raised before loading: nothing is read.
    let progress = Progress::new();
    progress.request_stop();
    let opts = LoadOptions {
        progress,
        ..LoadOptions::default()
    };
    match load(&d, &opts) {
        Err(e @ LoadError::Stopped { phase }) => {
            assert_eq!(phase, phases::READING);
            assert!(e.to_string().contains("stopped"), "{e}");
        }
        other => panic!("{other:?}"),
    }
    // Raised by the callback once the parts are validated: decomposition is not begun.
    let progress = Progress::new();
    let flag = progress.stop_flag();
    let opts = LoadOptions {
        progress: Progress::with_callback(move |phase, done, total| {
            if phase == phases::VALIDATING && done == total {
                flag.store(true, std::sync::atomic::Ordering::Relaxed);
            }
        })
        .with_stop_flag(progress.stop_flag()),
        ..LoadOptions::default()
    };
    assert!(matches!(
        load(&d, &opts),
        Err(LoadError::Stopped {
            phase: phases::VALIDATING
        })
    ));
}

#[test]
fn grid_spans_all_parts_and_bad_parts_do_not_stop_the_rest() {
    let d = tmp("grid");
    write_off(
        &d.join("big.off"),
        &boxed(None, [1000.0, 0.0, 0.0], [1001.0, 1.0, 1.0]),
    );
    write_off(
        &d.join("small.off"),
        &boxed(None, [0.0; 3], [0.1, 0.1, 0.1]),
    );
    let mut nan = boxed(None, [5.0; 3], [6.0; 3]);
    nan.vertices[2][0] = f64::NAN;
    write_off(&d.join("nan.off"), &nan);
    let l = load(&d, &LoadOptions::default()).unwrap();
    let a = &l.assembly;
    let h = a.grid.step();
    assert!(a.grid.snap(1001.0).unsigned_abs() < 1 << 30);
    assert!(a.max_snap_displacement > 0.0 && a.max_snap_displacement <= h / 2.0);
    assert_eq!(a.parts.len(), 3);
    let errors: Vec<_> = l
        .problems
        .iter()
        .filter(|p| p.severity == Severity::Error)
        .collect();
    assert_eq!(errors.len(), 1, "{errors:?}");
    assert_eq!(errors[0].part.as_deref(), Some("nan"));
    assert!(a.part("big").unwrap().convex && a.part("small").unwrap().convex);
}

#[test]
fn load_errors() {
    let d = tmp("errors");
    assert!(matches!(
        load(&d.join("missing"), &LoadOptions::default()),
        Err(LoadError::NotFound(_))
    ));
    assert!(matches!(
        load(&d, &LoadOptions::default()),
        Err(LoadError::NoParts(_))
    ));
    std::fs::write(d.join("x.step"), "ISO").unwrap();
    assert!(matches!(
        load(&d.join("x.step"), &LoadOptions::default()),
        Err(LoadError::Read { .. })
    ));
    std::fs::write(d.join("assembly.json"), "{\"parts\": 3}").unwrap();
    let e = load(&d, &LoadOptions::default()).unwrap_err().to_string();
    assert!(
        e.contains("assembly.json") && e.contains("\"parts\""),
        "{e}"
    );
    let opts = LoadOptions {
        grid_bits: 99,
        ..LoadOptions::default()
    };
    write_off(&d.join("sub/a.off"), &boxed(None, [0.0; 3], [1.0; 3]));
    assert!(matches!(
        load(&d.join("sub"), &opts),
        Err(LoadError::Grid(_))
    ));
}
