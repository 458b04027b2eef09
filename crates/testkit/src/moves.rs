//! Two-part assemblies that come apart in two moves and not in one (level 2), off the
//! voxel grid, each with its answer known by construction: which part moves, the only
//! direction it can start along, how far that first move may go, and a direction that
//! takes it away afterwards.
//!
//! Every part is a union of convex prisms (a convex polygon in the xy-plane between two
//! heights) with integer coordinates below 100, written as declared convex pieces; the
//! prisms of an assembly have disjoint interiors and touch along faces. The moving part
//! touches the fixed one on faces whose normals leave it a single direction of motion
//! (every other direction immediately pushes into a face in contact), and that motion
//! ends against a wall, so no single translation separates the parts.
//!
//! - [`l_slot`]: a block under two lips in a channel running along (1, 1, 0) in the
//!   xy-plane; slid to the far end, past the lips, it lifts out along +z.
//! - [`keyhole`]: a key (a square head under a plate, a shaft up through a slot)
//!   slides along −x to the keyhole's wide (square) end, then lifts out.
//! - [`drawer`]: a drawer in a cabinet behind a lip at the front bottom edge: up over
//!   the lip, then out along −y.
//! - [`diagonal_two_move`]: a block in a covered channel along (2, 1, 0) slides to a
//!   window in the side wall and leaves through it along (−1, 2, 0).

use crate::solids::IntMesh;
use std::fmt::Write as _;
use std::path::Path;

/// A convex prism: a convex polygon (counter-clockwise, no three vertices collinear)
/// in the xy-plane extruded from `z[0]` to `z[1]`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Prism {
    /// The section, counter-clockwise.
    pub poly: Vec<[i64; 2]>,
    /// Bottom and top heights, `z[0] < z[1]`.
    pub z: [i64; 2],
}

/// One part: a name and its convex pieces.
#[derive(Clone, Debug)]
pub struct MovePart {
    /// The part's name (its folder in the written assembly).
    pub name: &'static str,
    /// Convex pieces with disjoint interiors whose union is the part.
    pub pieces: Vec<Prism>,
}

/// A level-2 assembly with its known answer.
#[derive(Clone, Debug)]
pub struct TwoMoves {
    /// The example's name (its folder under `examples/`).
    pub name: &'static str,
    /// The parts; the fixed one first.
    pub parts: Vec<MovePart>,
    /// Index of the part that moves.
    pub moving: usize,
    /// The only direction the moving part can start along (small integers).
    pub first: [i64; 3],
    /// The first move's extent: any displacement `k · first` with `k` in this range
    /// (inclusive) frees the part for `second`; from `k = 0` only up to the upper end.
    pub first_range: [i64; 2],
    /// A direction along which the part leaves for ever after the first move.
    pub second: [i64; 3],
    /// One sentence describing the assembly, for its README.
    pub about: &'static str,
}

impl Prism {
    /// The prism of the convex polygon `poly` (either orientation) from `z0` to `z1`.
    pub fn new(poly: &[[i64; 2]], z0: i64, z1: i64) -> Prism {
        let mut poly = poly.to_vec();
        if area2(&poly) < 0 {
            poly.reverse();
        }
        assert!(z0 < z1 && area2(&poly) > 0, "a prism with volume");
        Prism { poly, z: [z0, z1] }
    }

    /// The axis-aligned box `lo..hi`.
    pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Prism {
        Prism::new(
            &[
                [lo[0], lo[1]],
                [hi[0], lo[1]],
                [hi[0], hi[1]],
                [lo[0], hi[1]],
            ],
            lo[2],
            hi[2],
        )
    }

    /// The prism over the parallelogram `{o + s·u + t·v : s ∈ s_range, t ∈ t_range}`.
    pub fn slanted(
        o: [i64; 2],
        u: [i64; 2],
        v: [i64; 2],
        s_range: [i64; 2],
        t_range: [i64; 2],
        z: [i64; 2],
    ) -> Prism {
        let at = |s: i64, t: i64| [o[0] + s * u[0] + t * v[0], o[1] + s * u[1] + t * v[1]];
        let [s0, s1] = s_range;
        let [t0, t1] = t_range;
        Prism::new(
            &[at(s0, t0), at(s1, t0), at(s1, t1), at(s0, t1)],
            z[0],
            z[1],
        )
    }

    /// The prism moved by `t`.
    pub fn translated(&self, t: [i64; 3]) -> Prism {
        Prism {
            poly: self
                .poly
                .iter()
                .map(|p| [p[0] + t[0], p[1] + t[1]])
                .collect(),
            z: [self.z[0] + t[2], self.z[1] + t[2]],
        }
    }

    /// The region the prism sweeps moving by `d`, horizontal or vertical (a prism too).
    ///
    /// # Panics
    /// When `d` is neither horizontal nor vertical.
    pub fn swept(&self, d: [i64; 3]) -> Prism {
        if d[0] == 0 && d[1] == 0 {
            return Prism {
                poly: self.poly.clone(),
                z: [self.z[0] + d[2].min(0), self.z[1] + d[2].max(0)],
            };
        }
        assert_eq!(d[2], 0, "a horizontal or vertical sweep");
        let mut pts = self.poly.clone();
        pts.extend(self.poly.iter().map(|p| [p[0] + d[0], p[1] + d[1]]));
        Prism {
            poly: hull(pts),
            z: self.z,
        }
    }

    /// The closed outward mesh: fans on the caps, two triangles per side.
    pub fn mesh(&self) -> IntMesh {
        let n = self.poly.len() as u32;
        let mut points: Vec<[i64; 3]> = self.poly.iter().map(|p| [p[0], p[1], self.z[0]]).collect();
        points.extend(self.poly.iter().map(|p| [p[0], p[1], self.z[1]]));
        let mut triangles = Vec::new();
        for i in 1..n - 1 {
            triangles.push([0, i + 1, i]);
            triangles.push([n, n + i, n + i + 1]);
        }
        for i in 0..n {
            let j = (i + 1) % n;
            triangles.push([i, j, n + j]);
            triangles.push([i, n + j, n + i]);
        }
        IntMesh { points, triangles }
    }
}

/// Twice the signed area of a polygon.
fn area2(poly: &[[i64; 2]]) -> i128 {
    (0..poly.len())
        .map(|i| {
            let (a, b) = (poly[i], poly[(i + 1) % poly.len()]);
            i128::from(a[0]) * i128::from(b[1]) - i128::from(a[1]) * i128::from(b[0])
        })
        .sum()
}

fn cross(o: [i64; 2], a: [i64; 2], b: [i64; 2]) -> i128 {
    i128::from(a[0] - o[0]) * i128::from(b[1] - o[1])
        - i128::from(a[1] - o[1]) * i128::from(b[0] - o[0])
}

/// The convex hull, counter-clockwise without collinear vertices (monotone chain).
fn hull(mut pts: Vec<[i64; 2]>) -> Vec<[i64; 2]> {
    pts.sort_unstable();
    pts.dedup();
    let mut h: Vec<[i64; 2]> = Vec::new();
    for pass in 0..2 {
        let start = h.len();
        let iter: Box<dyn Iterator<Item = &[i64; 2]>> = if pass == 0 {
            Box::new(pts.iter())
        } else {
            Box::new(pts.iter().rev())
        };
        for &p in iter {
            while h.len() >= start + 2 && cross(h[h.len() - 2], h[h.len() - 1], p) <= 0 {
                h.pop();
            }
            h.push(p);
        }
        h.pop();
    }
    h
}

/// The interiors of two prisms meet: their height ranges overlap with positive length
/// and no edge line of either section separates the sections (exact integers).
pub fn interiors_meet(a: &Prism, b: &Prism) -> bool {
    a.z[0] < b.z[1] && b.z[0] < a.z[1] && sections_meet(&a.poly, &b.poly)
}

/// The interiors of two convex polygons meet (no edge line of either separates them).
fn sections_meet(a: &[[i64; 2]], b: &[[i64; 2]]) -> bool {
    let separates = |p: &[[i64; 2]], q: &[[i64; 2]]| {
        (0..p.len()).any(|i| {
            let (s, e) = (p[i], p[(i + 1) % p.len()]);
            // `p` lies left of (s → e); `q` wholly right of it or on it is separated.
            q.iter().all(|&x| cross(s, e, x) <= 0)
        })
    };
    !separates(a, b) && !separates(b, a)
}

/// The outward normals (reduced to coprime integers, without repeats) of the faces of
/// `moving` that touch a face of `fixed` over a positive area: a translation with a
/// positive component along any of them pushes into `fixed` at once.
pub fn contact_normals(moving: &[Prism], fixed: &[Prism]) -> Vec<[i64; 3]> {
    let mut normals = Vec::new();
    for a in moving {
        for b in fixed {
            if sections_meet(&a.poly, &b.poly) {
                if a.z[1] == b.z[0] {
                    normals.push([0, 0, 1]);
                }
                if a.z[0] == b.z[1] {
                    normals.push([0, 0, -1]);
                }
            }
            if !(a.z[0] < b.z[1] && b.z[0] < a.z[1]) {
                continue;
            }
            for i in 0..a.poly.len() {
                let (p, q) = (a.poly[i], a.poly[(i + 1) % a.poly.len()]);
                for j in 0..b.poly.len() {
                    let (r, s) = (b.poly[j], b.poly[(j + 1) % b.poly.len()]);
                    if cross(p, q, r) != 0 || cross(p, q, s) != 0 {
                        continue;
                    }
                    // Opposite edges on one line overlapping over a positive length.
                    let e = [q[0] - p[0], q[1] - p[1]];
                    let at = |x: [i64; 2]| i128::from(e[0] * (x[0] - p[0]) + e[1] * (x[1] - p[1]));
                    let len = at(q);
                    let (lo, hi) = (at(s).min(at(r)), at(s).max(at(r)));
                    if at(s) < at(r) && lo.max(0) < hi.min(len) {
                        normals.push(reduced([e[1], -e[0], 0]));
                    }
                }
            }
        }
    }
    normals.sort_unstable();
    normals.dedup();
    normals
}

/// The vector divided by the greatest common divisor of its entries.
fn reduced(v: [i64; 3]) -> [i64; 3] {
    let gcd = |mut a: i64, mut b: i64| {
        while b != 0 {
            (a, b) = (b, a % b);
        }
        a.abs()
    };
    let g = gcd(gcd(v[0], v[1]), v[2]).max(1);
    v.map(|c| c / g)
}

impl TwoMoves {
    /// The parts with the moving one displaced by `k · first`.
    pub fn displaced(&self, k: i64) -> Vec<MovePart> {
        let t = self.first.map(|v| k * v);
        let mut parts = self.parts.clone();
        let m = &mut parts[self.moving];
        m.pieces = m.pieces.iter().map(|p| p.translated(t)).collect();
        parts
    }

    /// `expected.json`: the level, the moving part, the first move's direction and
    /// extent (as displacements), and a direction that frees the part afterwards.
    pub fn expected_json(&self) -> String {
        let v = |d: [i64; 3]| format!("[{}, {}, {}]", d[0], d[1], d[2]);
        let [lo, hi] = self.first_range;
        format!(
            "{{\n  \"level\": 2,\n  \"axes\": false,\n  \"moving\": \"{}\",\n  \"first_move\": {},\n  \
             \"first_move_min\": {},\n  \"first_move_max\": {},\n  \"second_move\": {}\n}}\n",
            self.parts[self.moving].name,
            v(self.first),
            v(self.first.map(|c| lo * c)),
            v(self.first.map(|c| hi * c)),
            v(self.second)
        )
    }
}

/// Writes parts as an assembly folder: `<part>/piece_<i>.off` for each convex piece and
/// an `assembly.json` declaring each part as the union of its pieces.
pub fn write_parts(dir: &Path, name: &str, parts: &[MovePart]) -> std::io::Result<()> {
    std::fs::create_dir_all(dir)?;
    let mut json = format!("{{\n  \"name\": \"{name}\",\n  \"parts\": [\n");
    for (k, part) in parts.iter().enumerate() {
        std::fs::create_dir_all(dir.join(part.name))?;
        let mut files = Vec::new();
        for (i, p) in part.pieces.iter().enumerate() {
            let file = format!("{}/piece_{i}.off", part.name);
            std::fs::write(dir.join(&file), p.mesh().off_text())?;
            files.push(format!("\"{file}\""));
        }
        let comma = if k + 1 < parts.len() { "," } else { "" };
        let _ = writeln!(
            json,
            "    {{\"name\": \"{}\", \"pieces\": [{}]}}{comma}",
            part.name,
            files.join(", ")
        );
    }
    json.push_str("  ]\n}\n");
    std::fs::write(dir.join("assembly.json"), json)
}

/// A block in a channel along (1, 1, 0) under two lips that stop short of the channel's
/// closed far end: slide 6 to 7 units along (1, 1, 0), then lift along +z.
pub fn l_slot() -> TwoMoves {
    // Channel coordinates: s along u = (1, 1), t along v = (1, −1), origin (10, 10).
    let p =
        |s: [i64; 2], t: [i64; 2], z: [i64; 2]| Prism::slanted([10, 10], [1, 1], [1, -1], s, t, z);
    let frame = vec![
        p([-2, 12], [-2, 6], [0, 1]), // base
        p([-2, 12], [-2, 0], [1, 3]), // side walls
        p([-2, 12], [4, 6], [1, 3]),
        p([-2, 0], [0, 4], [1, 3]), // closed ends
        p([10, 12], [0, 4], [1, 3]),
        p([-2, 6], [-2, 1], [3, 4]), // lips over the channel's edges, stopping at s = 6
        p([-2, 6], [3, 6], [3, 4]),
    ];
    let block = vec![p([0, 3], [0, 4], [1, 3])];
    TwoMoves {
        name: "l-slot",
        parts: vec![
            MovePart {
                name: "frame",
                pieces: frame,
            },
            MovePart {
                name: "block",
                pieces: block,
            },
        ],
        moving: 1,
        first: [1, 1, 0],
        first_range: [6, 7],
        second: [0, 0, 1],
        about: "A block in a channel running along (1, 1, 0), held down by two lips that \
                stop 3 units short of the channel's closed far end: it slides along \
                (1, 1, 0) by 6 to 7 units (a displacement of (6, 6, 0) to (7, 7, 0)) past \
                the lips, then lifts out along +z.",
    }
}

/// A key (a 6×6 head under a plate, a 2×2 shaft up through a slot) that slides along
/// −x by 9 to 11 units to the keyhole's wide end, then lifts out along +z.
pub fn keyhole() -> TwoMoves {
    let c = Prism::cuboid;
    // A closed box: floor, four walls, and a plate with the keyhole, the wide end
    // [3, 11] × [4, 10] and the slot [11, 18] × [6, 8].
    let frame = vec![
        c([0, 0, 0], [24, 14, 2]),
        c([0, 0, 2], [2, 14, 5]),
        c([22, 0, 2], [24, 14, 5]),
        c([2, 0, 2], [22, 2, 5]),
        c([2, 12, 2], [22, 14, 5]),
        c([0, 0, 5], [24, 4, 7]),
        c([0, 10, 5], [24, 14, 7]),
        c([0, 4, 5], [3, 10, 7]),
        c([18, 4, 5], [24, 10, 7]),
        c([11, 4, 5], [18, 6, 7]),
        c([11, 8, 5], [18, 10, 7]),
    ];
    let key = vec![c([14, 4, 2], [20, 10, 5]), c([16, 6, 5], [18, 8, 10])];
    TwoMoves {
        name: "keyhole",
        parts: vec![
            MovePart {
                name: "box",
                pieces: frame,
            },
            MovePart {
                name: "key",
                pieces: key,
            },
        ],
        moving: 1,
        first: [-1, 0, 0],
        first_range: [9, 11],
        second: [0, 0, 1],
        about: "A key whose 6×6 head lies in a closed box under a plate and whose 2×2 \
                shaft rises through a slot in the plate: it slides along −x by 9 to 11 \
                units until the head is under the keyhole's wide end, then lifts out \
                along +z.",
    }
}

/// A drawer (an open tray) in a cabinet open at the front (−y) behind a lip 3 units
/// high: it lifts by 3 to 8 units along +z, then pulls out along −y.
pub fn drawer() -> TwoMoves {
    let c = Prism::cuboid;
    let cabinet = vec![
        c([0, 0, 0], [24, 24, 2]),   // floor
        c([0, 0, 20], [24, 24, 22]), // top
        c([0, 22, 2], [24, 24, 20]), // back
        c([0, 0, 2], [2, 22, 20]),   // sides
        c([22, 0, 2], [24, 22, 20]),
        c([2, 0, 2], [22, 2, 5]), // the lip at the front bottom edge
    ];
    let drawer = vec![
        c([2, 2, 2], [22, 22, 4]), // bottom
        c([2, 2, 4], [22, 4, 12]), // front and back
        c([2, 20, 4], [22, 22, 12]),
        c([2, 4, 4], [4, 20, 12]), // sides
        c([20, 4, 4], [22, 20, 12]),
    ];
    TwoMoves {
        name: "drawer",
        parts: vec![
            MovePart {
                name: "cabinet",
                pieces: cabinet,
            },
            MovePart {
                name: "drawer",
                pieces: drawer,
            },
        ],
        moving: 1,
        first: [0, 0, 1],
        first_range: [3, 8],
        second: [0, -1, 0],
        about: "A drawer filling a cabinet's width and depth, on its floor, behind a lip \
                3 units high along the open front's bottom edge: it lifts by 3 to 8 units \
                along +z (the ceiling is 8 above it), then pulls out along −y.",
    }
}

/// A block in a covered channel along (2, 1, 0) with a window in one side wall near the
/// far end: it slides by 5 to 6 times (2, 1, 0), then leaves along (−1, 2, 0).
pub fn diagonal_two_move() -> TwoMoves {
    // Channel coordinates: s along u = (2, 1), t along v = (−1, 2), origin (10, 10).
    let p =
        |s: [i64; 2], t: [i64; 2], z: [i64; 2]| Prism::slanted([10, 10], [2, 1], [-1, 2], s, t, z);
    let frame = vec![
        p([-1, 9], [-1, 3], [0, 1]), // floor
        p([-1, 9], [-1, 3], [3, 4]), // roof
        p([-1, 9], [-1, 0], [1, 3]), // solid side wall
        p([-1, 5], [2, 3], [1, 3]),  // side wall with the window s in [5, 8]
        p([-1, 0], [0, 2], [1, 3]),  // closed ends
        p([8, 9], [0, 3], [1, 3]),
    ];
    let block = vec![p([0, 2], [0, 2], [1, 3])];
    TwoMoves {
        name: "diagonal-two-move",
        parts: vec![
            MovePart {
                name: "tunnel",
                pieces: frame,
            },
            MovePart {
                name: "block",
                pieces: block,
            },
        ],
        moving: 1,
        first: [2, 1, 0],
        first_range: [5, 6],
        second: [-1, 2, 0],
        about: "A block in a covered, closed channel running along (2, 1, 0), with a \
                window in one side wall near the far end: it slides by 5 to 6 times \
                (2, 1, 0) (a displacement of (10, 5, 0) to (12, 6, 0)) to the window, then \
                leaves through it along (−1, 2, 0); neither move is along an axis.",
    }
}

/// The four level-2 assemblies.
pub fn all() -> Vec<TwoMoves> {
    vec![l_slot(), keyhole(), drawer(), diagonal_two_move()]
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::collections::HashMap;

    fn meet_any(moving: &[Prism], fixed: &[Prism]) -> bool {
        moving
            .iter()
            .any(|m| fixed.iter().any(|f| interiors_meet(m, f)))
    }

    #[test]
    fn prism_meshes_are_closed_and_outward() {
        for a in all() {
            for part in &a.parts {
                for p in &part.pieces {
                    let m = p.mesh();
                    let mut edges: HashMap<(u32, u32), i32> = HashMap::new();
                    for t in &m.triangles {
                        for k in 0..3 {
                            *edges.entry((t[k], t[(k + 1) % 3])).or_default() += 1;
                        }
                    }
                    assert!(edges
                        .iter()
                        .all(|(&(x, y), &c)| c == 1 && edges.get(&(y, x)) == Some(&1)));
                    let h = i128::from(p.z[1] - p.z[0]);
                    assert_eq!(m.volume6(), 3 * area2(&p.poly) * h, "{}", a.name);
                    assert!(m.points.iter().flatten().all(|v| (0..100).contains(v)));
                    // No zero-area triangle.
                    for t in &m.triangles {
                        let [x, y, z] = t.map(|i| m.points[i as usize]);
                        let u = [0, 1, 2].map(|k| y[k] - x[k]);
                        let v = [0, 1, 2].map(|k| z[k] - x[k]);
                        let n = [
                            u[1] * v[2] - u[2] * v[1],
                            u[2] * v[0] - u[0] * v[2],
                            u[0] * v[1] - u[1] * v[0],
                        ];
                        assert_ne!(n, [0, 0, 0]);
                    }
                }
            }
        }
    }

    #[test]
    fn pieces_have_disjoint_interiors() {
        for a in all() {
            let pieces: Vec<&Prism> = a.parts.iter().flat_map(|p| &p.pieces).collect();
            for i in 0..pieces.len() {
                for j in i + 1..pieces.len() {
                    assert!(!interiors_meet(pieces[i], pieces[j]), "{} {i} {j}", a.name);
                }
            }
        }
    }

    #[test]
    fn the_first_move_is_free_and_then_the_second_frees_the_part() {
        for a in all() {
            let fixed = &a.parts[1 - a.moving].pieces;
            let moving = &a.parts[a.moving].pieces;
            let [lo, hi] = a.first_range;
            // How far the first move can go: its sweep meets nothing up to `reach`, and
            // something one unit further (so it is finite).
            let sweep_free = |k: i64| {
                let swept: Vec<Prism> = moving
                    .iter()
                    .map(|p| p.swept(a.first.map(|v| k * v)))
                    .collect();
                !meet_any(&swept, fixed)
            };
            let reach = (1..100).take_while(|&k| sweep_free(k)).last().unwrap_or(0);
            assert!(reach >= hi && reach < 99, "{}: reach {reach}", a.name);
            // The second move takes the part far (200 times the direction: past every
            // coordinate below 100) exactly from the displacements `lo..=hi`.
            for k in 0..=reach {
                let at = &a.displaced(k)[a.moving].pieces;
                let out: Vec<Prism> = at
                    .iter()
                    .map(|p| p.swept(a.second.map(|v| 200 * v)))
                    .collect();
                assert_eq!(
                    !meet_any(&out, fixed),
                    (lo..=hi).contains(&k),
                    "{} k = {k}",
                    a.name
                );
            }
        }
    }

    #[test]
    fn the_moving_part_can_start_along_its_first_direction_only() {
        let dot = |a: [i64; 3], b: [i64; 3]| a[0] * b[0] + a[1] * b[1] + a[2] * b[2];
        for a in all() {
            let normals = contact_normals(&a.parts[a.moving].pieces, &a.parts[1 - a.moving].pieces);
            let f = a.first;
            // `first` pushes into no contact face, and some contact face opposes it.
            assert!(normals.iter().all(|&n| dot(n, f) <= 0), "{}", a.name);
            assert!(normals.iter().any(|&n| dot(n, f) < 0), "{}", a.name);
            // Contact faces facing both ways along two independent directions across
            // `first`: a direction pushing into none is a positive multiple of `first`
            // (and that move is finite, by the sweep test), so no single translation
            // separates the parts.
            let across: Vec<[i64; 3]> = normals
                .iter()
                .copied()
                .filter(|&n| dot(n, f) == 0 && normals.contains(&n.map(|c| -c)))
                .collect();
            let independent = across.iter().any(|&u| {
                across.iter().any(|&v| {
                    let c = [
                        u[1] * v[2] - u[2] * v[1],
                        u[2] * v[0] - u[0] * v[2],
                        u[0] * v[1] - u[1] * v[0],
                    ];
                    c != [0, 0, 0]
                })
            });
            assert!(independent, "{}: {normals:?}", a.name);
        }
    }

    #[test]
    fn contact_normals_of_a_cube_in_a_corner() {
        let cube = [Prism::cuboid([1, 1, 1], [2, 2, 2])];
        let walls = [
            Prism::cuboid([0, 0, 0], [3, 3, 1]),
            Prism::cuboid([0, 0, 1], [1, 3, 3]),
            // Touching only along an edge: no contact face.
            Prism::cuboid([2, 2, 1], [3, 3, 3]),
        ];
        assert_eq!(contact_normals(&cube, &walls), vec![[-1, 0, 0], [0, 0, -1]]);
    }

    #[test]
    fn hulls_and_separation_are_exact() {
        assert_eq!(
            hull(vec![[0, 0], [2, 0], [1, 0], [2, 2], [0, 2], [1, 1]]),
            vec![[0, 0], [2, 0], [2, 2], [0, 2]]
        );
        let a = Prism::cuboid([0, 0, 0], [2, 2, 2]);
        assert!(!interiors_meet(&a, &Prism::cuboid([2, 0, 0], [4, 2, 2])));
        assert!(interiors_meet(&a, &Prism::cuboid([1, 1, 1], [4, 2, 2])));
        let diamond = Prism::new(&[[2, 1], [3, 2], [2, 3], [1, 2]], 0, 1);
        assert!(interiors_meet(&a, &diamond));
        assert!(!interiors_meet(
            &a.translated([1, 1, 0]).translated([-3, -3, 0]),
            &diamond
        ));
    }
}
