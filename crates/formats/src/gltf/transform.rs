//! A node's own transform, read from its matrix or its translation, rotation and
//! scale, and refused when it is not a finite affine map with a unit rotation.

use super::{malformed, node_label, QUATERNION_TOLERANCE};
use crate::transform::{Affine, TOL_F32};
use crate::ReadError;

/// `[1, 0.5, 2]`: values as a message lists them.
fn list(v: &[f32]) -> String {
    let items: Vec<String> = v.iter().map(|x| x.to_string()).collect();
    format!("[{}]", items.join(", "))
}

/// The node's own transform; errors for values that are not finite, a matrix that is
/// not affine, and a rotation that is not a unit quaternion.
pub(super) fn local_transform(node: &gltf::Node) -> Result<Affine, ReadError> {
    let bad = |what: String| malformed(format!("{}: {what}", node_label(node)));
    match node.transform() {
        gltf::scene::Transform::Matrix { matrix: c } => {
            let flat: Vec<f32> = c.iter().flatten().copied().collect();
            if flat.iter().any(|v| !v.is_finite()) {
                return Err(bad(format!(
                    "its matrix {} has a value that is not a finite number",
                    list(&flat)
                )));
            }
            // Column-major.
            let mut rows = [[0.0f64; 4]; 4];
            for (j, col) in c.iter().enumerate() {
                for (i, v) in col.iter().enumerate() {
                    rows[i][j] = *v as f64;
                }
            }
            let last = rows[3];
            if last
                .iter()
                .zip([0.0, 0.0, 0.0, 1.0])
                .any(|(v, want)| (v - want).abs() > TOL_F32)
            {
                return Err(bad(format!(
                    "its matrix is not affine: the last row is {}, not [0, 0, 0, 1]",
                    list(&last.map(|v| v as f32))
                )));
            }
            rows[3] = [0.0, 0.0, 0.0, 1.0];
            Ok(Affine::from_rows(rows).expect("last row set"))
        }
        gltf::scene::Transform::Decomposed {
            translation,
            rotation,
            scale,
        } => {
            for (what, v) in [
                ("translation", &translation[..]),
                ("rotation", &rotation[..]),
                ("scale", &scale[..]),
            ] {
                if v.iter().any(|x| !x.is_finite()) {
                    return Err(bad(format!(
                        "its {what} {} has a value that is not a finite number",
                        list(v)
                    )));
                }
            }
            let q = rotation.map(|v| v as f64);
            let norm = q.iter().map(|v| v * v).sum::<f64>().sqrt();
            // Finite: the components are finite f32 values.
            if (norm - 1.0).abs() > QUATERNION_TOLERANCE {
                return Err(bad(format!(
                    "its rotation {} is not a unit quaternion (norm {norm}, which must be 1 within {QUATERNION_TOLERANCE})",
                    list(&rotation)
                )));
            }
            let r = Affine::quaternion(q).expect("a norm near 1");
            let s = Affine::scale(scale.map(|v| v as f64));
            Ok(Affine::translation(translation.map(|v| v as f64)).then_after(&r.then_after(&s)))
        }
    }
}
