//! Closed integer solids with known structure, each with facts about it found without
//! decomposing it: the volume by a hand formula, the reflex edges counted by hand, and
//! sample points classified from the solid's definition.
//!
//! The shared inputs of the decomposition tests and benchmarks and of the planner's
//! ring-and-cone benchmark. Everything is plain integers: callers convert the points and
//! the volume to their exact types.

use std::collections::HashMap;

/// A sample point `x / w` and whether it lies strictly inside (`true`) or strictly
/// outside (`false`) its solid.
pub type Sample = ([i128; 3], i128, bool);

/// A closed integer mesh with independent facts about it.
#[derive(Clone, Debug)]
pub struct Shape {
    /// What the solid is, for messages and tables.
    pub name: &'static str,
    /// Vertex coordinates.
    pub points: Vec<[i64; 3]>,
    /// Outward triangles as indices into `points`.
    pub tris: Vec<[u32; 3]>,
    /// The volume as `[numerator, denominator]`, from a formula independent of any
    /// decomposition.
    pub volume: [i128; 2],
    /// Reflex edges counted by hand, when known.
    pub reflex: Option<usize>,
    /// Sample points with their membership.
    pub samples: Vec<Sample>,
}

/// Welds points given by their coordinates into indices, in order of first use.
#[derive(Default)]
struct Welder {
    ids: HashMap<[i64; 3], u32>,
    points: Vec<[i64; 3]>,
}

impl Welder {
    fn id(&mut self, p: [i64; 3]) -> u32 {
        let n = self.points.len() as u32;
        *self.ids.entry(p).or_insert_with(|| {
            self.points.push(p);
            n
        })
    }
}

/// Six times the volume of a closed mesh by the divergence theorem (panics if it does not
/// fit in an `i128`).
fn volume6(points: &[[i64; 3]], tris: &[[u32; 3]]) -> i128 {
    let mut v = 0i128;
    for t in tris {
        let [a, b, c] = t.map(|i| points[i as usize].map(i128::from));
        let cross = [
            b[1] * c[2] - b[2] * c[1],
            b[2] * c[0] - b[0] * c[2],
            b[0] * c[1] - b[1] * c[0],
        ];
        let det = (0..3)
            .try_fold(0i128, |s, k| s.checked_add(a[k].checked_mul(cross[k])?))
            .expect("the volume fits in i128");
        v = v.checked_add(det).expect("the volume fits in i128");
    }
    v
}

/// The union of the filled cells of the rectilinear grid `xs × ys × zs` (strictly
/// increasing coordinates): its boundary faces, two triangles per grid rectangle (the
/// mesh of [`crate::solids::rectilinear`]), with its volume and a sample point at the
/// centre of every cell and just outside each face of the bounding box.
pub fn rectilinear(
    name: &'static str,
    g: [&[i64]; 3],
    filled: impl Fn([usize; 3]) -> bool,
    reflex: Option<usize>,
) -> Shape {
    let n = [g[0].len() - 1, g[1].len() - 1, g[2].len() - 1];
    let mesh = crate::solids::rectilinear(g, &filled);
    let mut volume = 0i128;
    let mut samples = Vec::new();
    for i in 0..n[0] {
        for j in 0..n[1] {
            for k in 0..n[2] {
                let c = [i, j, k];
                let f = filled(c);
                if f {
                    volume += (0..3)
                        .map(|a| i128::from(g[a][c[a] + 1] - g[a][c[a]]))
                        .product::<i128>();
                }
                let mid = [0, 1, 2].map(|a| (g[a][c[a]] + g[a][c[a] + 1]) as i128);
                samples.push((mid, 2, f));
            }
        }
    }
    // Points just outside each face of the bounding box.
    let lo = [g[0][0], g[1][0], g[2][0]];
    let hi = [g[0][n[0]], g[1][n[1]], g[2][n[2]]];
    for a in 0..3 {
        let mut p = [0, 1, 2].map(|b| (lo[b] + hi[b]) as i128);
        p[a] = 2 * lo[a] as i128 - 1;
        samples.push((p, 2, false));
        p[a] = 2 * hi[a] as i128 + 1;
        samples.push((p, 2, false));
    }
    Shape {
        name,
        points: mesh.points,
        tris: mesh.triangles,
        volume: [volume, 1],
        reflex,
        samples,
    }
}

/// An L-shaped block: a 20 × 20 × 10 slab without one quarter (one reflex edge).
pub fn l_block() -> Shape {
    rectilinear(
        "L-block",
        [&[0, 10, 20], &[0, 10, 20], &[0, 10]],
        |c| !(c[0] == 1 && c[1] == 1),
        Some(1),
    )
}

/// A U-shaped channel: a base and two walls (two reflex edges).
pub fn u_channel() -> Shape {
    rectilinear(
        "U-channel",
        [&[0, 10, 20, 30], &[0, 10, 30], &[0, 40]],
        |c| c[1] == 0 || c[0] != 1,
        Some(2),
    )
}

/// A square slab with a square hole through it (four reflex edges).
pub fn box_with_hole() -> Shape {
    rectilinear(
        "box with through-hole",
        [&[0, 10, 20, 30], &[0, 10, 20, 30], &[0, 15]],
        |c| !(c[0] == 1 && c[1] == 1),
        Some(4),
    )
}

/// A comb: a base with `teeth` teeth (`2 (teeth − 1)` reflex edges, all in one plane).
pub fn comb(teeth: usize) -> Shape {
    let xs: Vec<i64> = (0..=(2 * teeth - 1) as i64).map(|i| 10 * i).collect();
    rectilinear(
        "comb",
        [&xs, &[0, 10, 40], &[0, 10]],
        |c| c[1] == 0 || c[0] % 2 == 0,
        Some(2 * (teeth - 1)),
    )
}

/// A plus-shaped prism: the arms' side faces are coplanar in pairs across the centre,
/// and each such plane holds two reflex edges.
pub fn plus_prism() -> Shape {
    rectilinear(
        "plus prism (coplanar faces at reflex edges)",
        [&[0, 10, 20, 30], &[0, 10, 20, 30], &[0, 10]],
        |c| c[0] == 1 || c[1] == 1,
        Some(4),
    )
}

/// An I-beam: two flanges and a web, with coplanar flange undersides.
pub fn i_beam() -> Shape {
    rectilinear(
        "I-beam (coplanar faces at reflex edges)",
        [&[0, 40, 50, 90], &[0, 8, 92, 100], &[0, 300]],
        |c| c[1] != 1 || c[0] == 1,
        Some(4),
    )
}

/// Two cubes of side 10 sharing an edge.
pub fn two_cubes_edge() -> Shape {
    rectilinear(
        "two cubes sharing an edge",
        [&[0, 10, 20], &[0, 10, 20], &[0, 10]],
        |c| c[0] == c[1],
        Some(0),
    )
}

/// Two cubes of side 10 sharing a vertex.
pub fn two_cubes_vertex() -> Shape {
    rectilinear(
        "two cubes sharing a vertex",
        [&[0, 10, 20], &[0, 10, 20], &[0, 10, 20]],
        |c| c[0] == c[1] && c[1] == c[2],
        Some(0),
    )
}

/// Sheet metal: a 1500 x 1000 plate 2 units thick with two bent-up flanges 300 high,
/// three rectangular holes in the plate and one in a flange.
pub fn sheet_metal() -> Shape {
    let xs = [0, 2, 300, 340, 700, 760, 1498, 1500];
    let ys = [0, 200, 260, 400, 600, 800, 860, 1000];
    let zs = [0, 2, 100, 200, 300];
    rectilinear(
        "sheet metal (t = 2, flanges, holes)",
        [&xs, &ys, &zs],
        |c| {
            let [i, j, k] = c;
            if k == 0 {
                let hole = (i == 2 && j == 1) || (i == 4 && j == 5) || (i == 2 && j == 5);
                !hole
            } else {
                (i == 0 || i == 6) && !(i == 0 && j == 3 && k == 2)
            }
        },
        None,
    )
}

/// The unit cubes of a `dims` voxel grid whose entries of `on` are set (index
/// `(x dims[1] + y) dims[2] + z`).
pub fn voxels(dims: [usize; 3], on: &[bool]) -> Shape {
    let axis = |n: usize| (0..=n as i64).collect::<Vec<_>>();
    let (xs, ys, zs) = (axis(dims[0]), axis(dims[1]), axis(dims[2]));
    rectilinear(
        "voxels",
        [&xs, &ys, &zs],
        |c| on[(c[0] * dims[1] + c[1]) * dims[2] + c[2]],
        None,
    )
}

/// Integer points `(x, y)` with `x² + y² = r2`, sorted.
fn lattice_circle(r2: i64) -> Vec<[i64; 2]> {
    let r = (r2 as f64).sqrt() as i64 + 1;
    let mut out = Vec::new();
    for x in -r..=r {
        let y2 = r2 - x * x;
        if y2 < 0 {
            continue;
        }
        let y = (y2 as f64).sqrt().round() as i64;
        for y in [y - 1, y, y + 1] {
            if y >= 0 && y * y == y2 {
                out.push([x, y]);
                if y != 0 {
                    out.push([x, -y]);
                }
            }
        }
    }
    out.sort();
    out.dedup();
    out
}

/// A polygonal torus: `stations` planes through the z axis (integer directions of equal
/// length R = 32045, chosen among the lattice points of that circle), each holding the
/// same 16-gon cross-section (the lattice points of x² + z² = 65 around s = 20, scaled by
/// R). Consecutive cross-sections are exact rotations of each other, so the quads between
/// them are planar trapezoids: every segment is convex.
pub struct Ring {
    /// The stations' directions in the xy plane, all of length `radius`.
    pub dirs: Vec<[i64; 2]>,
    /// The cross-section `(s, z)`, counter-clockwise, in units of `radius`.
    pub section: Vec<[i64; 2]>,
    /// The length of every direction.
    pub radius: i64,
}

impl Ring {
    /// The ring of `stations` stations with the 16-gon cross-section.
    pub fn new(stations: usize) -> Ring {
        Ring::with_section(stations, 65, 20, 5 * 13 * 17 * 29)
    }

    /// `stations` stations of direction length `radius`, cross-section the lattice
    /// points of `a² + b² = r2` around `s = s0`.
    pub fn with_section(stations: usize, r2: i64, s0: i64, radius: i64) -> Ring {
        assert!(stations % 2 == 0);
        let circle = lattice_circle(radius * radius);
        let half = stations / 2;
        let mut dirs = Vec::new();
        for j in 0..half {
            let t = std::f64::consts::TAU * j as f64 / stations as f64;
            let best = circle
                .iter()
                .max_by(|a, b| {
                    let da = a[0] as f64 * t.cos() + a[1] as f64 * t.sin();
                    let db = b[0] as f64 * t.cos() + b[1] as f64 * t.sin();
                    da.total_cmp(&db)
                })
                .unwrap();
            dirs.push(*best);
        }
        for j in 0..half {
            dirs.push([-dirs[j][0], -dirs[j][1]]);
        }
        let mut distinct = dirs.clone();
        distinct.sort();
        distinct.dedup();
        assert_eq!(distinct.len(), stations, "too few lattice directions");
        let mut section: Vec<[i64; 2]> = lattice_circle(r2);
        section.sort_by(|a, b| {
            (a[1] as f64)
                .atan2(a[0] as f64)
                .total_cmp(&(b[1] as f64).atan2(b[0] as f64))
        });
        let section = section.into_iter().map(|[a, b]| [s0 + a, b]).collect();
        Ring {
            dirs,
            section,
            radius,
        }
    }

    fn point(&self, j: usize, k: usize) -> [i64; 3] {
        let d = self.dirs[j % self.dirs.len()];
        let [s, z] = self.section[k % self.section.len()];
        [s * d[0], s * d[1], z * self.radius]
    }

    /// The planes `(n, c)` (inside `n · x <= c`) of segment `j`'s trapezoids.
    fn segment_planes(&self, j: usize) -> Vec<([i128; 3], i128)> {
        (0..self.section.len())
            .map(|k| {
                let (a, b, c) = (
                    self.point(j, k),
                    self.point(j + 1, k),
                    self.point(j + 1, k + 1),
                );
                let u = [0, 1, 2].map(|i| (b[i] - a[i]) as i128);
                let v = [0, 1, 2].map(|i| (c[i] - a[i]) as i128);
                let n = [
                    u[1] * v[2] - u[2] * v[1],
                    u[2] * v[0] - u[0] * v[2],
                    u[0] * v[1] - u[1] * v[0],
                ];
                let off = n[0] * a[0] as i128 + n[1] * a[1] as i128 + n[2] * a[2] as i128;
                (n, off)
            })
            .collect()
    }

    /// Membership of the point `x / w` (`None` on a boundary or an internal station
    /// plane), from the definition: the sector between two stations, then the segment's
    /// trapezoid planes.
    pub fn inside(&self, x: [i128; 3], w: i128) -> Option<bool> {
        let m = self.dirs.len();
        let cross = |d: [i64; 2]| d[0] as i128 * x[1] - d[1] as i128 * x[0];
        for j in 0..m {
            let (a, b) = (cross(self.dirs[j]), -cross(self.dirs[(j + 1) % m]));
            if a == 0 || b == 0 {
                return None;
            }
            if a > 0 && b > 0 {
                let mut inside = true;
                for (n, c) in self.segment_planes(j) {
                    let v = n[0] * x[0] + n[1] * x[1] + n[2] * x[2] - c * w;
                    if v == 0 {
                        return None;
                    }
                    if v > 0 {
                        inside = false;
                    }
                }
                return Some(inside);
            }
        }
        None
    }

    /// The ring's surface (two triangles per trapezoid), its volume by the divergence
    /// theorem, and sample points on a lattice through its box, classified by
    /// [`Ring::inside`].
    pub fn shape(&self) -> Shape {
        let (m, q) = (self.dirs.len(), self.section.len());
        let mut w = Welder::default();
        let mut tris = Vec::new();
        for j in 0..m {
            for k in 0..q {
                let a = w.id(self.point(j, k));
                let b = w.id(self.point(j + 1, k));
                let c = w.id(self.point(j + 1, k + 1));
                let d = w.id(self.point(j, k + 1));
                tris.push([a, b, c]);
                tris.push([a, c, d]);
            }
        }
        let volume = [volume6(&w.points, &tris), 6];
        // Sample points on a lattice through the ring's box, classified by definition.
        let mut samples = Vec::new();
        let smax = self.section.iter().map(|p| p[0]).max().unwrap() + 1;
        let zmax = self.section.iter().map(|p| p[1]).max().unwrap() + 1;
        let ext = smax * self.radius;
        let h = zmax * self.radius;
        let steps = 9i64;
        for a in 0..=steps {
            for b in 0..=steps {
                for c in 0..=4 {
                    let p = [
                        (-ext + 2 * ext * a / steps) as i128 * 7 + 1,
                        (-ext + 2 * ext * b / steps) as i128 * 7 + 2,
                        (-h + 2 * h * c / 4) as i128 * 7 + 3,
                    ];
                    if let Some(inside) = self.inside(p, 7) {
                        samples.push((p, 7, inside));
                    }
                }
            }
        }
        Shape {
            name: if m == 64 && q == 16 {
                "ring (64 segments, 16-gon section)"
            } else {
                "ring (256 segments, 32-gon section)"
            },
            points: w.points,
            tris,
            volume,
            reflex: None,
            samples,
        }
    }
}

/// The sign of the determinant of `q − p`, `r − p`, `s − p`: positive when `s` lies on
/// the positive side of the plane through `p`, `q`, `r` (counter-clockwise seen from it).
fn orientation(p: [i64; 3], q: [i64; 3], r: [i64; 3], s: [i64; 3]) -> i128 {
    let [u, v, w] = [q, r, s].map(|x| [0, 1, 2].map(|k| i128::from(x[k] - p[k])));
    let det = u[0] * (v[1] * w[2] - v[2] * w[1]) - u[1] * (v[0] * w[2] - v[2] * w[0])
        + u[2] * (v[0] * w[1] - v[1] * w[0]);
    det.signum()
}

/// The Schönhardt twisted prism: the top triangle turned by 30 degrees against the
/// bottom one, each side quad split along its reflex diagonal. Volume by the prismatoid
/// formula `h / 6 (A_bottom + A_top + 4 A_mid)`.
pub fn schonhardt() -> Shape {
    let h = 100i64;
    let a = [[100i64, 0], [-50, 87], [-50, -87]];
    let b = [[87i64, 50], [-87, 50], [0, -100]];
    let pa = |i: usize| [a[i % 3][0], a[i % 3][1], 0];
    let pb = |i: usize| [b[i % 3][0], b[i % 3][1], h];
    let points: Vec<[i64; 3]> = (0..3).map(pa).chain((0..3).map(pb)).collect();
    let mut tris = vec![[0u32, 2, 1], [3, 4, 5]];
    let mut lateral = Vec::new(); // lateral edges in cyclic order, as point pairs
    for i in 0..3 {
        let j = (i + 1) % 3;
        let (ai, aj, bi, bj) = (i as u32, j as u32, 3 + i as u32, 3 + j as u32);
        lateral.push((pa(i), pb(i)));
        // Diagonal a_i b_j is reflex when b_i is above the plane of (a_i, a_j, b_j).
        if orientation(pa(i), pa(j), pb(j), pb(i)) > 0 {
            tris.push([ai, aj, bj]);
            tris.push([ai, bj, bi]);
            lateral.push((pa(i), pb(j)));
        } else {
            tris.push([ai, aj, bi]);
            tris.push([aj, bj, bi]);
            lateral.push((pa(j), pb(i)));
        }
    }
    let area2 = |poly: &[[i64; 2]]| -> i64 {
        (0..poly.len())
            .map(|k| {
                let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
                p[0] * q[1] - p[1] * q[0]
            })
            .sum()
    };
    // Mid-section vertices are midpoints of the lateral edges: doubled coordinates.
    let mid: Vec<[i64; 2]> = lateral
        .iter()
        .map(|(p, q)| [p[0] + q[0], p[1] + q[1]])
        .collect();
    let (ab, at, am) = (area2(&a), area2(&b), area2(&mid)); // 2A, 2A, 8A
                                                            // V = h/6 (A_b + A_t + 4 A_m) = h/6 (ab/2 + at/2 + am/2)
    let volume = [i128::from(h * (ab + at + am)), 12];
    let samples = vec![
        ([0, 0, 100], 2, true),
        ([0, 0, 1], 1, true),
        ([0, 0, -1], 1, false),
        ([0, 0, 101], 1, false),
    ];
    Shape {
        name: "Schönhardt twisted prism",
        points,
        tris,
        volume,
        reflex: Some(3),
        samples,
    }
}

/// The red part of the Split Star (faces from `split_star/0_red.off`).
pub fn split_star_red() -> Shape {
    let points: Vec<[i64; 3]> = vec![
        [-1, -1, 1],
        [-2, 0, 2],
        [-2, 0, 0],
        [-1, 1, 1],
        [1, -1, 1],
        [2, 0, 0],
        [2, 0, 2],
        [1, 1, 1],
        [0, 0, 0],
        [0, 0, 2],
    ];
    let tris: Vec<[u32; 3]> = vec![
        [0, 1, 2],
        [2, 1, 3],
        [2, 3, 0],
        [4, 5, 6],
        [7, 6, 5],
        [4, 7, 5],
        [0, 8, 4],
        [0, 3, 8],
        [7, 4, 8],
        [7, 8, 3],
        [1, 0, 9],
        [9, 0, 4],
        [9, 4, 6],
        [6, 7, 9],
        [9, 7, 3],
        [9, 3, 1],
    ];
    let volume = [volume6(&points, &tris), 6];
    Shape {
        name: "Split Star red part",
        points,
        tris,
        volume,
        reflex: None,
        samples: vec![
            ([0, 0, 1], 1, true),
            ([0, 0, 3], 1, false),
            ([0, 0, -1], 1, false),
        ],
    }
}

/// A prism over a simple counter-clockwise polygon in the xy plane, `z` in `[0, h]`,
/// with the sample points of [`bent_sheet`].
pub fn extrusion(name: &'static str, poly: &[[i64; 2]], h: i64, reflex: Option<usize>) -> Shape {
    let n = poly.len() as u32;
    let points: Vec<[i64; 3]> = poly
        .iter()
        .map(|p| [p[0], p[1], 0])
        .chain(poly.iter().map(|p| [p[0], p[1], h]))
        .collect();
    let mut tris = Vec::new();
    for t in crate::solids::ear_clip(poly) {
        let t = t.map(|i| i as u32);
        tris.push([t[0], t[2], t[1]]);
        tris.push([t[0] + n, t[1] + n, t[2] + n]);
    }
    for i in 0..n {
        let j = (i + 1) % n;
        tris.push([i, j, j + n]);
        tris.push([i, j + n, i + n]);
    }
    let area2: i64 = (0..poly.len())
        .map(|k| {
            let (p, q) = (poly[k], poly[(k + 1) % poly.len()]);
            p[0] * q[1] - p[1] * q[0]
        })
        .sum();
    Shape {
        name,
        points,
        tris,
        volume: [i128::from(area2 * h), 2],
        reflex,
        samples: vec![
            ([1000, 1, 400], 1, true),
            ([1000, 3, 400], 1, false),
            ([2000, 601, 400], 1, true),
        ],
    }
}

/// A sheet 2 units thick bent twice by 45 degrees (a Z profile), 800 deep.
pub fn bent_sheet() -> Shape {
    let poly = [
        [0, 0],
        [1000, 0],
        [1600, 600],
        [2600, 600],
        [2600, 602],
        [1600, 602],
        [1000, 2],
        [0, 2],
    ];
    extrusion("bent sheet (t = 2, two 45° bends)", &poly, 800, Some(2))
}

/// All test shapes, in table order.
pub fn all() -> Vec<Shape> {
    vec![
        l_block(),
        u_channel(),
        box_with_hole(),
        Ring::new(64).shape(),
        comb(8),
        plus_prism(),
        i_beam(),
        schonhardt(),
        sheet_metal(),
        bent_sheet(),
        two_cubes_edge(),
        two_cubes_vertex(),
        split_star_red(),
    ]
}

/// The image of `shape` under the integer linear map `m` (rows), `det m > 0`: the same
/// structure with generic planes. Volumes scale by `det m`, samples map along.
pub fn transformed(shape: &Shape, m: [[i64; 3]; 3]) -> Shape {
    let det = m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
        - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
        + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0]);
    assert!(det > 0);
    let apply = |p: [i128; 3]| -> [i128; 3] {
        [0, 1, 2].map(|r| (0..3).map(|c| m[r][c] as i128 * p[c]).sum())
    };
    let points = shape
        .points
        .iter()
        .map(|p| {
            apply(p.map(i128::from)).map(|v| i64::try_from(v).expect("coordinates fit in i64"))
        })
        .collect();
    Shape {
        name: shape.name,
        points,
        tris: shape.tris.clone(),
        volume: [
            shape.volume[0]
                .checked_mul(i128::from(det))
                .expect("the volume fits in i128"),
            shape.volume[1],
        ],
        reflex: shape.reflex,
        samples: shape
            .samples
            .iter()
            .map(|(x, w, i)| (apply(*x), *w, *i))
            .collect(),
    }
}

/// A block over an `n × n` grid of cells of side `cell` whose top is the triangulated
/// height field `h` (`(n + 1)²` heights, row-major in x, then y), bottom at z = 0. Each
/// cell is split along its diagonal from (i, j) to (i + 1, j + 1). Volume: the sum over
/// top triangles of their projected area times their mean height.
pub fn terrain(n: usize, cell: i64, h: &[i64]) -> Shape {
    assert_eq!(h.len(), (n + 1) * (n + 1));
    let at = |i: usize, j: usize| h[i * (n + 1) + j];
    let top = |i: usize, j: usize| [i as i64 * cell, j as i64 * cell, at(i, j)];
    let bottom = |i: usize, j: usize| [i as i64 * cell, j as i64 * cell, 0];
    let mut w = Welder::default();
    let mut tris = Vec::new();
    let mut top_tris: Vec<[[i64; 3]; 3]> = Vec::new();
    for i in 0..n {
        for j in 0..n {
            let t = [top(i, j), top(i + 1, j), top(i + 1, j + 1), top(i, j + 1)];
            for tri in [[t[0], t[1], t[2]], [t[0], t[2], t[3]]] {
                tris.push(tri.map(|p| w.id(p)));
                top_tris.push(tri);
            }
            let b = [
                bottom(i, j),
                bottom(i + 1, j),
                bottom(i + 1, j + 1),
                bottom(i, j + 1),
            ];
            tris.push([w.id(b[0]), w.id(b[2]), w.id(b[1])]);
            tris.push([w.id(b[0]), w.id(b[3]), w.id(b[2])]);
        }
    }
    // Walls, counter-clockwise around the boundary seen from above.
    let mut ring: Vec<(usize, usize)> = Vec::new();
    ring.extend((0..n).map(|i| (i, 0)));
    ring.extend((0..n).map(|j| (n, j)));
    ring.extend((0..n).map(|i| (n - i, n)));
    ring.extend((0..n).map(|j| (0, n - j)));
    for k in 0..ring.len() {
        let (p, q) = (ring[k], ring[(k + 1) % ring.len()]);
        let (bp, bq, tq, tp) = (
            w.id(bottom(p.0, p.1)),
            w.id(bottom(q.0, q.1)),
            w.id(top(q.0, q.1)),
            w.id(top(p.0, p.1)),
        );
        tris.push([bp, bq, tq]);
        tris.push([bp, tq, tp]);
    }
    let area = cell * cell; // twice the projected area of a triangle
    let mut volume = 0i128;
    for t in &top_tris {
        volume += i128::from(area * (t[0][2] + t[1][2] + t[2][2]));
    }
    // Samples: a lattice of points classified against the top triangle above them.
    let hmax = h.iter().max().unwrap() + 5;
    let mut samples = Vec::new();
    let steps = 4 * n as i64 + 1;
    for a in 0..=steps {
        for b in 0..=steps {
            for c in 0..=6 {
                let w = 13i128;
                let p = [
                    (a * n as i64 * cell / steps) as i128 * w + 3,
                    (b * n as i64 * cell / steps) as i128 * w + 5,
                    (c * hmax / 6) as i128 * w + 7,
                ];
                if let Some(inside) = terrain_inside(n, cell, &top_tris, p, w) {
                    samples.push((p, w, inside));
                }
            }
        }
    }
    Shape {
        name: "terrain",
        points: w.points,
        tris,
        volume: [volume, 6],
        reflex: None,
        samples,
    }
}

/// Membership of `x / w` in a terrain block (`None` on a boundary or ambiguous).
fn terrain_inside(
    n: usize,
    cell: i64,
    top: &[[[i64; 3]; 3]],
    x: [i128; 3],
    w: i128,
) -> Option<bool> {
    let size = n as i128 * cell as i128 * w;
    if x[0] <= 0 || x[1] <= 0 || x[0] >= size || x[1] >= size || x[2] <= 0 {
        return Some(false);
    }
    let orient = |a: [i64; 3], b: [i64; 3]| -> i128 {
        (b[0] - a[0]) as i128 * (x[1] - a[1] as i128 * w)
            - (b[1] - a[1]) as i128 * (x[0] - a[0] as i128 * w)
    };
    for t in top {
        let o = [orient(t[0], t[1]), orient(t[1], t[2]), orient(t[2], t[0])];
        if o.contains(&0) && o.iter().all(|&v| v >= 0) {
            return None; // over a triangle edge: skip
        }
        if o.iter().all(|&v| v > 0) {
            let u = [0, 1, 2].map(|k| (t[1][k] - t[0][k]) as i128);
            let v = [0, 1, 2].map(|k| (t[2][k] - t[0][k]) as i128);
            let nrm = [
                u[1] * v[2] - u[2] * v[1],
                u[2] * v[0] - u[0] * v[2],
                u[0] * v[1] - u[1] * v[0],
            ];
            let c = nrm[0] * t[0][0] as i128 + nrm[1] * t[0][1] as i128 + nrm[2] * t[0][2] as i128;
            let s = nrm[0] * x[0] + nrm[1] * x[1] + nrm[2] * x[2] - c * w;
            return if s == 0 { None } else { Some(s < 0) };
        }
    }
    None
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn volumes_by_formula_match_the_divergence_theorem() {
        let h: Vec<i64> = (0..16).map(|k| 10 + (k * 7) % 13).collect();
        for s in all().into_iter().chain([
            terrain(3, 20, &h),
            transformed(&box_with_hole(), [[3, 1, 0], [1, 4, 1], [0, 2, 5]]),
        ]) {
            let v6 = volume6(&s.points, &s.tris);
            assert_eq!(v6 * s.volume[1], 6 * s.volume[0], "{}", s.name);
        }
    }

    #[test]
    fn ring_samples_agree_with_membership() {
        let ring = Ring::new(64);
        let s = ring.shape();
        assert_eq!(s.tris.len(), 64 * 16 * 2);
        assert!(s.samples.iter().any(|x| x.2) && s.samples.iter().any(|x| !x.2));
    }
}
