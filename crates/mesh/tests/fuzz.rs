//! Robustness: random bytes and mutated valid files fed to every reader, and whatever
//! they return fed on to snapping and validation. Nothing may panic (an `Err` is fine).
//! (cargo-fuzz needs a nightly toolchain, which this project does not assume; these
//! proptest runs are the stable substitute.)

use apart_formats::{off, read_bytes, stl, Format, Polygons, RawObject};
use apart_kernel::Grid;
use apart_mesh::validate::check_solid;
use apart_testkit::solids::CUBOID_QUADS;
use proptest::prelude::*;

fn cube() -> RawObject {
    let vertices = (0..8)
        .map(|i| [(i & 1) as f64, (i >> 1 & 1) as f64 * 0.5, (i >> 2) as f64])
        .collect();
    let faces = Polygons::from(CUBOID_QUADS.iter().map(|q| q.to_vec()).collect::<Vec<_>>());
    RawObject {
        name: None,
        vertices,
        faces,
    }
}

fn tri_faces(o: &RawObject) -> Vec<[u32; 3]> {
    o.faces
        .iter()
        .flat_map(|f| (1..f.len() - 1).map(move |k| [f[0], f[k], f[k + 1]]))
        .collect()
}

/// Valid files of every format (and both encodings where there are two).
fn samples() -> Vec<(Format, Vec<u8>)> {
    let c = cube();
    let mut out = Vec::new();
    let mut b = Vec::new();
    off::write(&mut b, &c.vertices, &c.faces).unwrap();
    out.push((Format::Off, b));
    let mut b = Vec::new();
    apart_formats::obj::write(
        &mut b,
        &[
            c.clone(),
            RawObject {
                name: Some("two".into()),
                ..c.clone()
            },
        ],
    )
    .unwrap();
    out.push((Format::Obj, b));
    let mut b = Vec::new();
    stl::write(&mut b, &c.vertices, &tri_faces(&c)).unwrap();
    out.push((Format::Stl, b));
    let mut a = String::from("solid c\n");
    for t in tri_faces(&c) {
        a.push_str("facet normal 0 0 0\nouter loop\n");
        for v in t {
            let p = c.vertices[v as usize];
            a.push_str(&format!("vertex {} {} {}\n", p[0], p[1], p[2]));
        }
        a.push_str("endloop\nendfacet\n");
    }
    a.push_str("endsolid c\n");
    out.push((Format::Stl, a.into_bytes()));
    let mut p = format!(
        "ply\nformat ascii 1.0\nelement vertex 8\nproperty double x\nproperty double y\nproperty double z\nelement face {}\nproperty list uchar int vertex_indices\nend_header\n",
        c.faces.len()
    );
    for v in &c.vertices {
        p.push_str(&format!("{} {} {}\n", v[0], v[1], v[2]));
    }
    for f in c.faces.iter() {
        p.push_str(&format!(
            "{} {}\n",
            f.len(),
            f.iter()
                .map(|i| i.to_string())
                .collect::<Vec<_>>()
                .join(" ")
        ));
    }
    out.push((Format::Ply, p.into_bytes()));
    let mut pb = format!(
        "ply\nformat binary_little_endian 1.0\nelement vertex 8\nproperty float x\nproperty float y\nproperty float z\nelement face {}\nproperty list uchar uint vertex_indices\nend_header\n",
        c.faces.len()
    )
    .into_bytes();
    for v in &c.vertices {
        for x in v {
            pb.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    for f in c.faces.iter() {
        pb.push(f.len() as u8);
        for i in f {
            pb.extend_from_slice(&i.to_le_bytes());
        }
    }
    out.push((Format::Ply, pb));
    let (json, bin) = gltf_parts(&c);
    out.push((Format::Gltf, gltf_with_data_uri(&json, &bin)));
    out.push((Format::Gltf, glb(&json, &bin)));
    out
}

fn gltf_parts(c: &RawObject) -> (String, Vec<u8>) {
    let tris = tri_faces(c);
    let mut bin = Vec::new();
    for v in &c.vertices {
        for x in v {
            bin.extend_from_slice(&(*x as f32).to_le_bytes());
        }
    }
    let pos_len = bin.len();
    for t in &tris {
        for i in t {
            bin.extend_from_slice(&(*i as u16).to_le_bytes());
        }
    }
    let idx_len = bin.len() - pos_len;
    while bin.len() % 4 != 0 {
        bin.push(0);
    }
    let json = format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0,1]}}],
"nodes":[{{"name":"a","mesh":0}},{{"name":"b","mesh":0,"translation":[3,0,0],"rotation":[0,0,0.7071068,0.7071068]}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}},"indices":1}}]}}],
"buffers":[{{"byteLength":{}URI}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":{pos_len}}},{{"buffer":0,"byteOffset":{pos_len},"byteLength":{idx_len}}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":8,"type":"VEC3","min":[0,0,0],"max":[1,0.5,1]}},
{{"bufferView":1,"componentType":5123,"count":{},"type":"SCALAR"}}]}}"#,
        bin.len(),
        3 * tris.len()
    );
    (json, bin)
}

fn gltf_with_data_uri(json: &str, bin: &[u8]) -> Vec<u8> {
    json.replace(
        "URI",
        &format!(
            ",\"uri\":\"data:application/octet-stream;base64,{}\"",
            apart_testkit::base64(bin)
        ),
    )
    .into_bytes()
}

fn glb(json: &str, bin: &[u8]) -> Vec<u8> {
    let mut j = json.replace("URI", "").into_bytes();
    while j.len() % 4 != 0 {
        j.push(b' ');
    }
    let total = 12 + 8 + j.len() + 8 + bin.len();
    let mut out = b"glTF".to_vec();
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(j.len() as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(&j);
    out.extend_from_slice(&(bin.len() as u32).to_le_bytes());
    out.extend_from_slice(b"BIN\0");
    out.extend_from_slice(bin);
    out
}

/// Files built to hurt: huge declared counts, a node DAG of 2^17
/// instances, a cycle, broken rotations, positions as bytes, an accessor far beyond
/// its view. Each must be refused quickly; mutations of them must not panic, hang or
/// allocate beyond what their bytes describe.
fn hostile_samples() -> Vec<(Format, Vec<u8>)> {
    let mut out = Vec::new();
    let xyz = "property float x\nproperty float y\nproperty float z\n";
    for header in [
        "ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nend_header\n".to_string(),
        format!("ply\nformat binary_little_endian 1.0\nelement vertex 3\n{xyz}element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n"),
        format!("ply\nformat ascii 1.0\nelement vertex 3\n{xyz}element face 4000000000\nproperty list uchar int vertex_indices\nend_header\n"),
    ] {
        let mut b = header.into_bytes();
        b.resize(250, b'0');
        out.push((Format::Ply, b));
    }
    out.push((
        Format::Off,
        b"OFF\n4000000000 4000000000 0\n0 0 0\n".to_vec(),
    ));
    let mut stl = vec![0u8; 134];
    stl[80..84].copy_from_slice(&u32::MAX.to_le_bytes());
    out.push((Format::Stl, stl));
    let (json, bin) = gltf_parts(&cube());
    let mut dag: Vec<String> = (0..17)
        .map(|k| format!(r#"{{"children":[{},{}]}}"#, k + 1, k + 1))
        .collect();
    dag.push(r#"{"name":"a","mesh":0}"#.into());
    let nodes_at = json.find("\"nodes\":[{").unwrap();
    let nodes_end = nodes_at + json[nodes_at..].find("}],").unwrap() + 2;
    let with_nodes = |nodes: &str| {
        format!(
            "{}\"nodes\":{nodes}{}",
            &json[..nodes_at],
            &json[nodes_end..]
        )
    };
    for variant in [
        with_nodes(&format!("[{}]", dag.join(","))).replace("\"nodes\":[0,1]", "\"nodes\":[0]"),
        with_nodes(r#"[{"mesh":0,"children":[1]},{"mesh":0,"children":[0]}]"#),
        json.replace("[0,0,0.7071068,0.7071068]", "[0,0,0,0]"),
        json.replace("[0,0,0.7071068,0.7071068]", "[1e39,0,0,1]"),
        json.replace("\"componentType\":5126", "\"componentType\":5121"),
        json.replace("\"count\":8", "\"count\":100000000"),
    ] {
        out.push((Format::Gltf, glb(&variant, &bin)));
    }
    out
}

/// Prisms over 40-gons (beyond the 32 vertices where triangulation switches from fans
/// and ear clipping to strips and the sweep), convex and toothed: mutations make their
/// caps non-planar, non-simple or touching, and must not panic.
fn polygon_samples() -> Vec<(Format, Vec<u8>)> {
    [1.0, 0.8]
        .iter()
        .map(|&inner| {
            let k = 40u32;
            let mut vertices = Vec::new();
            for z in [0.0, 3.0] {
                for i in 0..k {
                    let a = std::f64::consts::TAU * i as f64 / k as f64;
                    let r = if i % 2 == 1 { 20.0 * inner } else { 20.0 };
                    vertices.push([(r * a.cos()).round(), (r * a.sin()).round(), z]);
                }
            }
            let mut faces = vec![(0..k).rev().collect::<Vec<_>>(), (k..2 * k).collect()];
            for i in 0..k {
                let j = (i + 1) % k;
                faces.push(vec![i, j, k + j, k + i]);
            }
            let mut b = Vec::new();
            off::write(&mut b, &vertices, &Polygons::from(faces)).unwrap();
            (Format::Off, b)
        })
        .collect()
}

/// Reads, and validates whatever was read: must not panic.
fn exercise(format: Format, bytes: &[u8]) {
    if let Ok(objects) = read_bytes(bytes, format, None) {
        for o in objects.iter().take(4) {
            let finite = o
                .vertices
                .iter()
                .flatten()
                .copied()
                .filter(|v| v.is_finite());
            if let Ok(grid) = Grid::choose(finite, 30) {
                let _ = check_solid(o, &grid);
            }
        }
    }
}

#[test]
fn samples_are_valid_solids() {
    apart_formats::quiet_parser_panics();
    for (format, bytes) in samples() {
        let objects = read_bytes(&bytes, format, None).unwrap_or_else(|e| panic!("{format}: {e}"));
        assert!(!objects.is_empty());
        for o in &objects {
            let grid = Grid::choose(o.vertices.iter().flatten().copied(), 30).unwrap();
            let (_, info, problems) = check_solid(o, &grid);
            assert!(problems.is_empty(), "{format}: {problems:?}");
            assert_eq!(
                info.unwrap().volume_units(&grid).unwrap().to_string(),
                "1/2",
                "{format}"
            );
        }
    }
}

#[test]
fn polygon_samples_are_valid_solids() {
    for (format, bytes) in polygon_samples() {
        let objects = read_bytes(&bytes, format, None).unwrap();
        let grid = Grid::choose(objects[0].vertices.iter().flatten().copied(), 30).unwrap();
        let (_, info, problems) = check_solid(&objects[0], &grid);
        assert!(problems.is_empty(), "{problems:?}");
        assert_eq!(info.unwrap().triangles, 4 * 40 - 4);
    }
}

#[test]
fn hostile_samples_are_refused_quickly() {
    apart_formats::quiet_parser_panics();
    for (format, bytes) in hostile_samples() {
        let t = std::time::Instant::now();
        let e = read_bytes(&bytes, format, None).unwrap_err().to_string();
        assert!(!e.contains("parser failed"), "{format}: {e}");
        assert!(t.elapsed().as_secs() < 5, "{format}: {e}");
    }
}

#[derive(Clone, Debug)]
enum Mutation {
    Flip(usize, u8),
    Truncate(usize),
    Insert(usize, Vec<u8>),
    Delete(usize, usize),
}

fn apply(bytes: &[u8], muts: &[Mutation]) -> Vec<u8> {
    let mut b = bytes.to_vec();
    for m in muts {
        if b.is_empty() {
            break;
        }
        match m {
            Mutation::Flip(i, x) => {
                let i = i % b.len();
                b[i] ^= x | 1;
            }
            Mutation::Truncate(i) => b.truncate(i % b.len()),
            Mutation::Insert(i, g) => {
                let i = i % (b.len() + 1);
                b.splice(i..i, g.iter().copied());
            }
            Mutation::Delete(i, n) => {
                let i = i % b.len();
                let j = (i + n).min(b.len());
                b.drain(i..j);
            }
        }
    }
    b
}

fn mutation() -> impl Strategy<Value = Mutation> {
    prop_oneof![
        (any::<usize>(), any::<u8>()).prop_map(|(i, x)| Mutation::Flip(i, x)),
        any::<usize>().prop_map(Mutation::Truncate),
        (any::<usize>(), prop::collection::vec(any::<u8>(), 1..16))
            .prop_map(|(i, g)| Mutation::Insert(i, g)),
        (any::<usize>(), any::<usize>()).prop_map(|(i, g)| {
            // Digits and separators stress the text parsers more than random bytes.
            let text = [
                "-",
                "1e308",
                "nan",
                " ",
                "\n",
                "9",
                ".",
                "#",
                "999999999",
                "-0",
                "inf",
            ];
            Mutation::Insert(i, text[g % text.len()].as_bytes().to_vec())
        }),
        (any::<usize>(), 1usize..8).prop_map(|(i, n)| Mutation::Delete(i, n)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn random_bytes_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..600), f in 0usize..5) {
        apart_formats::quiet_parser_panics();
        exercise(Format::ALL[f], &bytes);
    }

    #[test]
    fn mutated_files_never_panic(which in 0usize..9, muts in prop::collection::vec(mutation(), 1..6)) {
        apart_formats::quiet_parser_panics();
        let s = samples();
        let (format, bytes) = &s[which % s.len()];
        exercise(*format, &apply(bytes, &muts));
    }

    #[test]
    fn mutated_large_polygons_never_panic(which in 0usize..2, muts in prop::collection::vec(mutation(), 1..6)) {
        apart_formats::quiet_parser_panics();
        let s = polygon_samples();
        let (format, bytes) = &s[which % s.len()];
        exercise(*format, &apply(bytes, &muts));
    }

    #[test]
    fn mutated_hostile_files_never_panic(which in 0usize..11, muts in prop::collection::vec(mutation(), 1..6)) {
        apart_formats::quiet_parser_panics();
        let s = hostile_samples();
        let (format, bytes) = &s[which % s.len()];
        exercise(*format, &apply(bytes, &muts));
    }

    /// Any declared count in a header, with whatever bytes follow: an answer (usually
    /// an error) without allocating for the count.
    #[test]
    fn declared_counts_are_bounded(
        which in 0usize..5,
        count in prop_oneof![0u64..16, any::<u32>().prop_map(u64::from), any::<u64>()],
        tail in prop::collection::vec(any::<u8>(), 0..200),
    ) {
        apart_formats::quiet_parser_panics();
        let (format, mut bytes) = match which {
            0 => (Format::Ply, format!("ply\nformat binary_little_endian 1.0\nelement vertex {count}\nproperty float x\nproperty float y\nproperty float z\nend_header\n").into_bytes()),
            1 => (Format::Ply, format!("ply\nformat binary_big_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement junk {count}\nend_header\n").into_bytes()),
            2 => (Format::Ply, format!("ply\nformat ascii 1.0\nelement vertex 1\nproperty float x\nproperty float y\nproperty float z\nelement face {count}\nproperty list uchar int vertex_indices\nend_header\n0 0 0\n").into_bytes()),
            3 => (Format::Off, format!("OFF\n{count} {count} 0\n").into_bytes()),
            _ => {
                let mut b = vec![0u8; 80];
                b.extend_from_slice(&(count as u32).to_le_bytes());
                (Format::Stl, b)
            }
        };
        bytes.extend_from_slice(&tail);
        exercise(format, &bytes);
    }
}
