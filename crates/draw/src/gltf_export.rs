//! The animated disassembly as a binary glTF 2.0 file (GLB).
//!
//! Layout: one scene with a root node `assembly` that turns the input's z-up frame into
//! glTF's y-up frame (a rotation of −90° about x), and under it one node per part, named
//! after the part, with its own mesh (flat-shaded triangles in input units: positions
//! with min/max, per-face normals) and material (the part's colour, matte). One
//! animation, `disassembly`, has a translation channel per part node: step `k` moves the
//! parts from keyframe `k` to keyframe `k + 1` ([`Keyframes`]: for a sequence, its
//! moving side out along its unit direction by `distance_factor` × the assembly's
//! bounding-box diagonal; for a plan of moves, by each move's translation) between
//! `k·(step + pause)` and `k·(step + pause) + step` seconds; the translations are in the
//! input frame (the root's).

use crate::colors::part_colors;
use crate::motion::{AnimationOptions, Keyframes};
use crate::shapes::{bounds_of, part_shapes, PartShape};
use apart_assembly::Assembly;
use apart_plan::Sequence;
use serde_json::{json, Value};

/// The disassembly of `assembly` by `sequence` as GLB bytes, with the default
/// [`AnimationOptions`] (1.5 diagonals per step, 1 s per step, 0.5 s pause).
pub fn disassembly_glb(assembly: &Assembly, sequence: &Sequence) -> Vec<u8> {
    disassembly_glb_with(assembly, sequence, &AnimationOptions::default())
}

/// [`disassembly_glb`] with chosen distances and timings.
pub fn disassembly_glb_with(
    assembly: &Assembly,
    sequence: &Sequence,
    opts: &AnimationOptions,
) -> Vec<u8> {
    let shapes = part_shapes(assembly);
    let distance = opts.distance_factor * bounds_of(&shapes, None).diagonal();
    let frames = Keyframes::of_sequence(sequence, shapes.len(), distance);
    animated_glb(assembly, &shapes, &frames, opts)
}

/// The GLB of `assembly` (its surfaces `shapes`) playing `frames` with `opts`' timings.
pub(crate) fn animated_glb(
    assembly: &Assembly,
    shapes: &[PartShape],
    frames: &Keyframes,
    opts: &AnimationOptions,
) -> Vec<u8> {
    let names: Vec<&str> = assembly.parts.iter().map(|p| p.name.as_str()).collect();
    let colors = part_colors(&names);

    let mut w = Writer::default();
    let mut nodes = vec![json!({
        "name": "assembly",
        "rotation": [-std::f64::consts::FRAC_1_SQRT_2, 0.0, 0.0, std::f64::consts::FRAC_1_SQRT_2],
        "children": (1..=shapes.len()).collect::<Vec<_>>(),
    })];
    let mut meshes = Vec::new();
    let mut materials = Vec::new();
    for (k, shape) in shapes.iter().enumerate() {
        let c = colors[k].linear();
        materials.push(json!({
            "name": names[k],
            "pbrMetallicRoughness": {
                "baseColorFactor": [c[0], c[1], c[2], 1.0],
                "metallicFactor": 0.0,
                "roughnessFactor": 0.7,
            },
        }));
        let mut node = json!({ "name": names[k] });
        if !shape.triangles.is_empty() {
            let (positions, normals) = flat_vertices(shape);
            let pos = w.accessor_vec3(&positions, Some(ARRAY_BUFFER), true);
            let nor = w.accessor_vec3(&normals, Some(ARRAY_BUFFER), false);
            node["mesh"] = json!(meshes.len());
            meshes.push(json!({
                "name": names[k],
                "primitives": [{
                    "attributes": { "POSITION": pos, "NORMAL": nor },
                    "material": k,
                    "mode": 4,
                }],
            }));
        }
        nodes.push(node);
    }

    let mut animations = Vec::new();
    if frames.steps() > 0 {
        // Keys at each step's start (everything where the previous steps left it) and
        // end (its moving side displaced); a start equal to the previous end is merged.
        let step = opts.step_seconds.max(1e-3);
        let period = step + opts.pause_seconds.max(0.0);
        let mut keys: Vec<(f64, usize)> = Vec::new();
        for k in 0..frames.steps() {
            let start = k as f64 * period;
            if keys.last().is_none_or(|&(t, _)| t < start - 1e-6) {
                keys.push((start, k));
            }
            keys.push((start + step, k + 1));
        }
        let times: Vec<f64> = keys.iter().map(|&(t, _)| t).collect();
        let input = w.accessor_scalar(&times);
        let mut samplers = Vec::new();
        let mut channels = Vec::new();
        for k in 0..shapes.len() {
            let values: Vec<[f64; 3]> = keys
                .iter()
                .map(|&(_, done)| frames.offsets[done][k])
                .collect();
            let output = w.accessor_vec3(&values, None, false);
            channels.push(json!({
                "sampler": samplers.len(),
                "target": { "node": k + 1, "path": "translation" },
            }));
            samplers.push(json!({ "input": input, "output": output, "interpolation": "LINEAR" }));
        }
        animations
            .push(json!({ "name": "disassembly", "samplers": samplers, "channels": channels }));
    }

    let mut root = json!({
        "asset": { "version": "2.0", "generator": "apart-draw" },
        "scene": 0,
        "scenes": [{ "name": assembly.name, "nodes": [0] }],
        "nodes": nodes,
        "materials": materials,
    });
    if !meshes.is_empty() {
        root["meshes"] = json!(meshes);
    }
    if !animations.is_empty() {
        root["animations"] = json!(animations);
    }
    if !w.bin.is_empty() {
        root["buffers"] = json!([{ "byteLength": w.bin.len() }]);
        root["bufferViews"] = json!(w.views);
        root["accessors"] = json!(w.accessors);
    }
    glb(
        &serde_json::to_vec(&root).expect("JSON of plain values"),
        &w.bin,
    )
}

/// `bufferView.target` for vertex attributes.
const ARRAY_BUFFER: u32 = 34962;
/// `accessor.componentType` for 32-bit floats.
const FLOAT: u32 = 5126;

/// Three vertices per triangle, each with its triangle's normal.
fn flat_vertices(shape: &PartShape) -> (Vec<[f64; 3]>, Vec<[f64; 3]>) {
    let mut positions = Vec::with_capacity(3 * shape.triangles.len());
    let mut normals = Vec::with_capacity(3 * shape.triangles.len());
    for (t, tri) in shape.triangles.iter().enumerate() {
        let n = shape.normal(t);
        for p in tri {
            positions.push(*p);
            normals.push(n);
        }
    }
    (positions, normals)
}

/// The binary chunk and the buffer views and accessors describing it.
#[derive(Default)]
struct Writer {
    bin: Vec<u8>,
    views: Vec<Value>,
    accessors: Vec<Value>,
}

impl Writer {
    fn view(&mut self, bytes: &[u8], target: Option<u32>) -> usize {
        let offset = self.bin.len();
        self.bin.extend_from_slice(bytes);
        let mut v = json!({ "buffer": 0, "byteOffset": offset, "byteLength": bytes.len() });
        if let Some(t) = target {
            v["target"] = json!(t);
        }
        self.views.push(v);
        self.views.len() - 1
    }

    fn accessor_vec3(&mut self, values: &[[f64; 3]], target: Option<u32>, bounds: bool) -> usize {
        let floats: Vec<[f32; 3]> = values.iter().map(|v| v.map(|c| c as f32)).collect();
        let bytes: Vec<u8> = floats
            .iter()
            .flatten()
            .flat_map(|c| c.to_le_bytes())
            .collect();
        let view = self.view(&bytes, target);
        let mut a = json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": values.len(),
            "type": "VEC3",
        });
        if bounds {
            // The bounds of the stored f32 values, as the specification requires.
            let mut min = [f32::INFINITY; 3];
            let mut max = [f32::NEG_INFINITY; 3];
            for v in &floats {
                for k in 0..3 {
                    min[k] = min[k].min(v[k]);
                    max[k] = max[k].max(v[k]);
                }
            }
            a["min"] = json!(min);
            a["max"] = json!(max);
        }
        self.accessors.push(a);
        self.accessors.len() - 1
    }

    fn accessor_scalar(&mut self, values: &[f64]) -> usize {
        let floats: Vec<f32> = values.iter().map(|&v| v as f32).collect();
        let bytes: Vec<u8> = floats.iter().flat_map(|c| c.to_le_bytes()).collect();
        let view = self.view(&bytes, None);
        let min = floats.iter().copied().fold(f32::INFINITY, f32::min);
        let max = floats.iter().copied().fold(f32::NEG_INFINITY, f32::max);
        self.accessors.push(json!({
            "bufferView": view,
            "componentType": FLOAT,
            "count": values.len(),
            "type": "SCALAR",
            "min": [min],
            "max": [max],
        }));
        self.accessors.len() - 1
    }
}

/// The GLB container: header, JSON chunk (padded with spaces), BIN chunk (padded with
/// zeros), each chunk 4-byte aligned.
fn glb(json: &[u8], bin: &[u8]) -> Vec<u8> {
    let pad = |n: usize| (4 - n % 4) % 4;
    let json_len = json.len() + pad(json.len());
    let bin_len = bin.len() + pad(bin.len());
    let total = 12 + 8 + json_len + if bin.is_empty() { 0 } else { 8 + bin_len };
    let mut out = Vec::with_capacity(total);
    out.extend_from_slice(b"glTF");
    out.extend_from_slice(&2u32.to_le_bytes());
    out.extend_from_slice(&(total as u32).to_le_bytes());
    out.extend_from_slice(&(json_len as u32).to_le_bytes());
    out.extend_from_slice(b"JSON");
    out.extend_from_slice(json);
    out.extend(std::iter::repeat_n(b' ', pad(json.len())));
    if !bin.is_empty() {
        out.extend_from_slice(&(bin_len as u32).to_le_bytes());
        out.extend_from_slice(b"BIN\0");
        out.extend_from_slice(bin);
        out.extend(std::iter::repeat_n(0u8, pad(bin.len())));
    }
    out
}
