//! The animated GLB parsed back with the `gltf` crate (which validates the document):
//! structure, bounds, key times, and final translations against the plan.

mod common;

use apart_assembly::Assembly;
use apart_draw::disassembly_glb;
use apart_plan::Sequence;
use gltf::animation::util::ReadOutputs;

/// Parses a GLB as `gltf::import_slice` would (the document validated, every buffer
/// present and at least its declared length), without the `import` feature: it would
/// turn on image codecs in the gltf crate that the binary shares, and
/// `cargo test --release` would then compile the gltf crate and every crate above it
/// a second time.
fn parse(bytes: &[u8]) -> (gltf::Document, Vec<Vec<u8>>) {
    let gltf::Gltf { document, mut blob } =
        gltf::Gltf::from_slice(bytes).expect("a valid glTF 2.0 binary");
    let buffers = document
        .buffers()
        .map(|b| {
            assert!(
                matches!(b.source(), gltf::buffer::Source::Bin),
                "buffer {} is not the binary chunk",
                b.index()
            );
            let data = blob.take().expect("one binary chunk per buffer");
            assert!(data.len() >= b.length(), "buffer {} is short", b.index());
            data
        })
        .collect();
    (document, buffers)
}

/// Parses `bytes` and checks everything that does not depend on the example.
fn check(assembly: &Assembly, plan: &Sequence, bytes: &[u8]) {
    // GLB header: magic, version 2, total length.
    assert_eq!(&bytes[0..4], b"glTF");
    assert_eq!(u32::from_le_bytes(bytes[4..8].try_into().unwrap()), 2);
    assert_eq!(
        u32::from_le_bytes(bytes[8..12].try_into().unwrap()) as usize,
        bytes.len()
    );
    assert_eq!(bytes.len() % 4, 0);

    let (doc, buffers) = parse(bytes);
    let n = assembly.parts.len();
    assert_eq!(
        doc.nodes().count(),
        n + 1,
        "a root node and one node per part"
    );
    assert_eq!(doc.meshes().count(), n);
    assert_eq!(doc.materials().count(), n);
    assert_eq!(doc.scenes().count(), 1);
    let root = doc.scenes().next().unwrap().nodes().next().unwrap();
    assert_eq!(root.children().count(), n);

    // One node per part, named after it, each with a mesh whose positions carry bounds
    // equal to the bounds of the data, with normals of unit length.
    let diag = common::diagonal(assembly);
    for (k, node) in root.children().enumerate() {
        assert_eq!(node.name(), Some(assembly.parts[k].name.as_str()));
        let mesh = node.mesh().expect("every part has a mesh");
        for prim in mesh.primitives() {
            assert_eq!(prim.mode(), gltf::mesh::Mode::Triangles);
            let pos = prim.get(&gltf::Semantic::Positions).unwrap();
            let min = pos.min().expect("positions have min");
            let max = pos.max().expect("positions have max");
            let reader = prim.reader(|b| Some(&buffers[b.index()][..]));
            let points: Vec<[f32; 3]> = reader.read_positions().unwrap().collect();
            assert_eq!(points.len() % 3, 0);
            for c in 0..3 {
                let lo = points.iter().map(|p| p[c]).fold(f32::INFINITY, f32::min);
                let hi = points
                    .iter()
                    .map(|p| p[c])
                    .fold(f32::NEG_INFINITY, f32::max);
                assert_eq!(min[c].as_f64().unwrap() as f32, lo);
                assert_eq!(max[c].as_f64().unwrap() as f32, hi);
            }
            let normals: Vec<[f32; 3]> = reader.read_normals().unwrap().collect();
            assert_eq!(normals.len(), points.len());
            for v in normals {
                let l = (v[0] * v[0] + v[1] * v[1] + v[2] * v[2]).sqrt();
                assert!((l - 1.0).abs() < 1e-5);
            }
        }
    }

    // One animation, a translation channel per part node, increasing key times.
    assert_eq!(doc.animations().count(), 1);
    let anim = doc.animations().next().unwrap();
    assert_eq!(anim.channels().count(), n);
    for channel in anim.channels() {
        assert_eq!(
            channel.target().property(),
            gltf::animation::Property::Translation
        );
        let k = channel.target().node().index() - 1;
        let reader = channel.reader(|b| Some(&buffers[b.index()][..]));
        let times: Vec<f32> = reader.read_inputs().unwrap().collect();
        assert!(times.windows(2).all(|w| w[0] < w[1]), "{times:?}");
        assert_eq!(times[0], 0.0);
        let Some(ReadOutputs::Translations(out)) = reader.read_outputs() else {
            panic!("translation outputs");
        };
        let out: Vec<[f32; 3]> = out.collect();
        assert_eq!(out.len(), times.len());
        // Nothing has moved at the start; at the end the part has moved by the sum of
        // the displacements (1.5 diagonals along the unit direction) of its steps.
        assert_eq!(out[0], [0.0; 3]);
        let mut want = [0.0f64; 3];
        for step in plan.steps.iter().filter(|s| s.moving.contains(&k)) {
            for (w, u) in want.iter_mut().zip(step.unit) {
                *w += 1.5 * diag * u;
            }
        }
        let last = out.last().unwrap();
        for c in 0..3 {
            assert!(
                (last[c] as f64 - want[c]).abs() <= 1e-5 * diag.max(1.0),
                "part {k}: {last:?} vs {want:?}"
            );
        }
    }
}

#[test]
fn split_star_glb_parses_back_with_the_plan_in_its_animation() {
    let a = common::example("split-star-3");
    let (_, plan) = common::plan(&a);
    assert_eq!(plan.steps.len(), 5);
    let bytes = disassembly_glb(&a, &plan);
    check(&a, &plan, &bytes);
    // The meshes are in input units: their bounds are those of the loaded meshes.
    let (doc, _) = parse(&bytes);
    let red = doc.meshes().next().unwrap();
    let pos = red
        .primitives()
        .next()
        .unwrap()
        .get(&gltf::Semantic::Positions)
        .unwrap();
    let min: Vec<f64> = pos
        .min()
        .unwrap()
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    let max: Vec<f64> = pos
        .max()
        .unwrap()
        .as_array()
        .unwrap()
        .iter()
        .map(|v| v.as_f64().unwrap())
        .collect();
    assert_eq!(min, vec![-2.0, -1.0, 0.0]);
    assert_eq!(max, vec![2.0, 1.0, 2.0]);
}

#[test]
fn parts_given_only_by_pieces_and_a_twenty_part_plan_export() {
    let a = common::assembly_of("bricks", common::brick_rows());
    let (_, plan) = common::plan(&a);
    assert!(plan.complete());
    assert_eq!(plan.steps.len(), 19);
    check(&a, &plan, &disassembly_glb(&a, &plan));
}

#[test]
fn an_assembly_without_steps_still_exports() {
    let a = common::assembly_of(
        "one",
        vec![common::part(
            "cube",
            vec![common::cuboid([0, 0, 0], [1, 1, 1])],
        )],
    );
    let (_, plan) = common::plan(&a);
    let bytes = disassembly_glb(&a, &plan);
    let (doc, _) = parse(&bytes);
    assert_eq!(doc.nodes().count(), 2);
    assert_eq!(doc.animations().count(), 0);
}
