//! Exact support queries on polytopes with many vertices, by climbing the vertex graph.
//!
//! A linear function on a convex polytope has no local maximum that is not global: every
//! vertex that does not attain the maximum has a neighbour (along an edge) with a larger
//! value, and the vertices attaining it form a face, whose graph is connected. So the
//! exact support `max n · v` is found by walking to a better neighbour while there is
//! one (every comparison exact), then gathering the equal neighbours. The walk starts at
//! a vertex extreme along the centre of `n`'s cell in a cube map of directions (3,456
//! cells), a few steps from the answer even on a tessellated cylinder's ring of
//! thousands of vertices, where a scan of every vertex was the cost of a piece pair's
//! separating axes.

use crate::polytope::Polytope;
use apart_kernel::int::Int;
use apart_kernel::{fvec, Vec3};

/// Polytopes with at least this many vertices are climbed; smaller ones are scanned.
pub(crate) const CLIMB_MIN: usize = 64;

/// The shadow points of `p` and twice their dot products' error bound, when `u` (a
/// float unit direction) is finite and `p` has a shadow.
fn filter<'p>(p: &'p Polytope, u: &[f64; 3]) -> Option<(&'p [[f64; 3]], f64)> {
    let sh = p.shadow().filter(|_| u.iter().all(|c| c.is_finite()))?;
    Some((&sh.points, 2.0 * sh.error()))
}

/// Cells along each side of a face of the cube map of directions.
const SIDE: usize = 24;

/// The cell of the cube map holding direction `u` (any nonzero length; a zero or
/// non-finite one gets cell 0): the face of the largest coordinate, then the other two
/// coordinates over it.
fn cell_of(u: [f64; 3]) -> usize {
    let k = (0..3)
        .max_by(|&i, &j| u[i].abs().total_cmp(&u[j].abs()))
        .unwrap_or(0);
    let m = u[k].abs();
    if !(m > 0.0 && m.is_finite()) {
        return 0;
    }
    let face = 2 * k + usize::from(u[k] < 0.0);
    let coord = |c: f64| (((c / m + 1.0) * 0.5 * SIDE as f64) as usize).min(SIDE - 1);
    let (a, b) = (u[(k + 1) % 3], u[(k + 2) % 3]);
    (face * SIDE + coord(a)) * SIDE + coord(b)
}

/// The unit direction at the centre of cube-map cell `cell` ([`cell_of`]'s inverse).
fn cell_direction(cell: usize) -> [f64; 3] {
    let (face, rest) = (cell / (SIDE * SIDE), cell % (SIDE * SIDE));
    let (k, negative) = (face / 2, face % 2 == 1);
    let centre = |i: usize| (i as f64 + 0.5) / SIDE as f64 * 2.0 - 1.0;
    let mut d = [0.0; 3];
    d[k] = if negative { -1.0 } else { 1.0 };
    d[(k + 1) % 3] = centre(rest / SIDE);
    d[(k + 2) % 3] = centre(rest % SIDE);
    fvec::scale(d, 1.0 / fvec::norm(d))
}

/// The most vertices of a maximal face gathered by climbing.
const FACE_MAX: usize = 32;

/// The vertex graph of a polytope and its extreme vertices along sample directions.
#[derive(Clone, Debug)]
pub(crate) struct Climb {
    /// Neighbours of vertex `v`: `adjacent[offsets[v]..offsets[v + 1]]`.
    offsets: Vec<u32>,
    adjacent: Vec<u32>,
    /// For each cell of a cube map of directions ([`cell_of`]), a vertex extreme along
    /// its centre (in floating point: only a start, never an answer).
    starts: Vec<u32>,
}

impl Climb {
    /// The climbing structure of `p`.
    pub(crate) fn new(p: &Polytope) -> Climb {
        let nv = p.vertices().len();
        let mut degree = vec![0u32; nv + 1];
        for e in p.edges() {
            degree[e.ends[0] as usize] += 1;
            degree[e.ends[1] as usize] += 1;
        }
        let mut offsets = Vec::with_capacity(nv + 1);
        let mut total = 0u32;
        for d in &degree[..nv] {
            offsets.push(total);
            total += d;
        }
        offsets.push(total);
        let mut fill = offsets.clone();
        let mut adjacent = vec![0u32; total as usize];
        for e in p.edges() {
            let [a, b] = e.ends;
            adjacent[fill[a as usize] as usize] = b;
            fill[a as usize] += 1;
            adjacent[fill[b as usize] as usize] = a;
            fill[b as usize] += 1;
        }
        let approx: Vec<[f64; 3]> = p.vertices().iter().map(Vec3::approx).collect();
        let mut climb = Climb {
            offsets,
            adjacent,
            starts: Vec::with_capacity(6 * SIDE * SIDE),
        };
        // Each cell's start: the float climb from the previous cell's (a few steps).
        let mut v = 0u32;
        for cell in 0..6 * SIDE * SIDE {
            let u = cell_direction(cell);
            let at = |w: u32| fvec::dot(approx[w as usize], u);
            loop {
                let next = climb
                    .neighbours(v)
                    .iter()
                    .copied()
                    .filter(|&w| at(w) > at(v))
                    .max_by(|&x, &y| at(x).total_cmp(&at(y)));
                match next {
                    Some(w) => v = w,
                    None => break,
                }
            }
            climb.starts.push(v);
        }
        climb
    }

    fn neighbours(&self, v: u32) -> &[u32] {
        &self.adjacent[self.offsets[v as usize] as usize..self.offsets[v as usize + 1] as usize]
    }

    /// The support value `max n · v` over the stored vertices of `p` (whose structure
    /// this is).
    pub(crate) fn value(&self, p: &Polytope, n: &Vec3) -> Int {
        self.peak(p, n).1
    }

    /// The support value and the vertices attaining it, in increasing order; `None` when
    /// more than [`FACE_MAX`] vertices attain it.
    pub(crate) fn support(&self, p: &Polytope, n: &Vec3) -> Option<(Int, Vec<u32>)> {
        let (v, best) = self.peak(p, n);
        let verts = p.vertices();
        let u = n.unit_f64();
        let arg = match filter(p, &u) {
            Some((points, slack)) => {
                let at = |w: u32| fvec::dot(points[w as usize], u);
                self.face(v, |x, w| {
                    (at(w) - at(x)).abs() <= slack && n.dot(&verts[w as usize]) == best
                })
            }
            None => self.face(v, |_, w| n.dot(&verts[w as usize]) == best),
        }?;
        Some((best, arg))
    }

    /// A vertex attaining `max n · v`, and that value.
    fn peak(&self, p: &Polytope, n: &Vec3) -> (u32, Int) {
        let verts = p.vertices();
        let start = self.starts[cell_of(n.approx())];
        let exact = |w: u32| n.dot(&verts[w as usize]);
        // Machine integers when they fit (products of two 62-bit values in `i128`).
        if let Some(m) = n.as_small() {
            let small = |w: u32| {
                let c = verts[w as usize].as_small()?;
                Some(
                    m[0] as i128 * c[0] as i128
                        + m[1] as i128 * c[1] as i128
                        + m[2] as i128 * c[2] as i128,
                )
            };
            let v = self.climb(start, |a, b| match (small(a), small(b)) {
                (Some(x), Some(y)) => x > y,
                _ => exact(a) > exact(b),
            });
            return (v, exact(v));
        }
        let u = n.unit_f64();
        let v = match filter(p, &u) {
            // Each `u · x` is within `slack / 2` of the exact `n · x / (|n| den)`: a
            // float difference beyond `slack` decides, else the exact values do.
            Some((points, slack)) => {
                let at = |w: u32| fvec::dot(points[w as usize], u);
                self.climb(start, |a, b| {
                    let (fa, fb) = (at(a), at(b));
                    if fa > fb + slack {
                        true
                    } else if fa < fb - slack {
                        false
                    } else {
                        exact(a) > exact(b)
                    }
                })
            }
            None => self.climb(start, |a, b| exact(a) > exact(b)),
        };
        (v, exact(v))
    }

    /// The walk from `start` to a vertex no neighbour of which is `above` it (`above(a,
    /// b)`: `a`'s value exceeds `b`'s, exactly): the maximum. Each step goes to a
    /// neighbour above the current vertex, so the value increases strictly.
    fn climb(&self, start: u32, above: impl Fn(u32, u32) -> bool) -> u32 {
        let mut v = start;
        'walk: loop {
            for &w in self.neighbours(v) {
                if above(w, v) {
                    v = w;
                    continue 'walk;
                }
            }
            return v;
        }
    }

    /// The maximal face from its vertex `v`: connected, so reached through neighbours
    /// of equal value (`equal(x, w)` for a vertex `x` of the face and a neighbour `w`).
    /// `None` beyond [`FACE_MAX`] vertices (a cylinder's cap along its axis).
    fn face(&self, v: u32, equal: impl Fn(u32, u32) -> bool) -> Option<Vec<u32>> {
        let mut arg = vec![v];
        let mut stack = vec![v];
        while let Some(x) = stack.pop() {
            for &w in self.neighbours(x) {
                if !arg.contains(&w) && equal(x, w) {
                    if arg.len() == FACE_MAX {
                        return None;
                    }
                    arg.push(w);
                    stack.push(w);
                }
            }
        }
        arg.sort_unstable();
        Some(arg)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use proptest::prelude::*;

    /// A prism over a regular-ish `k`-gon (rounded to the grid), `h` high, shifted by
    /// `(dx, dy)`: a tessellated cylinder, the climb's typical piece.
    fn cylinder(k: usize, r: f64, h: i64, dx: i64, dy: i64) -> Polytope {
        let mut pts = Vec::new();
        for i in 0..k {
            let t = i as f64 * std::f64::consts::TAU / k as f64;
            let (x, y) = (
                (r * t.cos()).round() as i64 + dx,
                (r * t.sin()).round() as i64 + dy,
            );
            pts.push(Vec3::new(x, y, 0));
            pts.push(Vec3::new(x, y, h));
        }
        Polytope::hull(&pts).unwrap()
    }

    fn direction() -> impl Strategy<Value = Vec3> {
        (-3i64..=3, -3i64..=3, -3i64..=3, -50i64..=50)
            .prop_filter("nonzero", |v| *v != (0, 0, 0, 0))
            .prop_map(|(x, y, z, w)| {
                // Small directions hit faces and edges; mixed ones general vertices.
                if w % 3 == 0 {
                    Vec3::new(x * 97 + w, y * 89 - w, z * 83 + 2 * w)
                } else {
                    Vec3::new(x, y, z)
                }
            })
    }

    #[test]
    fn each_cell_centre_lies_in_its_cell() {
        for cell in 0..6 * SIDE * SIDE {
            assert_eq!(cell_of(cell_direction(cell)), cell);
            assert_eq!(cell_of(fvec::scale(cell_direction(cell), 1e-200)), cell);
        }
        assert_eq!(cell_of([0.0; 3]), 0);
    }

    proptest! {
        #![proptest_config(ProptestConfig::with_cases(96))]
        /// Climbing finds the scan's support value and maximisers, on cylinders (many
        /// vertices of equal height, caps of many vertices) and random hulls.
        #[test]
        fn climbing_agrees_with_the_scan(
            k in 32usize..1200,
            r in 50f64..100000.0,
            h in 1i64..1000,
            shift in (-1000i64..1000, -1000i64..1000),
            pts in prop::collection::vec((-3000i64..3000, -3000i64..3000, -3000i64..3000), 64..400),
            dirs in prop::collection::vec(direction(), 1..20),
            den in 1i64..1000,
        ) {
            let random = Polytope::hull(
                &pts.iter().map(|&(x, y, z)| Vec3::new(x, y, z)).collect::<Vec<_>>(),
            ).unwrap();
            // Directions and coordinates beyond machine integers take the filtered walk.
            let big = Vec3::new(1 << 40, 3, -(1 << 41)).scale(&Int::from(1i64 << 40));
            let huge: Vec<Vec3> = dirs.iter().map(|d| d.scale(&Int::from(1i64 << 62))).collect();
            let wide = Polytope::hull(
                &pts.iter().map(|&(x, y, z)| Vec3::new(x, y, z).scale(&Int::from(1i64 << 55))).collect::<Vec<_>>(),
            ).unwrap().with_den(Int::from(den));
            for p in [cylinder(k, r, h, shift.0, shift.1), random, wide] {
                if p.vertices().len() < CLIMB_MIN {
                    continue;
                }
                let c = Climb::new(&p);
                for d in dirs.iter().chain(&huge).chain([&big]) {
                    let scan = p.support_scan(d);
                    match c.support(&p, d) {
                        Some(s) => prop_assert_eq!(&s, &scan),
                        None => prop_assert!(scan.1.len() > FACE_MAX),
                    }
                    prop_assert_eq!(c.value(&p, d), scan.0.clone());
                    prop_assert_eq!(p.support_value(d), scan.0.clone());
                    prop_assert_eq!(p.support(d), scan);
                }
                // Copies whose stored integers change (translated, rescaled) climb on their own.
                let t = p.translated(&Vec3::new(7, -3, 11));
                let r = p.rescaled(&Int::from(3));
                for d in dirs.iter().chain(&huge) {
                    prop_assert_eq!(t.support(d), t.support_scan(d));
                    prop_assert_eq!(r.support(d), r.support_scan(d));
                    prop_assert_eq!(r.support_value(d), r.support_scan(d).0);
                }
            }
        }
    }
}
