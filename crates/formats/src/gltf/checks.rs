//! Checks made before the document is walked: the GLB container, the position
//! accessors the gltf crate would index unchecked, and the size of the node
//! hierarchy once expanded.

use super::meshes::mesh_values;
use super::{malformed, node_label, MAX_EXPANDED_VALUES, MAX_MESH_INSTANCES, MAX_NODE_INSTANCES};
use crate::escape::quoted;
use crate::ReadError;

/// Checks the hierarchy below `roots` before it is walked: no cycle, and at most
/// [`MAX_NODE_INSTANCES`] nodes, [`MAX_MESH_INSTANCES`] meshes and
/// [`MAX_EXPANDED_VALUES`] vertices and indices once every node is instanced under
/// each parent that lists it. Counts are summed bottom-up over the graph (each node
/// once), so a small file describing billions of instances is refused in linear time.
/// Returns which nodes are reachable from the roots.
pub(super) fn check_hierarchy(
    document: &gltf::Document,
    roots: &[gltf::Node],
) -> Result<Vec<bool>, ReadError> {
    let nodes: Vec<gltf::Node> = document.nodes().collect();
    // Per node: (nodes, meshes, values) in the subtree it expands to, saturating.
    let mut below: Vec<Option<[u64; 3]>> = vec![None; nodes.len()];
    let mut on_path = vec![false; nodes.len()];
    for root in roots {
        // Iterative depth-first search: (node, next child to visit).
        let mut stack: Vec<(usize, usize)> = Vec::new();
        if below[root.index()].is_none() {
            stack.push((root.index(), 0));
            on_path[root.index()] = true;
        }
        while let Some(&mut (n, ref mut next)) = stack.last_mut() {
            let child = nodes[n].children().nth(*next);
            *next += 1;
            match child {
                Some(c) => {
                    let c = c.index();
                    if on_path[c] {
                        return Err(malformed(format!(
                            "{} lists {} as a child, which is also its ancestor: the node hierarchy has a cycle",
                            node_label(&nodes[n]),
                            node_label(&nodes[c])
                        )));
                    }
                    if below[c].is_none() {
                        on_path[c] = true;
                        stack.push((c, 0));
                    }
                }
                None => {
                    let node = &nodes[n];
                    let mut sum = [1, 0, 0];
                    if let Some(m) = node.mesh() {
                        sum[1] = 1;
                        sum[2] = mesh_values(&m);
                    }
                    for c in node.children() {
                        let b = below[c.index()].expect("children are done first");
                        for k in 0..3 {
                            sum[k] = sum[k].saturating_add(b[k]);
                        }
                    }
                    below[n] = Some(sum);
                    on_path[n] = false;
                    stack.pop();
                }
            }
        }
    }
    let mut total = [0u64; 3];
    for r in roots {
        let b = below[r.index()].expect("every root was walked");
        for k in 0..3 {
            total[k] = total[k].saturating_add(b[k]);
        }
    }
    let saturated = |v: u64| {
        if v == u64::MAX {
            "more than 2^64".to_string()
        } else {
            v.to_string()
        }
    };
    let why = "a node listed as the child of several nodes is instanced under each";
    if total[0] > MAX_NODE_INSTANCES as u64 {
        return Err(malformed(format!(
            "the scene's node hierarchy expands to {} node instances ({why}), more than the limit of {MAX_NODE_INSTANCES}",
            saturated(total[0])
        )));
    }
    if total[1] > MAX_MESH_INSTANCES as u64 {
        return Err(malformed(format!(
            "the scene's node hierarchy expands to {} mesh instances ({why}), more than the limit of {MAX_MESH_INSTANCES}",
            saturated(total[1])
        )));
    }
    if total[2] > MAX_EXPANDED_VALUES {
        return Err(malformed(format!(
            "the scene's meshes, each counted once per instance ({why}), hold {} vertices and indices, more than the limit of {MAX_EXPANDED_VALUES}",
            saturated(total[2])
        )));
    }
    Ok(below.iter().map(Option::is_some).collect())
}

/// Checks that every primitive's `POSITION` names an accessor that exists (the gltf
/// crate's validation indexes it without checking, and panics).
pub(super) fn check_position_indices(root: &gltf::json::Root) -> Result<(), ReadError> {
    let positions = gltf::json::validation::Checked::Valid(gltf::Semantic::Positions);
    for (m, mesh) in root.meshes.iter().enumerate() {
        for (p, prim) in mesh.primitives.iter().enumerate() {
            if let Some(a) = prim.attributes.get(&positions) {
                if a.value() >= root.accessors.len() {
                    return Err(malformed(format!(
                        "mesh {m}, primitive {p}: POSITION is accessor {}, but there are only {} accessors",
                        a.value(),
                        root.accessors.len()
                    )));
                }
            }
        }
    }
    Ok(())
}

/// The name of a GLB chunk type, as a message shows it.
fn chunk_type(ty: &[u8]) -> String {
    match ty {
        b"JSON" => "JSON".to_string(),
        b"BIN\0" => "BIN".to_string(),
        _ => quoted(&String::from_utf8_lossy(ty)),
    }
}

/// Checks the GLB container before the gltf crate reads it: the header's length is the
/// file's, and the chunks (JSON first, then BIN if any, then any others) tile the rest
/// exactly.
pub(super) fn check_glb(bytes: &[u8]) -> Result<(), ReadError> {
    let word =
        |at: usize| u32::from_le_bytes([bytes[at], bytes[at + 1], bytes[at + 2], bytes[at + 3]]);
    if bytes.len() < 12 {
        return Err(malformed(format!(
            "the GLB file has {} bytes, fewer than its 12-byte header",
            bytes.len()
        )));
    }
    let declared = word(8) as usize;
    if declared != bytes.len() {
        return Err(malformed(format!(
            "the GLB header declares {declared} bytes but the file has {}",
            bytes.len()
        )));
    }
    let mut at = 12;
    for k in 0.. {
        let left = bytes.len() - at;
        if left == 0 {
            break;
        }
        if left < 8 {
            let after = match k {
                0 => "the header".to_string(),
                k => format!("chunk {}", k - 1),
            };
            return Err(malformed(format!(
                "{left} bytes at byte offset {at}, after {after}, are too few for a chunk header (8 bytes)"
            )));
        }
        let (length, ty) = (word(at) as usize, &bytes[at + 4..at + 8]);
        let what = format!("GLB chunk {k} ({}) at byte offset {at}", chunk_type(ty));
        if k == 0 && ty != b"JSON" {
            return Err(malformed(format!("{what}: the first chunk must be JSON")));
        }
        if length > left - 8 {
            return Err(malformed(format!(
                "{what} declares {length} bytes of data, but only {} are left in the file",
                left - 8
            )));
        }
        at += 8 + length;
    }
    Ok(())
}
