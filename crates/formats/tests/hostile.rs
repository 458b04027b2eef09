//! Hostile and careless inputs through the public reading API: every case
//! ends quickly with a clear error naming the file and the element, or reads right.
//! The inputs are built here, small; nothing big is committed.

use apart_formats::{
    read_bytes, read_file, read_file_with, stl, Format, ReadOptions, MAX_FILE_BYTES,
};
use apart_testkit::Scratch;
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("fhostile-{}", name))
}

/// `read_file(path)`'s error message, failing the test if reading takes more than ten
/// seconds (a blocked open of a FIFO would otherwise hang the suite).
fn error_within(path: &Path, options: ReadOptions) -> String {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(read_file_with(&p, &options).map(|o| o.len()));
    });
    match rx.recv_timeout(Duration::from_secs(10)) {
        Ok(Ok(n)) => panic!("{}: read {n} objects", path.display()),
        Ok(Err(e)) => e.to_string(),
        Err(_) => panic!("{}: still reading after 10 s", path.display()),
    }
}

const TETRA: &[u8] =
    b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

#[test]
fn only_regular_files_are_read() {
    apart_formats::quiet_parser_panics();
    let d = scratch("regular");
    std::fs::write(d.join("ok.off"), TETRA).unwrap();
    assert_eq!(read_file(&d.join("ok.off")).unwrap().len(), 1);
    std::fs::create_dir_all(d.join("folder.stl")).unwrap();
    let e = error_within(&d.join("folder.stl"), ReadOptions::default());
    assert!(
        e.contains("folder.stl: it is a folder, not a regular file"),
        "{e}"
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("/dev/zero", d.join("zero.stl")).unwrap();
        let e = error_within(&d.join("zero.stl"), ReadOptions::default());
        assert!(
            e.contains("zero.stl: it is a character device, not a regular file"),
            "{e}"
        );
        let fifo = d.join("pipe.obj");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let e = error_within(&fifo, ReadOptions::default());
            assert!(
                e.contains("pipe.obj: it is a named pipe (FIFO), not a regular file"),
                "{e}"
            );
        }
    }
    // One byte more than the limit, as a sparse file: refused before reading.
    let big = d.join("big.stl");
    let f = std::fs::File::create(&big).unwrap();
    if f.set_len(MAX_FILE_BYTES + 1).is_ok() {
        let e = error_within(&big, ReadOptions::default());
        assert!(
            e.contains(
                "big.stl: it holds 4294967297 bytes, more than the limit of 4294967296 bytes"
            ),
            "{e}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn file_names_are_escaped() {
    let d = scratch("names");
    let name = d.join("a\x1b[2Jb.step");
    std::fs::write(&name, b"x").unwrap();
    let e = read_file(&name).unwrap_err().to_string();
    assert!(e.contains("a\\x1b[2Jb.step") && !e.contains('\x1b'), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn huge_declared_counts_fail_fast() {
    let d = scratch("counts");
    let mut ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    ply.resize(250, 0);
    std::fs::write(d.join("face.ply"), &ply).unwrap();
    let e = error_within(&d.join("face.ply"), ReadOptions::default());
    assert!(
        e.contains("element \"face\" declares 4000000000 entries"),
        "{e}"
    );
    let mut ply =
        b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nend_header\n".to_vec();
    ply.resize(250, 0);
    std::fs::write(d.join("vertex.ply"), &ply).unwrap();
    let e = error_within(&d.join("vertex.ply"), ReadOptions::default());
    assert!(
        e.contains("element \"vertex\" declares 4000000000 entries"),
        "{e}"
    );
    let mut stl = vec![0u8; 84];
    stl[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    std::fs::write(d.join("t.stl"), &stl).unwrap();
    let e = error_within(&d.join("t.stl"), ReadOptions::default());
    assert!(
        e.contains(
            "it declares 4000000000 triangles (200000000084 bytes) but the file has 84 bytes"
        ),
        "{e}"
    );
    std::fs::write(d.join("t.off"), b"OFF\n4000000000 1 0\n").unwrap();
    let e = error_within(&d.join("t.off"), ReadOptions::default());
    assert!(
        e.contains("4000000000 vertices and 1 faces declared"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A `.gltf` whose one buffer is the file `uri`, holding one triangle.
fn gltf_with_buffer(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"buffers":[{{"byteLength":36,"uri":"{uri}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]}}"#
    )
}

fn triangle_bin() -> Vec<u8> {
    [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect()
}

#[test]
fn gltf_buffers_stay_in_the_folder_of_the_file() {
    let d = scratch("gltf");
    std::fs::create_dir_all(d.join("model")).unwrap();
    std::fs::write(d.join("model/tri.bin"), triangle_bin()).unwrap();
    std::fs::write(d.join("outside.bin"), triangle_bin()).unwrap();
    let write = |name: &str, uri: &str| {
        let p = d.join("model").join(name);
        std::fs::write(&p, gltf_with_buffer(uri)).unwrap();
        p
    };
    let ok = write("ok.gltf", "tri.bin");
    assert_eq!(read_file(&ok).unwrap()[0].vertices[1], [1.0, 0.0, 0.0]);
    let up = write("up.gltf", "../outside.bin");
    let e = error_within(&up, ReadOptions::default());
    assert_eq!(
        e,
        format!(
            "buffer 0 (\"../outside.bin\"): \"../outside.bin\" lies outside the folder {} (a \"..\" component leaves the folder); --allow-outside reads it anyway",
            d.join("model").display()
        )
    );
    // Lifted explicitly.
    let lifted = ReadOptions {
        allow_outside: true,
    };
    assert_eq!(read_file_with(&up, &lifted).unwrap().len(), 1);
    // A bare file name: its folder is shown as ".".
    let cwd = std::env::current_dir().unwrap();
    std::env::set_current_dir(d.join("model")).unwrap();
    let e = error_within(Path::new("up.gltf"), ReadOptions::default());
    std::env::set_current_dir(cwd).unwrap();
    assert!(e.contains("lies outside the folder . (a"), "{e}");
    let abs = write("abs.gltf", "/etc/passwd");
    let e = error_within(&abs, ReadOptions::default());
    assert!(e.contains("it is an absolute path"), "{e}");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(d.join("outside.bin"), d.join("model/link.bin")).unwrap();
        let link = write("link.gltf", "link.bin");
        let e = error_within(&link, ReadOptions::default());
        assert!(e.contains("a symbolic link leads to"), "{e}");
        let fifo = d.join("model/pipe.bin");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let p = write("pipe.gltf", "pipe.bin");
            let e = error_within(&p, ReadOptions::default());
            assert!(e.contains("named pipe (FIFO), not a regular file"), "{e}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}

/// The message of reading `bytes` as `format`, failing the test if they are read.
fn refused(bytes: &[u8], format: Format) -> String {
    match read_bytes(bytes, format, None) {
        Ok(o) => panic!(
            "read {} objects from {:?}",
            o.len(),
            String::from_utf8_lossy(bytes)
        ),
        Err(e) => e.to_string(),
    }
}

/// A binary STL of `n` triangles, whose header starts with `solid`.
fn binary_stl(n: usize) -> Vec<u8> {
    let v = [[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]];
    let mut b = Vec::new();
    stl::write(&mut b, &v, &vec![[0, 1, 2]; n]).unwrap();
    b[..11].copy_from_slice(b"solid part ");
    b
}

#[test]
fn binary_stl_counts_must_match_the_size() {
    let good = binary_stl(3);
    assert_eq!(
        read_bytes(&good, Format::Stl, None).unwrap()[0].faces.len(),
        3
    );
    // A count one less than the records held: the last record would be dropped.
    let mut fewer = good.clone();
    fewer[80..84].copy_from_slice(&2u32.to_le_bytes());
    let e = refused(&fewer, Format::Stl);
    assert!(
        e.contains(
            "not binary STL: it declares 2 triangles (184 bytes) but the file has 234 bytes"
        ),
        "{e}"
    );
    // Trailing bytes after the declared records.
    let mut trailing = good.clone();
    trailing.extend_from_slice(b"junk");
    let e = refused(&trailing, Format::Stl);
    assert!(
        e.contains(
            "not binary STL: it declares 3 triangles (234 bytes) but the file has 238 bytes"
        ),
        "{e}"
    );
    // The header starts with "solid": the message also says why it is not ASCII STL.
    assert!(e.contains("not ASCII STL: line 1: "), "{e}");
    // Truncated, with a header that does not start with "solid".
    let mut cut = good[..good.len() - 1].to_vec();
    cut[..5].copy_from_slice(b"hello");
    let e = refused(&cut, Format::Stl);
    assert!(
        e.contains("malformed STL file: not binary STL: it declares 3 triangles (234 bytes) but the file has 233 bytes; and not ASCII STL: it does not start with \"solid\""),
        "{e}"
    );
    let e = refused(b"\0\0\0", Format::Stl);
    assert!(
        e.contains(
            "not binary STL: it has 3 bytes, fewer than the 84 of a binary STL's header and count"
        ),
        "{e}"
    );
}

const FACET: &str = "facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n  vertex 0 1 0\n endloop\nendfacet\n";

#[test]
fn ascii_stl_facets_have_three_vertices() {
    let two = format!(
        "solid a\n{FACET}facet normal 0 0 1\n outer loop\n  vertex 0 0 0\n  vertex 1 0 0\n endloop\nendfacet\nendsolid a\n"
    );
    let e = refused(two.as_bytes(), Format::Stl);
    assert!(
        e.contains("line 13: facet 2 has 2 vertices; an STL facet has 3"),
        "{e}"
    );
    let four = format!(
        "solid a\n{}endsolid a\n",
        FACET.replace("endloop", "  vertex 1 1 0\n endloop")
    );
    let e = refused(four.as_bytes(), Format::Stl);
    assert!(
        e.contains("not ASCII STL: line 8: facet 1 has 4 vertices; an STL facet has 3; and not binary STL: it declares"),
        "{e}"
    );
    let cut = format!("solid a\n{}", &FACET[..60]);
    let e = refused(cut.as_bytes(), Format::Stl);
    assert!(e.contains("line 5: the file ends inside facet 1"), "{e}");
    let e = refused(
        b"solid a\nfacet normal 0 0 1\nouter loop\nvertex 0 x 0\n",
        Format::Stl,
    );
    assert!(e.contains("line 4: \"x\" is not a number"), "{e}");
}

#[test]
fn ascii_stl_in_upper_case_with_a_mark_or_a_latin1_name_is_read() {
    let upper = "SOLID CUBE\r\n FACET NORMAL 0 0 1\r\n  OUTER LOOP\r\n   VERTEX 0 0 0\r\n   VERTEX 1 0 0\r\n   VERTEX 0 0.1 0\r\n  ENDLOOP\r\n ENDFACET\r\nENDSOLID CUBE\r\n";
    let mut bom = b"\xef\xbb\xbf".to_vec();
    bom.extend_from_slice(format!("solid bom\n{FACET}endsolid bom\n").as_bytes());
    let mut latin1 = b"solid W\xfcrfel\n".to_vec();
    latin1.extend_from_slice(FACET.as_bytes());
    latin1.extend_from_slice(b"endsolid W\xfcrfel\n");
    for (bytes, name, y) in [
        (upper.as_bytes(), "CUBE", 0.1),
        (&bom[..], "bom", 1.0),
        (&latin1[..], "W\u{fc}rfel", 1.0),
    ] {
        let o = read_bytes(bytes, Format::Stl, None).unwrap();
        assert_eq!(o.len(), 1);
        assert_eq!(o[0].name.as_deref(), Some(name));
        assert_eq!(
            o[0].vertices,
            vec![[0.0, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, y, 0.0]]
        );
        assert_eq!(o[0].faces.get(0), &[0, 1, 2]);
    }
    // Not ASCII STL after all: the line where it stopped, and the binary reading.
    let mut bad =
        b"\xef\xbb\xbf\n\nSOLID x\nFACET NORMAL 0 0 1\nOUTER LOOP\nVERTEX 0 0 0\n\xff\xfe 1 2 3\n"
            .to_vec();
    bad.resize(120, b' ');
    let e = refused(&bad, Format::Stl);
    assert!(
        e.contains("not ASCII STL: line 7: unexpected \"\u{fffd}\u{fffd}\"; and not binary STL: it declares 538976288 triangles (26948814484 bytes) but the file has 120 bytes"),
        "{e}"
    );
}

/// Eight vertices of a unit cube, as OBJ `v` lines (lines 1 to 8).
const CUBE_VERTICES: &str =
    "v 0 0 0\nv 1 0 0\nv 1 1 0\nv 0 1 0\nv 0 0 1\nv 1 0 1\nv 1 1 1\nv 0 1 1\n";

#[test]
fn obj_face_indices_out_of_range_name_the_line_and_face() {
    for (reference, want) in [
        ("0", "line 13: face 3 refers to vertex 0; OBJ indices start at 1"),
        ("9", "line 13: face 3 refers to vertex 9 but only 8 vertices are defined before it"),
        (
            "4294967298",
            "line 13: face 3 refers to vertex 4294967298 but only 8 vertices are defined before it",
        ),
        (
            "-9223372036854775808",
            "line 13: face 3 refers to vertex -9223372036854775808 but only 8 vertices are defined before it",
        ),
        (
            "99999999999999999999999",
            "line 13: face 3 refers to vertex 99999999999999999999999 but only 8 vertices are defined before it",
        ),
        ("-9", "line 13: face 3 refers to vertex -9 but only 8 vertices are defined before it"),
        ("-0/1", "line 13: face 3 refers to vertex -0; OBJ indices start at 1"),
        (
            "1/x",
            "line 13: face 3 \"1/x\" is not a vertex reference (v, v/vt, v//vn or v/vt/vn)",
        ),
        ("1/2/3/4", "line 13: face 3 \"1/2/3/4\" is not a vertex reference"),
    ] {
        let text = format!("{CUBE_VERTICES}o box\nf 1 2 3\n# third face next\nf 1 3 {reference}\n");
        let text = text.replacen("o box\n", "o box\nf 1 3 4\n", 1);
        let e = refused(text.as_bytes(), Format::Obj);
        assert!(e.contains(want), "{reference}: {e}");
    }
    // Only vertices defined before the face count.
    let e = refused(b"v 0 0 0\nv 1 0 0\nf 1 2 3\nv 0 1 0\n", Format::Obj);
    assert!(
        e.contains("line 3: face 1 refers to vertex 3 but only 2 vertices are defined before it"),
        "{e}"
    );
    let e = refused(b"v 0 0 0\nf -1 -1 -2\n", Format::Obj);
    assert!(
        e.contains("line 2: face 1 refers to vertex -2 but only 1 vertex is defined before it"),
        "{e}"
    );
    let e = refused(b"v 0 0 0\nv 1 0 0\nf 1 2\n", Format::Obj);
    assert!(
        e.contains("line 3: face 1 has 2 vertices; a face needs at least 3"),
        "{e}"
    );
    for (line, want) in [
        ("v 0 0", "line 2: vertex 2 has 2 coordinates, not 3"),
        ("v 0 0 x", "line 2: vertex 2: \"x\" is not a number"),
        ("v 0 0 0 0", "line 2: vertex 2 has a weight w of 0"),
        ("v 0 0 0 1 1", "line 2: vertex 2 has 5 numbers"),
    ] {
        let e = refused(format!("v 0 0 0\n{line}\n").as_bytes(), Format::Obj);
        assert!(e.contains(want), "{line}: {e}");
    }
}

#[test]
fn obj_texture_and_normal_indices_are_ignored() {
    // Relative indices, texture and normal indices beyond their lists (not read), vertex
    // colours, inline comments, and a name that is not UTF-8.
    let mut text = CUBE_VERTICES
        .replace("v 0 0 0\n", "v 0 0 0 1 0 0 # red\n")
        .into_bytes();
    text.extend_from_slice(b"vt 0 0\nvn 0 0 1\no caf\xe9\nf 1/7/9 2/1/1 3//99\nf -8/5 -6/99999999999999999999 -5/-7\nl 1 2\n");
    let o = read_bytes(&text, Format::Obj, None).unwrap();
    assert_eq!(o.len(), 1);
    assert_eq!(o[0].name.as_deref(), Some("caf\u{fffd}"));
    assert_eq!(o[0].faces.len(), 2);
    let corners: Vec<[f64; 3]> = o[0]
        .faces
        .get(1)
        .iter()
        .map(|&i| o[0].vertices[i as usize])
        .collect();
    assert_eq!(
        corners,
        vec![[0.0, 0.0, 0.0], [1.0, 1.0, 0.0], [0.0, 1.0, 0.0]]
    );
}

/// A triangle as OFF: the header (line 1), the counts (line 2), three vertices (lines 3
/// to 5) and then `faces` from line 6.
fn off_triangle(counts: &str, faces: &str) -> Vec<u8> {
    format!("OFF\n{counts}\n0 0 0\n1 0 0\n0 1 0\n{faces}").into_bytes()
}

#[test]
fn off_counts_must_match_the_data() {
    assert_eq!(
        read_bytes(
            &off_triangle("3 1 0", "3 0 1 2 # one\n\n# done\n"),
            Format::Off,
            None
        )
        .unwrap()[0]
            .faces
            .len(),
        1
    );
    for (counts, faces, want) in [
        (
            "3 1 0",
            "3 0 1 2\n3 0 2 1\n",
            "line 7: data after the 1 declared face",
        ),
        ("3 2 0", "3 0 1 2\n", "line 6: expected 2 faces, found 1"),
        ("2 1 0", "3 0 1 2\n", "line 5: face 0 has 0 vertices"),
        ("4 1 0", "3 0 1 2\n", "line 6: expected 1 face, found 0"),
        ("4 1 0", "", "line 5: expected 4 vertices, found 3"),
        (
            "3 1 0",
            "2 0 1\n",
            "line 6: face 0 has 2 vertices; a face needs at least 3",
        ),
        (
            "3 1 0",
            "4 0 1 2\n",
            "line 6: face 0 declares 4 vertices but lists 3",
        ),
        (
            "3 1 0",
            "3 0 1 2 0 1\n",
            "line 6: face 0 declares 3 vertices but the line holds 2 more values",
        ),
        (
            "3 1 0",
            "3 0 1 2 x\n",
            "line 6: face 0: \"x\" after its indices is not a number",
        ),
    ] {
        let e = refused(&off_triangle(counts, faces), Format::Off);
        assert!(e.contains(want), "{counts} / {faces}: {e}");
    }
}

const PLY_HEADER: &str = "ply\nformat ascii 1.0\nelement vertex 3\nproperty double x\nproperty double y\nproperty double z\nelement face 1\nproperty list uchar int vertex_indices\nend_header\n";

#[test]
fn ply_counts_must_match_the_data() {
    // The header takes lines 1 to 9; the vertices 10 to 12, the face 13.
    let ply = |vertices: &str, faces: &str| format!("{PLY_HEADER}{vertices}{faces}").into_bytes();
    let xyz = "0 0 0\n1 0 0\n0 1 0\n";
    assert_eq!(
        read_bytes(&ply(xyz, "3 0 1 2\n\n"), Format::Ply, None).unwrap()[0]
            .faces
            .len(),
        1
    );
    for (vertices, faces, want) in [
        (
            xyz,
            "3 0 1 2\n3 0 2 1\n",
            "line 14: data after the declared elements",
        ),
        (
            "0.000000000 0 0\n1 0 0\n0 1 0\n",
            "",
            "line 12: the file ends after 0 of the 1 declared entries of element \"face\"",
        ),
        (
            "0.000000000000000 0 0\n1.000000000000000 0 0\n",
            "",
            "line 11: the file ends after 2 of the 3 declared entries of element \"vertex\"",
        ),
        (
            xyz,
            "2 0 1\n",
            "line 13: face 0 has 2 vertices; a face needs at least 3",
        ),
        (
            xyz,
            "3 0 1 2 1\n",
            "line 13: face 0 has 5 values, but its properties (and list lengths) call for 4",
        ),
        (
            xyz,
            "4 0 1 2\n",
            "line 13: face 0 has 4 values, but its properties (and list lengths) call for 5",
        ),
        (
            "0 0 0 0\n1 0 0\n0 1 0\n",
            "3 0 1 2\n",
            "line 10: vertex 0 has 4 values, but its properties (and list lengths) call for 3",
        ),
        (
            xyz,
            "3 0 1 3\n",
            "line 13: face 0 refers to vertex 3, but there are only 3 vertices",
        ),
        (
            xyz,
            "3 0 1 -1\n",
            "line 13: face 0 has a negative vertex index",
        ),
    ] {
        let e = refused(&ply(vertices, faces), Format::Ply);
        assert!(e.contains(want), "{vertices} / {faces}: {e}");
    }
    // Binary: trailing bytes, and a face of two vertices, named by element.
    let mut b = PLY_HEADER
        .replace("ascii", "binary_little_endian")
        .into_bytes();
    for c in [0f64, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0, 0.0] {
        b.extend_from_slice(&c.to_le_bytes());
    }
    let mut two = b.clone();
    two.push(2);
    two.extend([0i32, 1].iter().flat_map(|i| i.to_le_bytes()));
    let e = refused(&two, Format::Ply);
    assert!(
        e.contains("malformed PLY file: face 0 has 2 vertices; a face needs at least 3"),
        "{e}"
    );
    b.push(3);
    b.extend([0i32, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    assert_eq!(read_bytes(&b, Format::Ply, None).unwrap()[0].faces.len(), 1);
    let len = b.len();
    b.extend_from_slice(b"junk");
    let e = refused(&b, Format::Ply);
    assert!(
        e.contains(&format!(
            "4 bytes after the declared elements, from byte offset {len}"
        )),
        "{e}"
    );
    let e = refused(&b[..len - 2], Format::Ply);
    assert!(
        e.contains("binary element 'face'") && !e.contains("Line"),
        "{e}"
    );
}

/// The JSON of a one-triangle glTF whose buffer 0 (`byte_length`, no URI) is the BIN
/// chunk, with `index_count` indices.
fn glb_json(byte_length: usize, index_count: usize) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":{byte_length}}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}},
{{"bufferView":1,"componentType":5123,"count":{index_count},"type":"SCALAR"}}]}}"#
    )
}

/// A GLB of `json` and `bin`, each padded to 4 bytes as the format wants.
fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut json = json.as_bytes().to_vec();
    json.resize(json.len().div_ceil(4) * 4, b' ');
    let mut bin = bin.to_vec();
    bin.resize(bin.len().div_ceil(4) * 4, 0);
    let mut out = b"glTF".to_vec();
    out.extend(2u32.to_le_bytes());
    out.extend(((12 + 8 + json.len() + 8 + bin.len()) as u32).to_le_bytes());
    out.extend((json.len() as u32).to_le_bytes());
    out.extend(b"JSON");
    out.extend(json);
    out.extend((bin.len() as u32).to_le_bytes());
    out.extend(b"BIN\0");
    out.extend(bin);
    out
}

/// Positions of one triangle and its three u16 indices: 42 bytes.
fn triangle_bin_with_indices() -> Vec<u8> {
    let mut b = triangle_bin();
    b.extend([0u16, 1, 2].iter().flat_map(|i| i.to_le_bytes()));
    b
}

#[test]
fn glb_lengths_must_match_the_file() {
    let bin = triangle_bin_with_indices();
    let good = glb(&glb_json(42, 3), &bin);
    let o = read_bytes(&good, Format::Gltf, None).unwrap();
    assert_eq!(o[0].vertices[2], [0.0, 1.0, 0.0]);
    let n = good.len();
    let json_len = u32::from_le_bytes(good[12..16].try_into().unwrap()) as usize;
    let bin_at = 20 + json_len;
    let with = |at: usize, value: usize| {
        let mut b = good.clone();
        b[at..at + 4].copy_from_slice(&(value as u32).to_le_bytes());
        b
    };
    let cases = [
        (
            with(8, n - 4),
            format!("the GLB header declares {} bytes but the file has {n}", n - 4),
        ),
        (
            with(8, n + 4),
            format!("the GLB header declares {} bytes but the file has {n}", n + 4),
        ),
        (
            with(12, n),
            format!(
                "GLB chunk 0 (JSON) at byte offset 12 declares {n} bytes of data, but only {} are left in the file",
                n - 20
            ),
        ),
        (
            with(12, json_len - 4),
            format!(") at byte offset {} declares", bin_at - 4),
        ),
        (
            with(bin_at, 48),
            format!("GLB chunk 1 (BIN) at byte offset {bin_at} declares 48 bytes of data, but only 44 are left"),
        ),
        (
            with(bin_at, 40),
            format!("4 bytes at byte offset {}, after chunk 1, are too few for a chunk header", n - 4),
        ),
        (
            glb(&glb_json(42, 3), &[&bin[..], &[0; 8]].concat()),
            "buffer 0 is the BIN chunk of 52 bytes, more than its byteLength 42 and at most 3 bytes of padding".to_string(),
        ),
        (
            glb(&glb_json(41, 3), &bin),
            "buffer view 1 (bytes 36 to 42) lies beyond the end of buffer 0 (41 bytes)".to_string(),
        ),
        (
            glb(&glb_json(42, 3).replace("\"accessors\"", "\"acc/ssors\""), &bin),
            "mesh 0, primitive 0: POSITION is accessor 0, but there are only 0 accessors"
                .to_string(),
        ),
        (
            glb(&glb_json(42, 2), &bin),
            "mesh 0, primitive 0: 2 indices for TRIANGLES, not a multiple of 3".to_string(),
        ),
        (
            [&with(8, 16)[..12], b"JSON"].concat(),
            "4 bytes at byte offset 12, after the header, are too few for a chunk header".to_string(),
        ),
        (
            good[..11].to_vec(),
            "the GLB file has 11 bytes, fewer than its 12-byte header".to_string(),
        ),
    ];
    for (bytes, want) in cases {
        let e = refused(&bytes, Format::Gltf);
        assert!(e.contains(&want), "{want}\n{e}");
    }
    // A chunk of another type after BIN is allowed (the format reserves them).
    let mut extra = good.clone();
    extra.extend(4u32.to_le_bytes());
    extra.extend(b"XTRA\0\0\0\0");
    let len = extra.len() as u32;
    extra[8..12].copy_from_slice(&len.to_le_bytes());
    assert_eq!(read_bytes(&extra, Format::Gltf, None).unwrap().len(), 1);
}

/// Every prefix, and many one-byte changes, of a valid file of each format: each is read
/// or refused, never a panic (which would show as "parser failed").
#[test]
fn cut_and_mutated_files_never_panic() {
    apart_formats::quiet_parser_panics();
    let obj = format!("{CUBE_VERTICES}o box\nf 1 2 3 4\nf -1/1 -2//3 -3/1/1\n");
    let samples: Vec<(Format, Vec<u8>)> = vec![
        (Format::Off, TETRA.to_vec()),
        (Format::Obj, obj.into_bytes()),
        (Format::Stl, binary_stl(2)),
        (
            Format::Stl,
            format!("solid a\n{FACET}endsolid a\n").into_bytes(),
        ),
        (
            Format::Ply,
            format!("{PLY_HEADER}0 0 0\n1 0 0\n0 1 0\n3 0 1 2\n").into_bytes(),
        ),
        (
            Format::Gltf,
            glb(&glb_json(42, 3), &triangle_bin_with_indices()),
        ),
    ];
    let mut seed = 0x2545_f491_4f6c_dd1du64;
    let mut next = || {
        seed ^= seed << 13;
        seed ^= seed >> 7;
        seed ^= seed << 17;
        seed
    };
    for (format, bytes) in samples {
        let mut inputs: Vec<Vec<u8>> = (0..bytes.len()).map(|n| bytes[..n].to_vec()).collect();
        for _ in 0..2000 {
            let mut b = bytes.clone();
            let at = next() as usize % b.len();
            b[at] = match next() % 4 {
                0 => b"0-9 \n/#"[next() as usize % 7],
                1 => 0xff,
                _ => next() as u8,
            };
            inputs.push(b);
        }
        for b in inputs {
            if let Err(e) = read_bytes(&b, format, None) {
                let e = e.to_string();
                assert!(
                    !e.contains("parser failed"),
                    "{format}: {e}\n{}",
                    String::from_utf8_lossy(&b)
                );
            }
        }
    }
}
