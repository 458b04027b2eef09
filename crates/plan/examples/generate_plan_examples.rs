//! Writes the example assemblies of the planners under `examples/` (the Split Star is
//! written by `cargo run -p apart-assembly --example generate_examples`):
//!
//! - `dovetail-and-cap/`: a dovetail slot (one part of four convex pieces), its
//!   trapezoidal tenon, and a cap closing the slot's open end;
//! - `hinge/`: a bolt (shaft and head) through a U-bracket and the tongue between its
//!   cheeks, like paper 000 fig. 7; the bracket and the tongue are plain meshes with
//!   holes (decomposed automatically);
//! - `tray-of-cubes/`: 20 parts: a tray (one non-convex mesh), 18 unit cubes filling it
//!   in two layers, and a lid;
//! - `linked-rings/`: two square rings linked like chain links (interlocked);
//! - `ring-and-cone/`: two 2,048-triangle rings stacked around a 158-triangle cone, like
//!   paper 000 fig. 2 (the rings are plain meshes, decomposed automatically).
//!
//! `cargo run -p apart-plan --example generate_plan_examples [-- OUT_DIR]`

use apart_formats::{off, Polygons};
use apart_testkit::shapes;
use std::collections::HashMap;
use std::path::{Path, PathBuf};

type Mesh = (Vec<[f64; 3]>, Vec<[u32; 3]>);

/// The closed boundary of a union of boxes `[lo, hi]` with integer corners: the faces
/// between covered and uncovered cells of the grid of all box coordinates, two
/// triangles each, outward, welded.
fn boxes_mesh(boxes: &[([i64; 3], [i64; 3])]) -> Mesh {
    let mut axes: [Vec<i64>; 3] = [vec![], vec![], vec![]];
    for (lo, hi) in boxes {
        for k in 0..3 {
            axes[k].push(lo[k]);
            axes[k].push(hi[k]);
        }
    }
    for a in &mut axes {
        a.sort_unstable();
        a.dedup();
    }
    let n = [axes[0].len() - 1, axes[1].len() - 1, axes[2].len() - 1];
    let filled = |c: [isize; 3]| -> bool {
        if (0..3).any(|k| c[k] < 0 || c[k] >= n[k] as isize) {
            return false;
        }
        let mid =
            [0, 1, 2].map(|k| (axes[k][c[k] as usize] + axes[k][c[k] as usize + 1]) as f64 / 2.0);
        boxes
            .iter()
            .any(|(lo, hi)| (0..3).all(|k| lo[k] as f64 <= mid[k] && mid[k] <= hi[k] as f64))
    };
    let mut ids: HashMap<[i64; 3], u32> = HashMap::new();
    let mut points: Vec<[f64; 3]> = Vec::new();
    let mut id = |p: [i64; 3], points: &mut Vec<[f64; 3]>| -> u32 {
        *ids.entry(p).or_insert_with(|| {
            points.push(p.map(|x| x as f64));
            (points.len() - 1) as u32
        })
    };
    let mut tris = Vec::new();
    for i in 0..n[0] as isize {
        for j in 0..n[1] as isize {
            for k in 0..n[2] as isize {
                let c = [i, j, k];
                if !filled(c) {
                    continue;
                }
                for axis in 0..3 {
                    for side in [0isize, 1] {
                        let mut nb = c;
                        nb[axis] += if side == 1 { 1 } else { -1 };
                        if filled(nb) {
                            continue;
                        }
                        // The face of cell c on this side: a rectangle in the plane
                        // axis = coordinate, spanned by the two other axes.
                        let (u, v) = ((axis + 1) % 3, (axis + 2) % 3);
                        let coord = |d: usize, t: isize| axes[d][(c[d] + t) as usize];
                        let at = |du: isize, dv: isize| {
                            let mut p = [0i64; 3];
                            p[axis] = coord(axis, side);
                            p[u] = coord(u, du);
                            p[v] = coord(v, dv);
                            p
                        };
                        let q =
                            [at(0, 0), at(1, 0), at(1, 1), at(0, 1)].map(|p| id(p, &mut points));
                        // (u, v, axis) is right-handed: counter-clockwise in (u, v) faces +axis.
                        if side == 1 {
                            tris.push([q[0], q[1], q[2]]);
                            tris.push([q[0], q[2], q[3]]);
                        } else {
                            tris.push([q[0], q[2], q[1]]);
                            tris.push([q[0], q[3], q[2]]);
                        }
                    }
                }
            }
        }
    }
    (points, tris)
}

fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Mesh {
    boxes_mesh(&[(lo, hi)])
}

/// A convex prism: polygon `yz` (counter-clockwise seen from +x) extruded over x0..x1.
fn prism_x(yz: &[[i64; 2]], x0: i64, x1: i64) -> Mesh {
    let n = yz.len() as u32;
    let mut pts = Vec::new();
    for &[y, z] in yz {
        pts.push([x0 as f64, y as f64, z as f64]);
    }
    for &[y, z] in yz {
        pts.push([x1 as f64, y as f64, z as f64]);
    }
    let mut tris = Vec::new();
    for k in 1..n - 1 {
        tris.push([0, k + 1, k]); // x0 end, facing -x
        tris.push([n, n + k, n + k + 1]); // x1 end, facing +x
    }
    for k in 0..n {
        let j = (k + 1) % n;
        tris.push([k, j, n + j]);
        tris.push([k, n + j, n + k]);
    }
    (pts, tris)
}

fn write_mesh(dir: &Path, file: &str, m: &Mesh) -> std::io::Result<()> {
    if let Some(parent) = dir.join(file).parent() {
        std::fs::create_dir_all(parent)?;
    }
    let mut f = std::fs::File::create(dir.join(file))?;
    off::write(&mut f, &m.0, &Polygons::from_triangles(&m.1))
}

/// A part: a name and either one mesh or convex pieces.
enum Spec {
    Mesh(Mesh),
    Pieces(Vec<Mesh>),
}

fn write_assembly(out: &Path, name: &str, parts: Vec<(&str, Spec)>) -> std::io::Result<()> {
    let dir = out.join(name);
    std::fs::create_dir_all(&dir)?;
    let mut entries = Vec::new();
    for (part, spec) in parts {
        match spec {
            Spec::Mesh(m) => {
                write_mesh(&dir, &format!("{part}.off"), &m)?;
                entries.push(format!(
                    "    {{\"name\": \"{part}\", \"mesh\": \"{part}.off\"}}"
                ));
            }
            Spec::Pieces(pieces) => {
                let mut files = Vec::new();
                for (k, m) in pieces.iter().enumerate() {
                    let f = format!("{part}/piece_{k}.off");
                    write_mesh(&dir, &f, m)?;
                    files.push(format!("\"{f}\""));
                }
                entries.push(format!(
                    "    {{\"name\": \"{part}\", \"pieces\": [{}]}}",
                    files.join(", ")
                ));
            }
        }
    }
    std::fs::write(
        dir.join("assembly.json"),
        format!(
            "{{\n  \"name\": \"{name}\",\n  \"parts\": [\n{}\n  ]\n}}\n",
            entries.join(",\n")
        ),
    )?;
    println!("wrote {}", dir.display());
    Ok(())
}

fn main() -> std::io::Result<()> {
    let out = std::env::args()
        .nth(1)
        .map(PathBuf::from)
        .unwrap_or_else(|| PathBuf::from(env!("CARGO_MANIFEST_DIR")).join("../../examples"));

    // Dovetail and cap: the tenon slides out along +x only after the cap is off.
    write_assembly(
        &out,
        "dovetail-and-cap",
        vec![
            (
                "slot",
                Spec::Pieces(vec![
                    cuboid([0, -4, 0], [10, 4, 1]),
                    prism_x(&[[-4, 1], [-3, 1], [-2, 3], [-4, 3]], 0, 10),
                    prism_x(&[[3, 1], [4, 1], [4, 3], [2, 3]], 0, 10),
                    cuboid([-1, -4, 0], [0, 4, 3]),
                ]),
            ),
            (
                "tenon",
                Spec::Pieces(vec![prism_x(&[[-3, 1], [3, 1], [2, 3], [-2, 3]], 0, 10)]),
            ),
            ("cap", Spec::Mesh(cuboid([10, -4, 0], [11, 4, 3]))),
        ],
    )?;

    // Hinge: a U-bracket (base and two cheeks with square holes), a tongue between the
    // cheeks with the same hole, and a bolt whose shaft fills the holes exactly and whose
    // head rests on the outer face of one cheek.
    let hole = |y0: i64, y1: i64, x: [i64; 2], z: [i64; 2]| -> Vec<([i64; 3], [i64; 3])> {
        // A plate x 0..12, z z0..z1 over y0..y1, minus the hole x 5..7, z 6..8.
        vec![
            ([x[0], y0, z[0]], [5, y1, z[1]]),
            ([7, y0, z[0]], [x[1], y1, z[1]]),
            ([5, y0, z[0]], [7, y1, 6]),
            ([5, y0, 8], [7, y1, z[1]]),
        ]
    };
    let mut bracket = vec![([0, -6, 0], [12, 6, 2])];
    bracket.extend(hole(-6, -4, [0, 12], [2, 12]));
    bracket.extend(hole(4, 6, [0, 12], [2, 12]));
    write_assembly(
        &out,
        "hinge",
        vec![
            ("bracket", Spec::Mesh(boxes_mesh(&bracket))),
            (
                "tongue",
                Spec::Mesh(boxes_mesh(&hole(-4, 4, [1, 13], [3, 11]))),
            ),
            (
                "bolt",
                Spec::Mesh(boxes_mesh(&[
                    ([5, -6, 6], [7, 6, 8]),
                    ([4, -7, 5], [8, -6, 9]),
                ])),
            ),
        ],
    )?;

    // Tray of cubes: 20 parts.
    let tray = vec![
        ([0, 0, 0], [5, 5, 1]),
        ([0, 0, 1], [1, 5, 3]),
        ([4, 0, 1], [5, 5, 3]),
        ([1, 0, 1], [4, 1, 3]),
        ([1, 4, 1], [4, 5, 3]),
    ];
    let mut parts: Vec<(String, Spec)> = vec![("tray".into(), Spec::Mesh(boxes_mesh(&tray)))];
    for z in 1..3 {
        for y in 1..4 {
            for x in 1..4 {
                parts.push((
                    format!("cube_{x}{y}{z}"),
                    Spec::Mesh(cuboid([x, y, z], [x + 1, y + 1, z + 1])),
                ));
            }
        }
    }
    parts.push(("lid".into(), Spec::Mesh(cuboid([0, 0, 3], [5, 5, 4]))));
    write_assembly(
        &out,
        "tray-of-cubes",
        parts
            .iter()
            .map(|(n, s)| (n.as_str(), clone_spec(s)))
            .collect(),
    )?;

    // Linked rings: each ring four bars (declared pieces).
    let bars = |b: &[([i64; 3], [i64; 3])]| {
        Spec::Pieces(b.iter().map(|&(lo, hi)| cuboid(lo, hi)).collect())
    };
    write_assembly(
        &out,
        "linked-rings",
        vec![
            (
                "ring_a",
                bars(&[
                    ([0, 0, 0], [6, 1, 1]),
                    ([0, 0, 5], [6, 1, 6]),
                    ([0, 0, 1], [1, 1, 5]),
                    ([5, 0, 1], [6, 1, 5]),
                ]),
            ),
            (
                "ring_b",
                bars(&[
                    ([2, -2, 2], [3, 3, 3]),
                    ([2, -2, -2], [3, 3, -1]),
                    ([2, -2, -1], [3, -1, 2]),
                    ([2, 2, -1], [3, 3, 2]),
                ]),
            ),
        ],
    )?;

    // Ring and cone.
    let ring = shapes::Ring::new(64);
    let r = ring.radius;
    let s = ring.shape();
    let lower: Mesh = (
        s.points.iter().map(|p| p.map(|c| c as f64)).collect(),
        s.tris.clone(),
    );
    let upper: Mesh = (
        s.points
            .iter()
            .map(|p| [p[0], p[1], p[2] + 16 * r].map(|c| c as f64))
            .collect(),
        s.tris.clone(),
    );
    let n = 80u32;
    let mut pts: Vec<[f64; 3]> = (0..n)
        .map(|k| {
            let t = std::f64::consts::TAU * k as f64 / n as f64;
            [
                (14.0 * r as f64 * t.cos()).round(),
                (14.0 * r as f64 * t.sin()).round(),
                (-20 * r) as f64,
            ]
        })
        .collect();
    pts.push([0.0, 0.0, (40 * r) as f64]);
    let mut tris: Vec<[u32; 3]> = (0..n).map(|k| [k, (k + 1) % n, n]).collect();
    for k in 1..n - 1 {
        tris.push([0, k + 1, k]);
    }
    write_assembly(
        &out,
        "ring-and-cone",
        vec![
            ("ring_lower", Spec::Mesh(lower)),
            ("ring_upper", Spec::Mesh(upper)),
            ("cone", Spec::Mesh((pts, tris))),
        ],
    )?;
    Ok(())
}

fn clone_spec(s: &Spec) -> Spec {
    match s {
        Spec::Mesh(m) => Spec::Mesh(m.clone()),
        Spec::Pieces(p) => Spec::Pieces(p.clone()),
    }
}
