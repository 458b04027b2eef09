//! Convex cells in H-representation with exact vertices, and their splitting by a plane.
//!
//! A cell keeps its facet planes (outward) and its vertices, each with the complete list
//! of facets through it. A vertex created by a split is the intersection of the crossed
//! edge's two facet planes with the cutting plane, computed from those three planes
//! (never from the edge's end points), so vertex sizes stay bounded however deep the
//! partition goes.

use apart_kernel::plane::{normals_det_sign, HPoint, Plane};
use apart_kernel::{int, Aabb, Int, Sign, Vec3};
use apart_pieces::hull2d::{self, hull_in_plane};
use apart_pieces::{Polytope, PolytopeError};
use rustc_hash::FxHashMap;

/// A vertex of a cell and the (sorted) indices of the facets through it.
#[derive(Clone, Debug)]
pub(crate) struct CVert {
    pub p: HPoint,
    pub on: Vec<u32>,
}

/// A full-dimensional convex polytope: facets `n · x <= c` and its vertices.
#[derive(Clone, Debug)]
pub(crate) struct Cell {
    pub facets: Vec<Plane>,
    pub verts: Vec<CVert>,
}

impl Cell {
    /// The box `[lo, hi]`.
    pub fn boxed(lo: [i64; 3], hi: [i64; 3]) -> Cell {
        let mut facets = Vec::with_capacity(6);
        for a in 0..3 {
            let mut n = [0i128; 3];
            n[a] = 1;
            facets.push(Plane::new(n, hi[a] as i128));
            n[a] = -1;
            facets.push(Plane::new(n, -(lo[a] as i128)));
        }
        let verts = (0..8)
            .map(|i| {
                let pick = |a: usize| (i >> a) & 1 == 1;
                let p = [0, 1, 2].map(|a| if pick(a) { hi[a] } else { lo[a] });
                let on = (0..3)
                    .map(|a| (2 * a + if pick(a) { 0 } else { 1 }) as u32)
                    .collect();
                CVert {
                    p: HPoint::int(p),
                    on,
                }
            })
            .collect();
        Cell { facets, verts }
    }

    /// The edges as `(vertex, vertex, facet, facet)`: pairs of vertices sharing two facets.
    pub fn edges(&self) -> Vec<(u32, u32, u32, u32)> {
        let mut map: FxHashMap<(u32, u32), (u32, u32, u8)> = FxHashMap::default();
        for (i, v) in self.verts.iter().enumerate() {
            for x in 0..v.on.len() {
                for y in x + 1..v.on.len() {
                    let e = map
                        .entry((v.on[x], v.on[y]))
                        .or_insert((i as u32, u32::MAX, 0));
                    if e.2 == 1 {
                        e.1 = i as u32;
                    }
                    e.2 += 1;
                }
            }
        }
        let mut out: Vec<(u32, u32, u32, u32)> = map
            .into_iter()
            .filter(|(_, e)| e.2 == 2)
            .map(|((fa, fb), (a, b, _))| (a, b, fa, fb))
            .collect();
        out.sort_unstable();
        out
    }

    /// The parts of the cell below (`n · x <= c`) and above the plane `h`; `None` for a part
    /// without interior. With `keep_above = false` only the part below is built.
    pub fn split(&self, h: &Plane, keep_above: bool) -> (Option<Cell>, Option<Cell>) {
        let s: Vec<Sign> = self.verts.iter().map(|v| h.side(&v.p)).collect();
        let pos = s.contains(&Sign::Positive);
        let neg = s.contains(&Sign::Negative);
        if !pos {
            return (neg.then(|| self.clone()), None);
        }
        if !neg {
            return (None, keep_above.then(|| self.clone()));
        }
        let mut fresh: Vec<CVert> = Vec::new();
        for (a, b, fa, fb) in self.edges() {
            if s[a as usize] * s[b as usize] == Sign::Negative {
                let p = HPoint::meet(&self.facets[fa as usize], &self.facets[fb as usize], h)
                    .expect("an edge crossing a plane meets it in one point");
                fresh.push(CVert {
                    p,
                    on: vec![fa, fb],
                });
            }
        }
        let below = self.part(&s, Sign::Negative, &fresh, *h);
        let above = keep_above.then(|| self.part(&s, Sign::Positive, &fresh, h.flipped()));
        (Some(below), above)
    }

    fn part(&self, s: &[Sign], keep: Sign, fresh: &[CVert], cut: Plane) -> Cell {
        let nf = self.facets.len();
        let mut alive = vec![false; nf];
        for (v, &sv) in self.verts.iter().zip(s) {
            if sv == keep {
                for &f in &v.on {
                    alive[f as usize] = true;
                }
            }
        }
        let mut remap = vec![u32::MAX; nf];
        let mut facets = Vec::with_capacity(nf + 1);
        for f in 0..nf {
            if alive[f] {
                remap[f] = facets.len() as u32;
                facets.push(self.facets[f]);
            }
        }
        let cut_id = facets.len() as u32;
        facets.push(cut);
        let mut verts = Vec::with_capacity(self.verts.len() + fresh.len());
        for (v, &sv) in self.verts.iter().zip(s) {
            if sv == -keep {
                continue;
            }
            let mut on: Vec<u32> =
                v.on.iter()
                    .map(|&f| remap[f as usize])
                    .filter(|&f| f != u32::MAX)
                    .collect();
            if sv == Sign::Zero {
                on.push(cut_id);
            }
            verts.push(CVert { p: v.p.clone(), on });
        }
        for v in fresh {
            verts.push(CVert {
                p: v.p.clone(),
                on: vec![remap[v.on[0] as usize], remap[v.on[1] as usize], cut_id],
            });
        }
        Cell { facets, verts }
    }

    /// The convex piece `K` cut from the cell by the inner half-spaces of `planes`,
    /// given polygons `polys[i]` in `planes[i]` that make up the part of `K`'s boundary
    /// in those planes (each point flagged when it may lie on a facet of the cell);
    /// `None` when `K` has no interior. The planes must bound `K` inside the cell this
    /// way (a leaf of the partition: its fragments are the facets of `K` inside the
    /// cell).
    ///
    /// Why it is exact and the same as clipping the cell plane by plane: every vertex of
    /// `K` lying in a facet of `K` is a vertex of that facet, hence of one of the polygons
    /// making up the facet (when the facet is in some `planes[i]`) or of the cell (when
    /// all facets through it are the cell's). So the candidates are the polygons'
    /// points and the cell's vertices inside every plane; each gets the planes of the
    /// polygons it is a corner of and the cell facets through it, and it is a vertex of
    /// `K` exactly when these normals span space (three supporting planes with
    /// independent normals meet `K` in one point, a face of `K`). A cell facet is a
    /// facet of `K` when at least three vertices lie on it (three vertices of a convex
    /// polytope are never collinear). Cost: points times cell facets plus cell vertices
    /// times planes, instead of planes times the growing vertex count of the clipped
    /// cell (quadratic for a leaf with many facets, such as the disc of a lathe).
    pub fn carve(&self, planes: &[Plane], polys: &[Vec<(&HPoint, bool)>]) -> Option<Cell> {
        let nc = self.facets.len();
        let mut facets: Vec<Plane> = self.facets.clone();
        let mut ids: FxHashMap<Plane, u32> =
            FxHashMap::with_capacity_and_hasher(planes.len(), Default::default());
        let mut points: Vec<(HPoint, Vec<u32>)> = Vec::new();
        let corners: usize = polys.iter().map(Vec::len).sum();
        let mut index: FxHashMap<HPoint, usize> =
            FxHashMap::with_capacity_and_hasher(corners, Default::default());
        for (pl, poly) in planes.iter().zip(polys) {
            let k = *ids.entry(*pl).or_insert_with(|| {
                facets.push(*pl);
                facets.len() as u32 - 1
            });
            for &(p, bnd) in poly {
                // Most points are corners of several fragments: look up before cloning.
                let i = match index.get(p) {
                    Some(&i) => i,
                    None => {
                        let on: Vec<u32> = if bnd {
                            (0..nc as u32)
                                .filter(|&f| self.facets[f as usize].side(p) == Sign::Zero)
                                .collect()
                        } else {
                            Vec::new()
                        };
                        points.push((p.clone(), on));
                        index.insert(p.clone(), points.len() - 1);
                        points.len() - 1
                    }
                };
                points[i].1.push(k);
            }
        }
        let cut = &facets[nc..];
        for v in &self.verts {
            if cut.iter().any(|pl| pl.side(&v.p) == Sign::Positive) {
                continue;
            }
            let i = match index.get(&v.p) {
                Some(&i) => i,
                None => {
                    points.push((v.p.clone(), Vec::new()));
                    points.len() - 1
                }
            };
            points[i].1.extend_from_slice(&v.on);
        }
        let mut verts: Vec<CVert> = Vec::new();
        let mut count = vec![0u32; facets.len()];
        for (p, mut on) in points {
            on.sort_unstable();
            on.dedup();
            if spans(&facets, &on) {
                for &f in &on {
                    count[f as usize] += 1;
                }
                verts.push(CVert { p, on });
            }
        }
        // Keep the facets with at least three vertices, renumbered.
        let mut remap = vec![u32::MAX; facets.len()];
        let mut kept = Vec::new();
        for (f, pl) in facets.iter().enumerate() {
            if count[f] >= 3 {
                remap[f] = kept.len() as u32;
                kept.push(*pl);
            }
        }
        for v in &mut verts {
            v.on =
                v.on.iter()
                    .map(|&f| remap[f as usize])
                    .filter(|&f| f != u32::MAX)
                    .collect();
        }
        (kept.len() >= 4 && verts.len() >= 4).then_some(Cell {
            facets: kept,
            verts,
        })
    }

    /// The floating-point bounding box of the vertices (for filters only).
    pub fn bbox(&self) -> Aabb<f64> {
        let mut b = Aabb::EMPTY;
        for v in &self.verts {
            b = b.with(&v.p.approx());
        }
        b
    }

    /// Bits of the largest vertex denominator.
    pub fn max_den_bits(&self) -> u32 {
        self.verts
            .iter()
            .map(|v| int::bit_len(v.p.den()))
            .max()
            .unwrap_or(0)
    }

    /// The cell as a [`Polytope`] with the common denominator of its vertices.
    pub fn to_polytope(&self) -> Result<Polytope, PolytopeError> {
        let (den, pts, on_facet) = self.integer_points();
        let mut facets = Vec::with_capacity(self.facets.len());
        for (f, (pl, ids)) in self.facets.iter().zip(on_facet).enumerate() {
            let normal = Vec3::from_i128(pl.n);
            let cycle = match self.facet_cycle(f as u32, &ids, &pts, &normal) {
                Some(c) => c,
                None => {
                    let sub: Vec<Vec3> = ids.iter().map(|&v| pts[v as usize].clone()).collect();
                    hull_in_plane(&normal, &sub)
                        .into_iter()
                        .map(|i| ids[i])
                        .collect()
                }
            };
            if cycle.len() < 3 {
                return Err(PolytopeError::Flat);
            }
            facets.push((normal, cycle));
        }
        Ok(Polytope::from_facets(&pts, facets)?.with_den(den))
    }

    /// The common denominator of the vertices, the vertices times it, and the vertices
    /// on each facet (in vertex order).
    fn integer_points(&self) -> (Int, Vec<Vec3>, Vec<Vec<u32>>) {
        let mut den = Int::ONE;
        for v in &self.verts {
            let w = v.p.den();
            let g = int::gcd(&den, w);
            den = &den / &g * w;
        }
        let pts: Vec<Vec3> = self
            .verts
            .iter()
            .map(|v| {
                let k = &den / v.p.den();
                let x = v.p.num();
                Vec3::from_ints([&x[0] * &k, &x[1] * &k, &x[2] * &k])
            })
            .collect();
        let mut on_facet: Vec<Vec<u32>> = vec![Vec::new(); self.facets.len()];
        for (v, cv) in self.verts.iter().enumerate() {
            for &f in &cv.on {
                on_facet[f as usize].push(v as u32);
            }
        }
        (den, pts, on_facet)
    }
}

impl Cell {
    /// The vertices `ids` of facet `f` (points `pts`, outward normal `normal`) in the
    /// order [`hull_in_plane`] gives them, read off the vertex lists instead of sorted:
    /// two vertices of a facet are neighbours on it exactly when they lie on a second
    /// common facet (the two facets meet in the edge between them; the lists are
    /// complete), so each other facet holds at most two of `ids`. One exact orientation
    /// then fixes the direction, and the cycle starts where the hull's does. `None` when
    /// the lists do not make one cycle through every vertex (the hull decides then).
    fn facet_cycle(&self, f: u32, ids: &[u32], pts: &[Vec3], normal: &Vec3) -> Option<Vec<u32>> {
        let k = ids.len();
        if k < 3 {
            return None;
        }
        // Per other facet, the (up to two) positions in `ids` on it.
        let mut on: FxHashMap<u32, [u32; 2]> = FxHashMap::default();
        let mut next = vec![[u32::MAX; 2]; k];
        for (i, &v) in ids.iter().enumerate() {
            for &g in &self.verts[v as usize].on {
                if g == f {
                    continue;
                }
                let e = on.entry(g).or_insert([u32::MAX; 2]);
                if e[0] == u32::MAX {
                    e[0] = i as u32;
                } else if e[1] == u32::MAX {
                    e[1] = i as u32;
                    let (a, b) = (e[0] as usize, i);
                    for (x, y) in [(a, b), (b, a)] {
                        let slot = next[x].iter_mut().find(|s| **s == u32::MAX)?;
                        *slot = y as u32;
                    }
                } else {
                    return None;
                }
            }
        }
        // Walk the cycle from position 0.
        let mut order = Vec::with_capacity(k);
        let (mut prev, mut cur) = (u32::MAX, 0u32);
        for _ in 0..k {
            order.push(cur as usize);
            let [a, b] = next[cur as usize];
            if a == u32::MAX || b == u32::MAX {
                return None;
            }
            let step = if a != prev { a } else { b };
            (prev, cur) = (cur, step);
        }
        if cur != 0 {
            return None;
        }
        let mut seen = vec![false; k];
        for &i in &order {
            if std::mem::replace(&mut seen[i], true) {
                return None;
            }
        }
        // Counter-clockwise in the hull's projection, then from its lexicographically
        // smallest point, then reversed when the projection is flipped.
        let (u, v, flip) = hull2d::plane_axes(normal);
        let p = |i: usize| &pts[ids[order[i]] as usize];
        let (a, b, c) = (p(0), p(1), p(2));
        let turn = (b.get(u) - a.get(u)) * (c.get(v) - a.get(v))
            - (b.get(v) - a.get(v)) * (c.get(u) - a.get(u));
        if turn == Int::ZERO {
            return None;
        }
        if turn < Int::ZERO {
            order.reverse();
        }
        let key = |i: usize| {
            let q = &pts[ids[order[i]] as usize];
            (q.get(u), q.get(v))
        };
        let start = (1..k).fold(0, |m, i| if key(i) < key(m) { i } else { m });
        order.rotate_left(start);
        if flip {
            order.reverse();
        }
        Some(order.into_iter().map(|i| ids[i]).collect())
    }
}

/// Whether the normals of the listed facets span space (a point on them all is a
/// vertex). Linear in the list: normals are primitive, so two are parallel exactly when
/// equal up to sign; given the first and one not parallel to it, the normals span space
/// exactly when some third is off their plane.
pub(crate) fn spans(facets: &[Plane], on: &[u32]) -> bool {
    let f = |i: &u32| &facets[*i as usize];
    let Some(a) = on.first().map(f) else {
        return false;
    };
    let neg = a.n.map(|v| -v);
    let Some(b) = on.iter().map(f).find(|p| p.n != a.n && p.n != neg) else {
        return false;
    };
    on.iter()
        .any(|i| normals_det_sign(a, b, f(i)) != Sign::Zero)
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::Rational;

    /// The facet cycles read off the vertex lists are the hull's, vertex for vertex,
    /// on cells cut from a box by random planes (many through its vertices, so with
    /// degenerate vertices on four or more facets) and on their merged unions.
    #[test]
    fn facet_cycles_are_the_hulls() {
        let mut g = apart_testkit::solids::Lcg(7);
        let mut checked = 0;
        for _ in 0..60 {
            let mut cells = vec![Cell::boxed([0, 0, 0], [6, 6, 6])];
            for _ in 0..6 {
                let c = cells.swap_remove(0);
                let r = |g: &mut apart_testkit::solids::Lcg| [0, 1, 2].map(|_| g.range(0, 4) * 2);
                let (a, b, d) = (r(&mut g), r(&mut g), r(&mut g));
                let Some(h) = Plane::through(&a, &b, &d) else {
                    cells.push(c);
                    continue;
                };
                let (lo, hi) = c.split(&h, true);
                cells.extend(lo);
                cells.extend(hi);
            }
            let (merged, _) = crate::merge::merge(cells.clone());
            for c in cells.iter().chain(&merged) {
                let (_, pts, on_facet) = c.integer_points();
                for (f, ids) in on_facet.iter().enumerate() {
                    let normal = Vec3::from_i128(c.facets[f].n);
                    let sub: Vec<Vec3> = ids.iter().map(|&v| pts[v as usize].clone()).collect();
                    let hull: Vec<u32> = hull_in_plane(&normal, &sub)
                        .into_iter()
                        .map(|i| ids[i])
                        .collect();
                    assert_eq!(c.facet_cycle(f as u32, ids, &pts, &normal), Some(hull));
                    checked += 1;
                }
            }
        }
        assert!(checked > 1000, "{checked}");
    }

    #[test]
    fn box_split_diagonally() {
        let c = Cell::boxed([0, 0, 0], [2, 2, 2]);
        assert_eq!(c.edges().len(), 12);
        let h = Plane::through(&[0, 0, 0], &[0, 0, 2], &[2, 2, 0]).unwrap(); // x = y
        let (a, b) = c.split(&h, true);
        let (a, b) = (a.unwrap(), b.unwrap());
        let (pa, pb) = (a.to_polytope().unwrap(), b.to_polytope().unwrap());
        assert_eq!(pa.volume(), Rational::from_int(4));
        assert_eq!(pb.volume(), Rational::from_int(4));
        // A plane creating a rational vertex (0, 0, 1/2): x + y + 2z = 1.
        let g = Plane::new([1, 1, 2], 1);
        let (lo, hi) = c.split(&g, true);
        let (lo, hi) = (
            lo.unwrap().to_polytope().unwrap(),
            hi.unwrap().to_polytope().unwrap(),
        );
        assert_eq!(lo.den(), &Int::from(2));
        assert_eq!(lo.volume(), Rational::new(Int::from(1), Int::from(12)));
        assert_eq!(&lo.volume() + &hi.volume(), Rational::from_int(8));
    }
}
