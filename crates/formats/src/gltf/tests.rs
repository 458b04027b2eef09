//! Tests of the glTF reader: embedded and external buffers, node transforms and the
//! malformed files it refuses.

use super::buffers::{base64_decode, data_uri_bytes, percent_decoded};
use super::*;
use std::fmt::Write;
use std::path::PathBuf;

/// Positions of one triangle (36 bytes), its u16 indices (6 bytes) and padding.
fn triangle_bin() -> Vec<u8> {
    let mut bin = Vec::new();
    for v in [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]] {
        for c in v {
            bin.extend_from_slice(&c.to_le_bytes());
        }
    }
    for i in [0u16, 1, 2] {
        bin.extend_from_slice(&i.to_le_bytes());
    }
    bin.extend_from_slice(&[0, 0]);
    bin
}

#[test]
fn base64_data_decodes_with_or_without_padding() {
    for n in 0..40usize {
        let bin: Vec<u8> = (0..n).map(|k| (k * 37 + 11) as u8).collect();
        let text = apart_testkit::base64(&bin);
        assert_eq!(base64_decode(&text).unwrap(), bin, "{text}");
        assert_eq!(base64_decode(text.trim_end_matches('=')).unwrap(), bin);
        let uri = format!("data:application/octet-stream;base64,{text}");
        assert_eq!(data_uri_bytes(&uri).unwrap(), bin);
    }
    assert_eq!(base64_decode("TWFu").unwrap(), b"Man");
    assert_eq!(base64_decode("+/+/").unwrap(), [0xfb, 0xff, 0xbf]);
    let e = base64_decode("TW-u").unwrap_err();
    assert!(e.contains("\"-\" at character 2"), "{e}");
    assert!(base64_decode("TWFuT").unwrap_err().contains("5 characters"));
    assert!(data_uri_bytes("data:text/plain,hello")
        .unwrap_err()
        .contains(";base64,"));
}

const ACCESSORS: &str = r#"[{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]"#;

/// A glTF of the triangle mesh with the given nodes, scene roots, accessors and
/// buffer URI (`None`: the data inline).
fn doc(nodes: &str, roots: &str, accessors: &str, uri: Option<&str>) -> Vec<u8> {
    let bin = triangle_bin();
    let uri = match uri {
        Some(u) => u.to_string(),
        None => format!(
            "data:application/octet-stream;base64,{}",
            apart_testkit::base64(&bin)
        ),
    };
    let mut j = String::new();
    write!(
        j,
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":{roots}}}],
"nodes":{nodes},
"meshes":[{{"name":"tri","primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":{},"uri":"{uri}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}},{{"buffer":0,"byteOffset":36,"byteLength":6}}],
"accessors":{accessors}}}"#,
        bin.len()
    )
    .unwrap();
    j.into_bytes()
}

/// One node with the mesh and the given extra properties.
fn one_node(props: &str) -> Vec<u8> {
    let sep = if props.is_empty() { "" } else { "," };
    doc(
        &format!(r#"[{{"name":"n","mesh":0{sep}{props}}}]"#),
        "[0]",
        ACCESSORS,
        None,
    )
}

fn err(bytes: &[u8]) -> String {
    read(bytes, None, &ReadOptions::default())
        .unwrap_err()
        .to_string()
}

/// A glTF with one triangle mesh used by two nodes: a parent translated by x+10 with
/// a child turned a quarter about z.
pub(crate) fn two_node_gltf() -> Vec<u8> {
    let s = std::f32::consts::FRAC_1_SQRT_2;
    doc(
        &format!(
            r#"[{{"name":"parent","mesh":0,"translation":[10,0,0],"children":[1]}},
{{"name":"child","mesh":0,"rotation":[0,0,{s},{s}]}}]"#
        ),
        "[0]",
        ACCESSORS,
        None,
    )
}

#[test]
fn nodes_with_transforms() {
    let objs = read(&two_node_gltf(), None, &ReadOptions::default()).unwrap();
    assert_eq!(objs.len(), 2);
    assert_eq!(objs[0].name.as_deref(), Some("parent"));
    assert_eq!(objs[0].vertices[1], [11.0, 0.0, 0.0]);
    // Child: quarter turn about z (exact after snapping), then the parent's shift.
    assert_eq!(objs[1].name.as_deref(), Some("child"));
    assert_eq!(objs[1].vertices[1], [10.0, 1.0, 0.0]);
    assert_eq!(objs[1].vertices[2], [9.0, 0.0, 0.0]);
    assert_eq!(objs[1].faces.get(0), &[0, 1, 2]);
}

#[test]
fn percent_escapes() {
    assert_eq!(percent_decoded("a%20b.bin").unwrap(), "a b.bin");
    assert_eq!(percent_decoded("100%").unwrap(), "100%");
    assert_eq!(percent_decoded("%2e%2e/x").unwrap(), "../x");
    assert!(percent_decoded("%ff").is_none());
}

fn scratch(name: &str) -> PathBuf {
    let d = std::env::temp_dir().join(format!("apart-gltf-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&d);
    std::fs::create_dir_all(d.join("model")).unwrap();
    d
}

#[test]
fn external_buffers_stay_in_the_folder() {
    let d = scratch("outside");
    let dir = d.join("model");
    std::fs::write(dir.join("tri.bin"), triangle_bin()).unwrap();
    // A secret outside the folder, with a control character.
    let mut secret = b"SECRET\x1b[2J".to_vec();
    secret.resize(44, b'!');
    std::fs::write(d.join("secret.bin"), &secret).unwrap();
    let nodes = r#"[{"name":"n","mesh":0}]"#;
    let safe = ReadOptions::default();
    let load = |uri: &str, options: &ReadOptions| {
        read(
            &doc(nodes, "[0]", ACCESSORS, Some(uri)),
            Some(&dir),
            options,
        )
    };
    let objs = load("tri.bin", &safe).unwrap();
    assert_eq!(objs[0].vertices[1], [1.0, 0.0, 0.0]);
    assert!(load("./sub/../tri.bin", &safe).is_err()); // no folder "sub"
    assert!(load("tri%2ebin", &safe).is_ok());
    for (uri, why) in [
        ("../secret.bin", "component leaves the folder"),
        ("%2e%2e/secret.bin", "component leaves the folder"),
        ("/etc/passwd", "absolute path"),
        ("file:///etc/passwd", "absolute path"),
    ] {
        let e = load(uri, &safe).unwrap_err().to_string();
        assert!(e.starts_with("buffer 0 (\""), "{e}");
        assert!(
            e.contains(why) && e.contains("--allow-outside"),
            "{uri}: {e}"
        );
    }
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("../secret.bin", dir.join("link.bin")).unwrap();
        let e = load("link.bin", &safe).unwrap_err().to_string();
        assert!(e.contains("symbolic link"), "{e}");
        std::os::unix::fs::symlink("/dev/zero", dir.join("zero.bin")).unwrap();
        let lifted = ReadOptions::default().allow_outside(true);
        let e = load("zero.bin", &lifted).unwrap_err().to_string();
        assert!(e.contains("character device, not a regular file"), "{e}");
        let e = load("/dev/zero", &lifted).unwrap_err().to_string();
        assert!(e.contains("character device"), "{e}");
    }
    // Lifted: the outside file is read; its bytes never reach a message.
    let lifted = ReadOptions::default().allow_outside(true);
    match load("../secret.bin", &lifted) {
        Ok(objs) => assert_eq!(objs.len(), 1),
        Err(e) => {
            let e = e.to_string();
            assert!(!e.contains("SECRET") && !e.contains('\x1b'), "{e}");
        }
    }
    let e = load("http://example.com/a.bin", &safe)
        .unwrap_err()
        .to_string();
    assert!(e.contains("URI scheme"), "{e}");
    // Without a folder, an external buffer is an error, not a path from the
    // current directory.
    let e = read(&doc(nodes, "[0]", ACCESSORS, Some("tri.bin")), None, &safe)
        .unwrap_err()
        .to_string();
    assert!(e.contains("folder to find it in is unknown"), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn node_hierarchies_are_bounded() {
    // 17 levels each listing the next level twice, the mesh at the bottom:
    // 2^17 = 131,072 instances from a file of a few hundred bytes.
    let mut nodes: Vec<String> = (0..17)
        .map(|k| format!(r#"{{"children":[{},{}]}}"#, k + 1, k + 1))
        .collect();
    nodes.push(r#"{"mesh":0}"#.into());
    let e = err(&doc(
        &format!("[{}]", nodes.join(",")),
        "[0]",
        ACCESSORS,
        None,
    ));
    assert!(
        e.contains("expands to 131072 mesh instances")
            && e.contains("more than the limit of 100000"),
        "{e}"
    );
    // Empty nodes, 60 levels: counted without walking them.
    let mut nodes: Vec<String> = (0..60)
        .map(|k| format!(r#"{{"children":[{},{}]}}"#, k + 1, k + 1))
        .collect();
    nodes.push("{}".into());
    let t = std::time::Instant::now();
    let e = err(&doc(
        &format!("[{}]", nodes.join(",")),
        "[0]",
        ACCESSORS,
        None,
    ));
    assert!(e.contains("node instances"), "{e}");
    assert!(t.elapsed().as_secs() < 5);
    // A few shared instances are fine.
    let objs = read(
        &doc(
            r#"[{"children":[1,1,1]},{"mesh":0}]"#,
            "[0, 0]",
            ACCESSORS,
            None,
        ),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(objs.len(), 6);
    // Cycles, through two nodes and through one.
    for nodes in [
        r#"[{"children":[1]},{"mesh":0,"children":[0]}]"#,
        r#"[{"mesh":0,"children":[0]}]"#,
    ] {
        let e = err(&doc(nodes, "[0]", ACCESSORS, None));
        assert!(e.contains("has a cycle") && e.contains("node 0"), "{e}");
    }
}

#[test]
fn transforms_must_be_finite_and_rotations_unit() {
    for (props, want) in [
        (r#""rotation":[0,0,0,0]"#, "not a unit quaternion (norm 0,"),
        (r#""rotation":[1e39,0,0,1]"#, "not a finite number"),
        (r#""rotation":[0,0,0,2]"#, "not a unit quaternion (norm 2,"),
        (r#""rotation":[0,0,1e30,1e30]"#, "not a unit quaternion"),
        (r#""translation":[1e39,0,0]"#, "translation"),
        (r#""scale":[1,-1e39,1]"#, "scale"),
        (
            r#""matrix":[1,0,0,0, 0,1,0,0, 0,0,1,0, 1e39,0,0,1]"#,
            "not a finite number",
        ),
        (
            r#""matrix":[1,0,0,0.5, 0,1,0,0, 0,0,1,0, 0,0,0,1]"#,
            "not affine",
        ),
    ] {
        // 1e39 is read as an infinite f32.
        let e = err(&one_node(props));
        assert!(
            e.contains(want) && e.contains("node 0 (\"n\"): its "),
            "{props}: {e}"
        );
    }
    // Near-unit quaternions (f32 rounding) are normalised.
    let o = read(
        &one_node(r#""rotation":[0,0,0,1.0004]"#),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(o[0].vertices[1], [1.0, 0.0, 0.0]);
}

#[test]
fn accessor_types_are_checked() {
    let node = r#"[{"mesh":0}]"#;
    for (accessors, want) in [
        (
            ACCESSORS.replace("5126", "5121"),
            "POSITION accessor 0 has componentType 5121 (UNSIGNED_BYTE) and type VEC3",
        ),
        (
            ACCESSORS.replace("\"VEC3\"", "\"VEC2\""),
            "componentType 5126 (FLOAT) and type VEC2",
        ),
        (
            ACCESSORS.replace("5123", "5126"),
            "index accessor 1 has componentType 5126 (FLOAT) and type SCALAR",
        ),
        (
            ACCESSORS.replace("5123", "5122"),
            "index accessor 1 has componentType 5122 (SHORT)",
        ),
    ] {
        let e = err(&doc(node, "[0]", &accessors, None));
        assert!(
            e.contains(want) && e.contains("mesh 0 (\"tri\"), primitive 0"),
            "{e}"
        );
    }
}

#[test]
fn declared_sizes_are_checked() {
    let node = r#"[{"mesh":0}]"#;
    for (accessors, want) in [
        // Four billion positions: refused before the views are looked at.
        (
            ACCESSORS.replace("\"count\":3,\"type\":\"VEC3\"", "\"count\":4000000000,\"type\":\"VEC3\""),
            "hold 4000000003 vertices and indices, more than the limit of 268435456",
        ),
        // A hundred million positions in a 36-byte view.
        (
            ACCESSORS.replace("\"count\":3,\"type\":\"VEC3\"", "\"count\":100000000,\"type\":\"VEC3\""),
            "100000000 elements of 12 bytes at a stride of 12 from byte 0 need 1200000000 bytes, but buffer view 0 holds 36",
        ),
        (
            ACCESSORS.replace("\"count\":3,\"type\":\"SCALAR\"", "\"count\":4,\"type\":\"SCALAR\""),
            "need 8 bytes, but buffer view 1 holds 6",
        ),
        // Sparse without a buffer view: zeros, but not more than the file could
        // describe.
        (
            ACCESSORS.replace("\"bufferView\":0,", "").replace(
                "\"count\":3,\"type\":\"VEC3\"",
                r#""count":100000000,"type":"VEC3","sparse":{"count":1,"indices":{"bufferView":1,"componentType":5123},"values":{"bufferView":0}}"#,
            ),
            "100000000 elements without a buffer view",
        ),
    ] {
        let e = err(&doc(node, "[0]", &accessors, None));
        assert!(e.contains(want), "{e}");
    }
    // Without a scene, every mesh once: bounded too.
    let j = String::from_utf8(doc(
        node,
        "[0]",
        &ACCESSORS.replace(
            "\"count\":3,\"type\":\"VEC3\"",
            "\"count\":200000000,\"type\":\"VEC3\"",
        ),
        None,
    ))
    .unwrap();
    let no_scene = j.replace("\"scene\":0,\"scenes\":[{\"nodes\":[0]}],", "");
    let three = no_scene.replace(
        r#"[{"attributes":{"POSITION":0},"indices":1}]"#,
        r#"[{"attributes":{"POSITION":0}},{"attributes":{"POSITION":0}}]"#,
    );
    let e = err(three.as_bytes());
    assert!(
        e.contains("the meshes hold 400000000 vertices and indices"),
        "{e}"
    );
    let t = std::time::Instant::now();
    let e = err(no_scene.as_bytes());
    assert!(
        e.contains("need 2400000000 bytes, but buffer view 0 holds 36"),
        "{e}"
    );
    assert!(t.elapsed().as_millis() < 500);
    // A buffer view beyond its buffer, and a buffer shorter than its byteLength.
    let j = String::from_utf8(doc(node, "[0]", ACCESSORS, None)).unwrap();
    let e = err(j
        .replace(
            "\"byteOffset\":36,\"byteLength\":6",
            "\"byteOffset\":36,\"byteLength\":600",
        )
        .as_bytes());
    assert!(
        e.contains("lies beyond the end of buffer 0 (44 bytes)"),
        "{e}"
    );
    let e = err(j
        .replace("\"byteLength\":44", "\"byteLength\":4000000000")
        .as_bytes());
    assert!(e.contains("fewer than its byteLength 4000000000"), "{e}");
}

#[test]
fn sparse_accessors() {
    // Three zero positions, the second and third replaced by the view's first two.
    let accessors = r#"[{"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,0,0],"sparse":{"count":2,"indices":{"bufferView":1,"componentType":5123,"byteOffset":2},"values":{"bufferView":0}}},
{"bufferView":1,"componentType":5123,"count":3,"type":"SCALAR"}]"#;
    let o = read(
        &doc(r#"[{"mesh":0}]"#, "[0]", accessors, None),
        None,
        &ReadOptions::default(),
    )
    .unwrap();
    assert_eq!(
        o[0].vertices,
        vec![[0.0, 0.0, 0.0], [0.0, 0.0, 0.0], [1.0, 0.0, 0.0]]
    );
}

#[test]
fn garbage() {
    assert!(read(b"{\"asset\":", None, &ReadOptions::default()).is_err());
    assert!(read(b"glTF\x02\0\0\0", None, &ReadOptions::default()).is_err());
    // Names quoted in messages are escaped.
    let j = String::from_utf8(doc(
        r#"[{"mesh":0}]"#,
        "[0]",
        &ACCESSORS.replace("5126", "5121"),
        None,
    ))
    .unwrap();
    let e = err(j
        .replace("\"name\":\"tri\"", "\"name\":\"t\\u001b[2Jri\"")
        .as_bytes());
    assert!(
        e.contains("mesh 0 (\"t\\x1b[2Jri\")") && !e.contains('\x1b'),
        "{e}"
    );
}
