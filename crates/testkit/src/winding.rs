//! An independent oracle for the winding-number rule: the exact winding number of a
//! point with respect to a triangle soup on the integer grid, and a seeded Monte Carlo
//! estimate (with a stated confidence bound) of the volume of the solid `{w >= 1}`.
//!
//! The winding number is counted along a ray in the `+x` direction from the point
//! symbolically perturbed by `(0, ε, ε²)`: the perturbed ray meets no edge and no vertex
//! of any triangle, so every crossing is a transversal crossing through a triangle's
//! interior, counted `+1` where the triangle faces `+x` (the ray leaves through it) and
//! `-1` where it faces `-x`. Off the surface the winding number is locally constant, so
//! the count at the perturbed point is the winding number at the point itself; a point
//! exactly on a triangle (zero-area slivers included) has none. All arithmetic is in
//! `i128` on coordinates below `2^31` in magnitude after scaling, exact.

use crate::solids::{IntMesh, Lcg};
use crate::Soup;

/// A triangle soup on the integer grid: any triangles (open, non-manifold, crossing,
/// zero-area), counter-clockwise seen from where the generator says is outside.
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct TriSoup {
    /// Vertex coordinates.
    pub points: Vec<[i64; 3]>,
    /// Triangles as vertex indices.
    pub triangles: Vec<[u32; 3]>,
}

impl TriSoup {
    /// Appends `other`, renumbering its vertices (no welding).
    pub fn append(&mut self, other: &TriSoup) {
        let base = self.points.len() as u32;
        self.points.extend_from_slice(&other.points);
        self.triangles
            .extend(other.triangles.iter().map(|t| t.map(|v| v + base)));
    }

    /// Adds a vertex and returns its index.
    pub fn point(&mut self, p: [i64; 3]) -> u32 {
        self.points.push(p);
        (self.points.len() - 1) as u32
    }

    /// Adds the triangle `a, b, c` (new vertices).
    pub fn triangle(&mut self, a: [i64; 3], b: [i64; 3], c: [i64; 3]) {
        let t = [self.point(a), self.point(b), self.point(c)];
        self.triangles.push(t);
    }

    /// Adds the planar polygon `poly` (convex, or star-shaped from its first vertex) as
    /// a fan of triangles from its first vertex.
    pub fn fan(&mut self, poly: &[[i64; 3]]) {
        let ids: Vec<u32> = poly.iter().map(|&p| self.point(p)).collect();
        for k in 1..ids.len() - 1 {
            self.triangles.push([ids[0], ids[k], ids[k + 1]]);
        }
    }

    /// The soup moved by `t`.
    pub fn translated(mut self, t: [i64; 3]) -> TriSoup {
        for p in &mut self.points {
            for k in 0..3 {
                p[k] += t[k];
            }
        }
        self
    }

    /// The soup with every triangle reversed.
    pub fn reversed(mut self) -> TriSoup {
        for t in &mut self.triangles {
            t.swap(1, 2);
        }
        self
    }

    /// As a [`Soup`] (exact: the coordinates are small integers).
    pub fn to_soup(&self) -> Soup {
        Soup {
            vertices: self.points.iter().map(|p| p.map(|c| c as f64)).collect(),
            faces: self.triangles.iter().map(|t| t.to_vec()).collect(),
        }
    }

    /// The smallest box holding every vertex: `(lo, hi)`.
    pub fn bbox(&self) -> ([i64; 3], [i64; 3]) {
        let mut lo = [i64::MAX; 3];
        let mut hi = [i64::MIN; 3];
        for p in &self.points {
            for k in 0..3 {
                lo[k] = lo[k].min(p[k]);
                hi[k] = hi[k].max(p[k]);
            }
        }
        (lo, hi)
    }

    /// Six times the signed volume of the triangles as a 2-chain (the divergence
    /// theorem's sum; the volume of `{w >= 1}` only when every winding number is 0 or 1
    /// and the soup is closed).
    pub fn volume6(&self) -> i128 {
        IntMesh {
            points: self.points.clone(),
            triangles: self.triangles.clone(),
        }
        .volume6()
    }

    /// The net use of each undirected edge (keyed by its coordinates, smaller end
    /// first): `+1` for each triangle using it from the smaller end to the larger, `-1`
    /// the other way. The edges with a non-zero count are the soup's boundary as a
    /// chain (zero for every edge of a closed, consistently oriented surface).
    pub fn edge_balance(&self) -> std::collections::BTreeMap<([i64; 3], [i64; 3]), i64> {
        let mut m = std::collections::BTreeMap::new();
        for t in &self.triangles {
            for k in 0..3 {
                let (a, b) = (
                    self.points[t[k] as usize],
                    self.points[t[(k + 1) % 3] as usize],
                );
                if a == b {
                    continue;
                }
                let (key, s) = if a < b { ((a, b), 1) } else { ((b, a), -1) };
                *m.entry(key).or_insert(0) += s;
            }
        }
        m
    }
}

impl From<&IntMesh> for TriSoup {
    fn from(m: &IntMesh) -> TriSoup {
        TriSoup {
            points: m.points.clone(),
            triangles: m.triangles.clone(),
        }
    }
}

fn sub(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [a[0] - b[0], a[1] - b[1], a[2] - b[2]]
}

fn cross(a: [i128; 3], b: [i128; 3]) -> [i128; 3] {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn dot(a: [i128; 3], b: [i128; 3]) -> i128 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

/// One triangle, scaled, with what the ray test needs.
struct Tri {
    v: [[i128; 3]; 3],
    /// `(b - a) × (c - a)`.
    n: [i128; 3],
    /// The box of its `y, z` projection.
    lo: [i128; 2],
    hi: [i128; 2],
}

/// The exact winding number of points with respect to a triangle soup whose
/// coordinates are scaled by `scale` (so that the points asked about, in the same
/// scaled units, may lie between the soup's grid points).
pub struct WindingOracle {
    tris: Vec<Tri>,
}

/// Beyond this magnitude (scaled) the `i128` products could overflow.
const LIMIT: i128 = 1 << 31;

impl WindingOracle {
    /// The oracle for `soup` with its coordinates multiplied by `scale >= 1`.
    ///
    /// # Panics
    /// When a scaled coordinate reaches `2^31` in magnitude.
    pub fn new(soup: &TriSoup, scale: i64) -> WindingOracle {
        assert!(scale >= 1);
        let tris = soup
            .triangles
            .iter()
            .map(|t| {
                let v = t.map(|i| {
                    soup.points[i as usize].map(|c| {
                        let s = c as i128 * scale as i128;
                        assert!(s.abs() < LIMIT, "coordinate {c} too large at scale {scale}");
                        s
                    })
                });
                let n = cross(sub(v[1], v[0]), sub(v[2], v[0]));
                let lo = [1, 2].map(|k| v[0][k].min(v[1][k]).min(v[2][k]));
                let hi = [1, 2].map(|k| v[0][k].max(v[1][k]).max(v[2][k]));
                Tri {
                    v,
                    n,
                    lo: [lo[0], lo[1]],
                    hi: [hi[0], hi[1]],
                }
            })
            .collect();
        WindingOracle { tris }
    }

    /// The winding number at `p` (scaled units), `None` when `p` lies on a triangle.
    pub fn winding(&self, p: [i64; 3]) -> Option<i64> {
        let p = p.map(|c| {
            let c = c as i128;
            assert!(c.abs() < LIMIT, "point coordinate {c} too large");
            c
        });
        let mut w = 0;
        for t in &self.tris {
            if p[1] < t.lo[0] || p[1] > t.hi[0] || p[2] < t.lo[1] || p[2] > t.hi[1] {
                continue;
            }
            if on_triangle(t, p) {
                return None;
            }
            if t.n[0] == 0 {
                // Parallel to the ray (zero-area slivers included): never crossed.
                continue;
            }
            let s = t.n[0].signum();
            let inside = (0..3).all(|k| orient_perturbed(t.v[k], t.v[(k + 1) % 3], p) == s);
            if !inside {
                continue;
            }
            // The ray meets the plane at x > p.x iff n · (q − a) has the sign of −n.x,
            // q the perturbed point (p off the triangle, so the first term decides
            // whenever it is not zero).
            let d = dot(t.n, sub(p, t.v[0]));
            let side = if d != 0 {
                d.signum()
            } else if t.n[1] != 0 {
                t.n[1].signum()
            } else {
                t.n[2].signum()
            };
            if side == -s {
                w += s as i64;
            }
        }
        Some(w)
    }
}

/// The sign of the orientation of `(a, b, q)` projected on the `y, z` plane, `q` being
/// `p + (0, ε, ε²)`: the exact determinant, else its `ε` term, else its `ε²` term.
fn orient_perturbed(a: [i128; 3], b: [i128; 3], p: [i128; 3]) -> i128 {
    let det = (b[1] - a[1]) * (p[2] - a[2]) - (b[2] - a[2]) * (p[1] - a[1]);
    if det != 0 {
        det.signum()
    } else if a[2] != b[2] {
        (a[2] - b[2]).signum()
    } else {
        (b[1] - a[1]).signum()
    }
}

/// True when `p` lies on the closed triangle (on a segment for a zero-area one).
fn on_triangle(t: &Tri, p: [i128; 3]) -> bool {
    let [a, b, c] = t.v;
    if t.n == [0, 0, 0] {
        return on_segment(a, b, p) || on_segment(b, c, p) || on_segment(c, a, p);
    }
    if dot(t.n, sub(p, a)) != 0 {
        return false;
    }
    // Project along the normal's largest component, keeping the orientation's sign.
    let k = (0..3).max_by_key(|&k| t.n[k].abs()).expect("three axes");
    let (u, v) = ((k + 1) % 3, (k + 2) % 3);
    let o = |a: [i128; 3], b: [i128; 3]| {
        ((b[u] - a[u]) * (p[v] - a[v]) - (b[v] - a[v]) * (p[u] - a[u])) * t.n[k].signum()
    };
    o(a, b) >= 0 && o(b, c) >= 0 && o(c, a) >= 0
}

fn on_segment(a: [i128; 3], b: [i128; 3], p: [i128; 3]) -> bool {
    let (ab, ap) = (sub(b, a), sub(p, a));
    cross(ab, ap) == [0, 0, 0] && dot(ab, ap) >= 0 && dot(ab, ap) <= dot(ab, ab)
}

/// The winding number of the grid point `p` with respect to `soup` (`None` on a
/// triangle).
pub fn winding_number(soup: &TriSoup, p: [i64; 3]) -> Option<i64> {
    WindingOracle::new(soup, 1).winding(p)
}

/// A Monte Carlo estimate of a volume.
#[derive(Clone, Debug, PartialEq)]
pub struct Estimate {
    /// Points drawn (those that fell on a triangle excluded).
    pub samples: usize,
    /// Points with winding number at least 1.
    pub hits: usize,
    /// Points that fell exactly on a triangle (drawn again).
    pub on_surface: usize,
    /// The volume of the sampling box.
    pub box_volume: f64,
    /// The estimate: `box_volume · hits / samples`.
    pub volume: f64,
    /// Four binomial standard errors, `4 · box_volume · sqrt(p (1 − p) / n)` with
    /// `p` the hit fraction, floored at `p (1 − p) >= 1/n` so that a fraction of 0 or 1
    /// still leaves room: a true volume outside `volume ± bound` has a probability
    /// below 1e-4 under the normal approximation.
    pub bound: f64,
}

impl Estimate {
    /// True when `v` lies within the bound of the estimate.
    pub fn agrees(&self, v: f64) -> bool {
        (self.volume - v).abs() <= self.bound
    }

    /// True when the interval `lo..=hi` comes within the bound of the estimate.
    pub fn agrees_with_range(&self, lo: f64, hi: f64) -> bool {
        self.volume + self.bound >= lo && self.volume - self.bound <= hi
    }
}

/// Sub-steps per grid step of the sampled points: samples have odd numerators over
/// `2 · SUBSTEPS`, so they never lie on a grid plane.
pub const SUBSTEPS: i64 = 512;

/// The volume of `{w >= 1}` of `soup` estimated from `samples` points drawn uniformly
/// (from [`Lcg`]`(seed)`) in the soup's bounding box, on the lattice of step
/// `1 / (2 · SUBSTEPS)` offset by half a step; a point that falls on a triangle is
/// drawn again (counted in `on_surface`).
pub fn monte_carlo_volume(soup: &TriSoup, samples: usize, seed: u64) -> Estimate {
    let (lo, hi) = soup.bbox();
    let scale = 2 * SUBSTEPS;
    let oracle = WindingOracle::new(soup, scale);
    let mut rng = Lcg(seed);
    let (mut hits, mut on_surface, mut n) = (0, 0, 0);
    while n < samples {
        let p: [i64; 3] = std::array::from_fn(|k| {
            let cells = ((hi[k] - lo[k]) * SUBSTEPS).max(1) as u64;
            lo[k] * scale + 2 * rng.below(cells) as i64 + 1
        });
        match oracle.winding(p) {
            None => on_surface += 1,
            Some(w) => {
                n += 1;
                if w >= 1 {
                    hits += 1;
                }
            }
        }
    }
    let box_volume: f64 = (0..3).map(|k| (hi[k] - lo[k]) as f64).product();
    let f = hits as f64 / samples as f64;
    let var = (f * (1.0 - f)).max(1.0 / samples as f64);
    Estimate {
        samples,
        hits,
        on_surface,
        box_volume,
        volume: box_volume * f,
        bound: 4.0 * box_volume * (var / samples as f64).sqrt(),
    }
}

/// The exact volume of `{w >= 1}` for a soup whose solid is a union of cells of the
/// rectilinear grid `xs × ys × zs` (strictly increasing; every face of the solid on a
/// grid plane): the sum of the volumes of the cells whose centre has winding number at
/// least 1. `None` when a centre lies on a triangle (the solid is then not such a
/// union).
pub fn cell_volume(soup: &TriSoup, g: [&[i64]; 3]) -> Option<i128> {
    let oracle = WindingOracle::new(soup, 2);
    let mut total = 0i128;
    for x in g[0].windows(2) {
        for y in g[1].windows(2) {
            for z in g[2].windows(2) {
                let c = [x[0] + x[1], y[0] + y[1], z[0] + z[1]];
                if oracle.winding(c)? >= 1 {
                    total += ((x[1] - x[0]) * (y[1] - y[0]) * (z[1] - z[0])) as i128;
                }
            }
        }
    }
    Some(total)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::solids::{cuboid_corners, voxels, CUBOID_QUADS};

    /// The box `lo..hi` as 12 outward triangles.
    pub(crate) fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> TriSoup {
        let c = cuboid_corners(lo, hi);
        let mut s = TriSoup::default();
        for q in CUBOID_QUADS {
            s.fan(&q.map(|i| c[i as usize]));
        }
        s
    }

    #[test]
    fn a_box_has_winding_one_inside_and_none_on_its_faces() {
        let b = cuboid([0; 3], [4, 5, 6]);
        assert_eq!(b.volume6(), 6 * 120);
        assert_eq!(winding_number(&b, [1, 1, 1]), Some(1));
        assert_eq!(winding_number(&b, [3, 4, 5]), Some(1));
        assert_eq!(winding_number(&b, [-1, 1, 1]), Some(0));
        assert_eq!(winding_number(&b, [5, 1, 1]), Some(0));
        assert_eq!(winding_number(&b, [1, 7, 1]), Some(0));
        // On a face, an edge, a vertex, and a face diagonal.
        for p in [
            [0, 1, 1],
            [4, 2, 3],
            [0, 0, 3],
            [4, 5, 6],
            [2, 5, 3],
            [1, 1, 6],
        ] {
            assert_eq!(winding_number(&b, p), None, "{p:?}");
        }
        // Rays that run along faces and through edges and vertices (same y or z as
        // them) still count exactly.
        for p in [[-3, 0, 0], [-3, 5, 6], [-3, 0, 3], [1, 0, 7], [-1, 5, 0]] {
            assert_eq!(winding_number(&b, p), Some(0), "{p:?}");
        }
        let o = WindingOracle::new(&b, 2);
        assert_eq!(o.winding([1, 1, 1]), Some(1));
        assert_eq!(o.winding([7, 9, 11]), Some(1));
        assert_eq!(o.winding([7, 10, 11]), None);
        assert_eq!(o.winding([9, 9, 11]), Some(0));
    }

    #[test]
    fn inside_out_overlapping_and_sliver_cases() {
        let b = cuboid([0; 3], [4; 3]).reversed();
        assert_eq!(winding_number(&b, [1, 1, 1]), Some(-1));
        let mut two = cuboid([0; 3], [4; 3]);
        two.append(&cuboid([2, 2, 2], [6, 6, 6]));
        let o = WindingOracle::new(&two, 2);
        assert_eq!(o.winding([5, 5, 5]), Some(2));
        assert_eq!(o.winding([1, 1, 1]), Some(1));
        assert_eq!(o.winding([9, 9, 9]), Some(1));
        assert_eq!(o.winding([1, 9, 9]), Some(0));
        assert_eq!(cell_volume(&two, [&[0, 2, 4, 6]; 3]), Some(64 + 64 - 8));
        // A zero-area sliver changes nothing except on itself.
        let mut s = cuboid([0; 3], [4; 3]);
        s.triangle([1, 1, 1], [2, 2, 2], [3, 3, 3]);
        assert_eq!(winding_number(&s, [1, 2, 1]), Some(1));
        assert_eq!(winding_number(&s, [2, 2, 2]), None);
        assert_eq!(winding_number(&s, [3, 3, 3]), None);
        // An open surface: a single square facing +x counts 1 behind it (the ray
        // crosses it), 0 in front.
        let mut sq = TriSoup::default();
        sq.fan(&[[2, 0, 0], [2, 4, 0], [2, 4, 4], [2, 0, 4]]);
        let o = WindingOracle::new(&sq, 2);
        assert_eq!(o.winding([1, 3, 3]), Some(1));
        assert_eq!(o.winding([5, 3, 3]), Some(0));
    }

    #[test]
    fn voxel_unions_have_their_volume_cell_by_cell_and_by_sampling() {
        let mut rng = Lcg(7);
        let dims = [4, 3, 5];
        let on: Vec<bool> = (0..60).map(|_| rng.below(3) > 0).collect();
        let m = voxels(dims, &on);
        let s = TriSoup::from(&m);
        let count = on.iter().filter(|&&b| b).count() as i128;
        assert_eq!(m.volume6(), 6 * count);
        let axis = |n: i64| (0..=n).collect::<Vec<_>>();
        let (xs, ys, zs) = (axis(4), axis(3), axis(5));
        assert_eq!(cell_volume(&s, [&xs, &ys, &zs]), Some(count));
        let e = monte_carlo_volume(&s, 4000, 11);
        assert!(e.agrees(count as f64), "{e:?}");
        assert!(e.bound < 0.1 * count as f64, "{e:?}");
        // A wrong volume is told apart.
        assert!(!e.agrees(count as f64 + 8.0), "{e:?}");
    }

    #[test]
    fn points_on_grid_planes_are_counted_exactly_or_found_on_the_surface() {
        // Random points on a lattice of quarter steps, so that most rays run along
        // grid planes, through edges and vertices of the voxels' triangles: the answer
        // is 1 inside the union, 0 outside, None on its boundary (a point in the
        // closure of a filled and of an empty cell).
        let mut rng = Lcg(21);
        let dims = [3usize, 4, 3];
        let on: Vec<bool> = (0..36).map(|_| rng.below(2) == 0).collect();
        let s = TriSoup::from(&voxels(dims, &on));
        let o = WindingOracle::new(&s, 4);
        let filled = |c: [i64; 3]| {
            (0..3).all(|k| c[k] >= 0 && (c[k] as usize) < dims[k])
                && on[(c[0] as usize * dims[1] + c[1] as usize) * dims[2] + c[2] as usize]
        };
        let (mut inside, mut outside, mut surface) = (0, 0, 0);
        for _ in 0..3000 {
            let p: [i64; 3] = std::array::from_fn(|k| rng.range(-4, 4 * dims[k] as i64 + 4));
            // The cells whose closure holds p.
            let span = |k: usize| {
                let c = p[k].div_euclid(4);
                if p[k] % 4 == 0 {
                    vec![c - 1, c]
                } else {
                    vec![c]
                }
            };
            let mut states = Vec::new();
            for x in span(0) {
                for y in span(1) {
                    for z in span(2) {
                        states.push(filled([x, y, z]));
                    }
                }
            }
            let want = if states.iter().all(|&b| b) {
                inside += 1;
                Some(1)
            } else if states.iter().all(|&b| !b) {
                outside += 1;
                Some(0)
            } else {
                surface += 1;
                None
            };
            assert_eq!(o.winding(p), want, "{p:?}");
        }
        assert!(inside > 100 && outside > 100 && surface > 100);
    }

    #[test]
    fn a_box_is_sampled_to_its_volume() {
        let b = cuboid([0; 3], [4, 5, 6]);
        // Sampling box = the box: every sample hits, the bound stays small.
        let e = monte_carlo_volume(&b, 500, 3);
        assert_eq!(e.hits, 500);
        assert!(e.agrees(120.0) && e.bound < 5.0, "{e:?}");
        let mut b2 = b.clone();
        b2.append(&cuboid([10, 10, 10], [11, 11, 11]));
        let e = monte_carlo_volume(&b2, 3000, 5);
        assert!(e.agrees(121.0), "{e:?}");
    }
}
