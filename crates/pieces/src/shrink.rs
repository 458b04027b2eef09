//! Shrinking a convex piece by a stated tolerance: every facet plane moved inward by at
//! least `eps`, exactly, and the result put back on the grid.
//!
//! The exact cut ([`Polytope::shrunk_exact`]): a facet `n · x <= c` (primitive integer
//! `n`) moves to `n · x <= c - eps · r` where `r = ⌈256 |n|⌉ / 256 >= |n|` is a rational
//! upper bound of the normal's length, so each plane moves by at least `eps` and by at
//! most `eps (1 + 1 / (256 |n|))`. The result is contained in the erosion of the piece by
//! a ball of radius `eps`, which is what makes a tolerance conservative: two pieces whose
//! interiors overlap by a depth below `2 eps` no longer overlap once both are shrunk.
//! It is the intersection of the moved half-spaces, computed by clipping the original
//! piece by one moved plane after the other. Vertices are homogeneous integer points
//! (`y / w`) carrying the complete list of planes through them; a vertex created on an
//! edge is the exact combination of the edge's end points that lies on the clipping
//! plane. Nothing is rounded there.
//!
//! What the planners get ([`Polytope::shrunk`]) is that cut made one grid step deeper,
//! with each vertex rounded to the nearest grid point and the convex hull taken: still
//! at least `eps` inside every face, with integers as short as the input's. Since the
//! vertices are rounded anyway, that cut is first made in floating point (each face
//! polygon clipped on its own, in an order of the exact coordinates, so that the same
//! solid stored another way rounds the same); the rounded hull is kept only when an
//! exact test puts every vertex at least `eps` inside every facet, else the exact cut is
//! made (also whenever the float cut comes out empty).
//! Either way the result holds the exact cut by `eps` plus two steps: a hull of points
//! each less than a step from a convex set's vertices holds that set eroded by a step.

use crate::hull2d::hull_in_plane;
use crate::polytope::Polytope;
use apart_kernel::fvec;
use apart_kernel::int::{self, Int};
use apart_kernel::{BigPlane, HPoint, Sign, Vec3};
use rustc_hash::FxHashMap as HashMap;

/// A vertex of a polytope being cut (the kernel's reduced homogeneous point `y / w`,
/// `w > 0`, on the piece's stored integers), and the sorted indices of the half-spaces
/// whose plane passes through it.
#[derive(Clone)]
struct Vertex {
    p: HPoint,
    on: Vec<u32>,
}

/// The side of the half-space `h` (`n · y <= c` on the piece's stored integers `y`)
/// that `p` is on: the sign of `n · (y / w) - c` (as `w > 0`), and the value
/// `n · y - c w` (positive outside).
fn side(p: &HPoint, h: &BigPlane) -> (Sign, Int) {
    let s = h.value(p);
    (int::sign_of(&s), s)
}

/// The point on the plane between `inner` (value `vi < 0`) and `outer` (`vo > 0`).
fn between(inner: &HPoint, outer: &HPoint, vi: &Int, vo: &Int) -> HPoint {
    // vo * inner - vi * outer lies on the plane; its weight is positive because
    // vo > 0 > vi and both weights are positive.
    let (iy, oy) = (inner.num(), outer.num());
    let y = [0, 1, 2].map(|k| vo * &iy[k] - vi * &oy[k]);
    let w = vo * inner.den() - vi * outer.den();
    HPoint::from_big(y, w)
}

/// Pieces of at most this many facets are cut plane by plane when the float cut fails;
/// bigger ones are scaled.
const EXACT_CUT_FACETS: usize = 32;

/// Pieces of at most this many facets try the float cut first (its cost grows with the
/// square of the facets). Scaling moves the faces far from the inner point by up to
/// their distance over the nearest face's times `eps`: 56 times `eps` on a gear's hub
/// pieces of 33 to 128 facets, which the float cut brings to `eps` plus a step.
const FLOAT_CUT_FACETS: usize = 128;

/// How close to a plane (grid steps) a vertex of the float cut counts as on it.
const FLOAT_ON: f64 = 1e-4;

/// The edges of the current polytope: pairs of vertices sharing two planes.
fn edges(verts: &[Vertex]) -> Vec<(u32, u32)> {
    let mut by_pair: HashMap<(u32, u32), Vec<u32>> = HashMap::default();
    for (i, v) in verts.iter().enumerate() {
        for a in 0..v.on.len() {
            for b in a + 1..v.on.len() {
                by_pair
                    .entry((v.on[a], v.on[b]))
                    .or_default()
                    .push(i as u32);
            }
        }
    }
    let mut out: Vec<(u32, u32)> = by_pair
        .into_values()
        .filter(|vs| vs.len() == 2)
        .map(|vs| (vs[0].min(vs[1]), vs[0].max(vs[1])))
        .collect();
    out.sort_unstable();
    out.dedup();
    out
}

/// Clips `verts` by half-space number `hi`. `None` when nothing of positive volume is
/// left on the inner side.
fn clip(verts: Vec<Vertex>, h: &BigPlane, hi: u32) -> Option<Vec<Vertex>> {
    let sides: Vec<(Sign, Int)> = verts.iter().map(|v| side(&v.p, h)).collect();
    if sides.iter().all(|(s, _)| *s != Sign::Positive) {
        // Nothing cut; vertices on the plane learn it.
        return Some(
            verts
                .into_iter()
                .zip(&sides)
                .map(|(mut v, (s, _))| {
                    if *s == Sign::Zero {
                        v.on.push(hi);
                    }
                    v
                })
                .collect(),
        );
    }
    if sides.iter().all(|(s, _)| *s != Sign::Negative) {
        return None;
    }
    let mut out: Vec<Vertex> = Vec::with_capacity(verts.len() + 8);
    for (e0, e1) in edges(&verts) {
        let (a, b) = (&verts[e0 as usize], &verts[e1 as usize]);
        let ((sa, va), (sb, vb)) = (&sides[e0 as usize], &sides[e1 as usize]);
        let (inner, outer, vi, vo) = match (sa, sb) {
            (Sign::Negative, Sign::Positive) => (a, b, va, vb),
            (Sign::Positive, Sign::Negative) => (b, a, vb, va),
            _ => continue,
        };
        let p = between(&inner.p, &outer.p, vi, vo);
        let mut on: Vec<u32> = inner
            .on
            .iter()
            .filter(|p| outer.on.contains(p))
            .copied()
            .collect();
        on.push(hi);
        out.push(Vertex { p, on });
    }
    for (mut v, (s, _)) in verts.into_iter().zip(&sides) {
        match s {
            Sign::Negative => out.push(v),
            Sign::Zero => {
                v.on.push(hi);
                out.push(v);
            }
            Sign::Positive => {}
        }
    }
    for v in &mut out {
        v.on.sort_unstable();
        v.on.dedup();
    }
    Some(out)
}

/// The faces of a convex polytope (convex polygons) cut by each half-space `u · x <= c`
/// in turn, in floating point: each face is clipped on its own (Sutherland–Hodgman) and
/// the points on the cutting plane, ordered around their centre, make the new face. No
/// vertex-to-plane incidences are kept, so near-parallel planes cannot make the cut
/// lose a vertex; only positions carry rounding errors. `None` when nothing is left.
fn cut_faces(
    mut faces: Vec<Vec<[f64; 3]>>,
    halves: &[([f64; 3], f64)],
) -> Option<Vec<Vec<[f64; 3]>>> {
    for (u, c) in halves {
        let value = |x: &[f64; 3]| fvec::dot(*u, *x) - c;
        if faces.iter().flatten().all(|x| value(x) <= FLOAT_ON) {
            continue;
        }
        let mut cap: Vec<[f64; 3]> = Vec::new();
        let mut out: Vec<Vec<[f64; 3]>> = Vec::with_capacity(faces.len() + 1);
        for face in &faces {
            let mut kept = Vec::with_capacity(face.len() + 2);
            for (i, x) in face.iter().enumerate() {
                let y = &face[(i + 1) % face.len()];
                let (vx, vy) = (value(x), value(y));
                if vx <= 0.0 {
                    kept.push(*x);
                    if vx >= -FLOAT_ON {
                        cap.push(*x);
                    }
                }
                if (vx < 0.0 && vy > 0.0) || (vx > 0.0 && vy < 0.0) {
                    let z = fvec::lerp(*x, *y, vx / (vx - vy));
                    kept.push(z);
                    cap.push(z);
                }
            }
            if kept.len() >= 3 {
                out.push(kept);
            }
        }
        if out.is_empty() {
            return None;
        }
        if cap.len() >= 3 {
            // Around the centre, by angle in a basis of the plane.
            let n = cap.len() as f64;
            let g = cap
                .iter()
                .fold([0.0; 3], |s, x| fvec::add(s, *x))
                .map(|s| s / n);
            let k = (0..3)
                .min_by(|&i, &j| u[i].abs().total_cmp(&u[j].abs()))
                .unwrap_or(0);
            let mut axis = [0.0; 3];
            axis[k] = 1.0;
            let e1 = fvec::cross(*u, axis);
            let e2 = fvec::cross(*u, e1);
            let angle = |x: &[f64; 3]| {
                let d = fvec::sub(*x, g);
                fvec::dot(d, e2).atan2(fvec::dot(d, e1))
            };
            let mut around: Vec<(f64, [f64; 3])> = cap.iter().map(|x| (angle(x), *x)).collect();
            around.sort_by(|a, b| a.0.total_cmp(&b.0));
            out.push(around.into_iter().map(|(_, x)| x).collect());
        }
        faces = out;
    }
    Some(faces)
}

/// How far the farthest facet plane of `original` moved inward in `shrunk` (true
/// coordinates), measured in floating point: a report of how much smaller than the
/// stated tolerance a scaled piece became, never a decision.
pub fn max_face_shift(original: &Polytope, shrunk: &Polytope) -> f64 {
    if let (Some(o), Some(s)) = (original.shadow(), shrunk.shadow()) {
        return o
            .facet_units
            .iter()
            .zip(&o.facet_levels)
            .map(|(u, h)| {
                let top = s
                    .points
                    .iter()
                    .map(|p| fvec::dot(*p, *u))
                    .fold(f64::NEG_INFINITY, f64::max);
                h - top
            })
            .fold(0.0, f64::max);
    }
    let pts: Vec<[f64; 3]> = shrunk
        .vertices()
        .iter()
        .map(|v| {
            [0, 1, 2].map(|k| apart_kernel::Rational::new(v.get(k), shrunk.den().clone()).to_f64())
        })
        .collect();
    original
        .facets()
        .iter()
        .map(|f| {
            let n = f.normal.approx();
            let len = fvec::norm(n);
            let h = apart_kernel::Rational::new(f.offset.clone(), original.den().clone()).to_f64();
            let top = pts
                .iter()
                .map(|p| fvec::dot(*p, n))
                .fold(f64::NEG_INFINITY, f64::max);
            (h - top) / len
        })
        .fold(0.0, f64::max)
}

/// A point near the centre of the largest inscribed ball of `p` (true coordinates, in
/// floating point, never trusted): a damped Newton method on the log barrier of the
/// facets, started at the vertex centroid.
fn inner_centre(p: &Polytope) -> [f64; 3] {
    // The vertices and each facet's unit normal `u` and level `h` (`u · x <= h`).
    type Facets = Vec<([f64; 3], f64)>;
    let (verts, units): (Vec<[f64; 3]>, Facets) = match p.shadow() {
        Some(s) => (
            s.points.clone(),
            s.facet_units
                .iter()
                .copied()
                .zip(s.facet_levels.iter().copied())
                .collect(),
        ),
        None => {
            let to_f = |v: &Vec3| {
                [0, 1, 2].map(|k| apart_kernel::Rational::new(v.get(k), p.den().clone()).to_f64())
            };
            let verts: Vec<[f64; 3]> = p.vertices().iter().map(to_f).collect();
            let units = p
                .facets()
                .iter()
                .map(|f| {
                    let a = f.normal.approx();
                    let len = fvec::norm(a);
                    let u = a.map(|x| x / len);
                    // u · x <= h for the points x of the facet's plane.
                    let v = &verts[f.cycle[0] as usize];
                    (u, fvec::dot(u, *v))
                })
                .collect();
            (verts, units)
        }
    };
    let n = verts.len() as f64;
    let mut c = [0.0; 3];
    for v in &verts {
        for k in 0..3 {
            c[k] += v[k] / n;
        }
    }
    // The analytic centre of the facet inequalities (damped Newton on the log barrier
    // from the vertex centroid, which lies inside): well away from every facet, also in
    // long thin pieces where the centroid may sit close to a side.
    let slack =
        |c: &[f64; 3]| -> Vec<f64> { units.iter().map(|(u, h)| h - fvec::dot(*u, *c)).collect() };
    let mut best = c;
    if slack(&c).iter().all(|&x| x > 0.0) {
        for _ in 0..50 {
            let sl = slack(&c);
            let mut g = [0.0; 3];
            let mut hm = [[0.0; 3]; 3];
            for ((u, _), s) in units.iter().zip(&sl) {
                for a in 0..3 {
                    g[a] += u[a] / s;
                    for b in 0..3 {
                        hm[a][b] += u[a] * u[b] / (s * s);
                    }
                }
            }
            let Some(step) = solve3(&hm, &g) else { break };
            let mut t = 1.0;
            let mut moved = false;
            for _ in 0..30 {
                let next = [0, 1, 2].map(|k| c[k] - t * step[k]);
                if slack(&next).iter().all(|&x| x > 0.0) {
                    c = next;
                    moved = true;
                    break;
                }
                t *= 0.5;
            }
            if !moved {
                break;
            }
        }
        best = c;
    }
    best
}

/// `centre` on the grid of spacing `1 / (den l)` as the integer vector `gamma`, checked
/// strictly inside exactly; the rounded vertex centroid when that fails.
fn inner_point(p: &Polytope, centre: &[f64; 3], l: &Int) -> Option<Vec3> {
    let scale = int::to_f64(p.den()) * int::to_f64(l);
    let inside = |g: &Vec3| {
        p.facets()
            .iter()
            .all(|f| l * &f.offset - f.normal.dot(g) > Int::ZERO)
    };
    let round = |c: &[f64; 3]| -> Option<Vec3> {
        let g = c.map(|x| (x * scale).round());
        if g.iter().all(|x| x.is_finite() && x.abs() < 9.0e15) {
            Some(Vec3::new(g[0] as i64, g[1] as i64, g[2] as i64))
        } else {
            None
        }
    };
    if let Some(g) = round(centre).filter(inside) {
        return Some(g);
    }
    // The exact vertex centroid, scaled to den l: (l / V) sum y, rounded down.
    let mut sum = Vec3::new(0, 0, 0);
    for v in p.vertices() {
        sum = sum.add(v);
    }
    let nv = Int::from(p.vertices().len());
    let g = Vec3::from_ints(sum.to_ints().map(|x| x * l / &nv));
    inside(&g).then_some(g)
}

/// The solution of the 3×3 system `m x = b` by Cramer's rule (`None` when singular).
fn solve3(m: &[[f64; 3]; 3], b: &[f64; 3]) -> Option<[f64; 3]> {
    let det = |m: &[[f64; 3]; 3]| {
        m[0][0] * (m[1][1] * m[2][2] - m[1][2] * m[2][1])
            - m[0][1] * (m[1][0] * m[2][2] - m[1][2] * m[2][0])
            + m[0][2] * (m[1][0] * m[2][1] - m[1][1] * m[2][0])
    };
    let d = det(m);
    if !d.is_normal() {
        return None;
    }
    Some([0, 1, 2].map(|k| {
        let mut mk = *m;
        for r in 0..3 {
            mk[r][k] = b[r];
        }
        det(&mk) / d
    }))
}

/// `⌈256 |n|⌉`: 256 times the rational upper bound of a normal's length.
fn length_bound_256(n: &Vec3) -> Int {
    int::ceil_sqrt(&(n.dot(n) * Int::from(65536)))
}

impl Polytope {
    /// The piece made `eps` smaller: every facet plane moved inward by at least `eps`
    /// (true coordinates; `eps > 0` given as the fraction `eps_num / eps_den` of the grid
    /// step), with its vertices on the grid again. `None` when nothing of positive volume
    /// is left.
    ///
    /// The piece is cut by `eps` plus one grid step. When it has at most 128 facets, the
    /// cut is made in floating point first and kept when an exact test confirms it;
    /// else, up to 32 facets, exactly ([`Polytope::shrunk_exact`]), and a bigger piece
    /// (each plane's exact cut costs a pass over all its vertices) is scaled about an
    /// inner point ([`Polytope::shrunk_by_scaling`], which moves some faces more). Each vertex of the
    /// cut is then rounded to the nearest grid point, and the result is the convex hull
    /// of those points ([`Polytope::hull`]). A rounded point lies less than one step from
    /// the cut, so every face still lies at least `eps` inside the piece's, and the
    /// shrunk pieces keep integers as short as the input's: the cut alone has rationals
    /// of hundreds of bits on tessellated curved pieces, which every later sum,
    /// projection and arrangement paid for.
    pub fn shrunk(&self, eps_num: &Int, eps_den: &Int) -> Option<Polytope> {
        let margin = eps_num + eps_den; // eps + 1 step
        if self.facets().len() <= FLOAT_CUT_FACETS {
            if let Some(p) = self.shrunk_in_floats(&margin, eps_num, eps_den) {
                return Some(p);
            }
        }
        let cut = if self.facets().len() <= EXACT_CUT_FACETS {
            self.shrunk_exact(&margin, eps_den)?
        } else {
            self.shrunk_by_scaling(&margin, eps_den)?
        };
        if *cut.den() == Int::ONE {
            return Some(cut);
        }
        cut.rounded_to_grid()
    }

    /// [`Polytope::shrunk`]'s fast path: the cut by `margin` (grid steps, as a fraction
    /// over `eps_den`) computed in floating point, each vertex rounded to the nearest
    /// grid point, and the exact hull of those points, returned only when every one of
    /// them lies at least `eps` inside every facet of the piece, checked exactly (the
    /// bound [`Polytope::shrunk_exact`] guarantees). `None` when the check fails, the
    /// float cut leaves nothing or the rounded points span no volume (float
    /// combinatorics can lose vertices where facets are nearly parallel, so emptiness is
    /// never decided here), or a coordinate does not fit: then the exact cut decides.
    fn shrunk_in_floats(&self, margin: &Int, eps_num: &Int, eps_den: &Int) -> Option<Polytope> {
        let den = self.den();
        let m = int::to_f64(margin) / int::to_f64(eps_den);
        let nf = self.facets().len() as u32;
        // True coordinates, each rounded once from its exact value, and the vertices and
        // facets taken in an order of those values: the same solid stored with another
        // denominator, or listed in another order, is cut by the same float operations
        // and rounds to the same grid points.
        let small_den = (int::bit_len(den) <= 53).then(|| int::to_f64(den));
        let coordinate = |c: i64| match small_den {
            Some(d) if c.unsigned_abs() <= 1 << 53 => c as f64 / d,
            _ => int::ratio_to_f64(&Int::from(c), den),
        };
        let points: Vec<[f64; 3]> = self
            .vertices()
            .iter()
            .map(|v| match v.as_small() {
                Some(c) => c.map(coordinate),
                None => [0, 1, 2].map(|k| int::ratio_to_f64(&v.get(k), den)),
            })
            .collect();
        if !points.iter().flatten().all(|c| c.is_finite()) {
            return None;
        }
        // Vertices by their rounded coordinates, ties by their exact ones.
        let vertex_order = |a: u32, b: u32| {
            let (va, vb) = (&self.vertices()[a as usize], &self.vertices()[b as usize]);
            fvec::lex_cmp(points[a as usize], points[b as usize]).then_with(|| {
                (0..3)
                    .map(|k| va.get(k).cmp(&vb.get(k)))
                    .find(|o| o.is_ne())
                    .unwrap_or(std::cmp::Ordering::Equal)
            })
        };
        let units: Vec<[f64; 3]> = self.facets().iter().map(|f| f.normal.unit_f64()).collect();
        if !units
            .iter()
            .all(|u| u.iter().all(|c| c.is_finite()) && *u != [0.0; 3])
        {
            return None;
        }
        let mut forder: Vec<u32> = (0..nf).collect();
        forder.sort_by(|&a, &b| fvec::lex_cmp(units[a as usize], units[b as usize]));
        let bounds: Vec<Int> = self
            .facets()
            .iter()
            .map(|f| length_bound_256(&f.normal))
            .collect();
        let halves: Vec<([f64; 3], f64)> = forder
            .iter()
            .map(|&k| {
                let (f, r) = (&self.facets()[k as usize], &bounds[k as usize]);
                // Moved by margin r / |n| (1 up to 1 / (256 |n|)).
                let n = int::to_f64(&f.normal.dot(&f.normal)).sqrt();
                let stretch = int::to_f64(r) / 256.0 / n;
                let stretch = if stretch.is_finite() { stretch } else { 1.0 };
                let level = int::ratio_to_f64(&f.offset, den) / n;
                (units[k as usize], level - m * stretch)
            })
            .collect();
        // Each facet's polygon in the facets' order, from its least vertex.
        let faces: Vec<Vec<[f64; 3]>> = forder
            .iter()
            .map(|&f| {
                let cycle = &self.facets()[f as usize].cycle;
                let first = (0..cycle.len())
                    .min_by(|&i, &j| vertex_order(cycle[i], cycle[j]))
                    .unwrap_or(0);
                (0..cycle.len())
                    .map(|i| points[cycle[(first + i) % cycle.len()] as usize])
                    .collect()
            })
            .collect();
        // An empty float cut is not trusted (the exact cut decides).
        let faces = cut_faces(faces, &halves)?;
        const LIMIT: f64 = (1u64 << 52) as f64;
        let points: Vec<Vec3> = faces
            .iter()
            .flatten()
            .map(|v| {
                let r = v.map(f64::round);
                r.iter()
                    .all(|x| x.abs() < LIMIT)
                    .then(|| Vec3::new(r[0] as i64, r[1] as i64, r[2] as i64))
            })
            .collect::<Option<_>>()?;
        let hull = Polytope::hull(&points).ok()?;
        if hull.volume6() <= Int::ZERO {
            return None;
        }
        // Every hull vertex v (true coordinates, integers) at least eps inside every
        // facet n · x <= c / den: 256 eps_den (c - den n · v) >= eps_num den ⌈256 |n|⌉.
        let scale = Int::from(256) * eps_den;
        let inside = self.facets().iter().zip(&bounds).all(|(f, r)| {
            let need = eps_num * den * r;
            hull.vertices()
                .iter()
                .all(|v| &scale * (&f.offset - den * f.normal.dot(v)) >= need)
        });
        inside.then_some(hull)
    }

    /// The convex hull of this polytope's vertices, each rounded to the nearest point of
    /// the grid itself (denominator 1). `None` when the hull is flat.
    fn rounded_to_grid(&self) -> Option<Polytope> {
        let from = self.den();
        let two = Int::from(2);
        let round = |y: Int| -> Int {
            // round(y / from) = floor((2 y + from) / (2 from)), exactly.
            let n = &two * y + from;
            let d = &two * from;
            let q = &n / &d;
            if &q * &d > n {
                q - Int::ONE
            } else {
                q
            }
        };
        let points: Vec<Vec3> = self
            .vertices()
            .iter()
            .map(|v| Vec3::from_ints(v.to_ints().map(&round)))
            .collect();
        let hull = Polytope::hull(&points).ok()?;
        (hull.volume6() > Int::ZERO).then_some(hull)
    }

    /// The piece scaled about an inner point `c` by the largest dyadic factor `1 - t`
    /// that still moves every facet plane inward by at least `eps`: facet `f` moves by
    /// `t` times its distance from `c`, so `t >= eps r_f / (o_f - n_f · c)` for every
    /// `f`, with `r_f = ⌈256 |n_f|⌉ / 256`. `c` is a dyadic point near the centre of the
    /// largest inscribed ball (found in floating point; only its membership is used, and
    /// that is checked exactly; on the piece's own grid unless that costs more than 1/64
    /// of the shrink, else 16 bits finer), and `t` is rounded up to 8 significant bits,
    /// so the vertices keep the short denominator `den · 2^j` (or `den · 2^(16 + j)`). Facets, normals and the
    /// combinatorics are those of the piece. `None` when `t >= 1` (nothing is left).
    pub fn shrunk_by_scaling(&self, eps_num: &Int, eps_den: &Int) -> Option<Polytope> {
        // The centre on the piece's own grid (l = 1) keeps the vertices' numbers short,
        // which makes every later sum, projection and arrangement cheaper; it is used
        // unless rounding to that grid costs more than 1/64 of the shrink factor (thin
        // pieces), in which case the centre gets 16 more bits.
        let den = self.den();
        let centre = inner_centre(self);
        let fine = Int::ONE << 16usize;
        let coarse = Int::ONE;
        let at = |l: &Int| -> Option<(Vec3, Int, Int)> {
            let gamma = inner_point(self, &centre, l)?;
            let (t_num, t_den) = self.scaling_factor(&gamma, l, eps_num, eps_den)?;
            Some((gamma, t_num, t_den))
        };
        let pick = match (at(&coarse), at(&fine)) {
            (Some(c), Some(f)) if &c.1 * &f.2 * Int::from(64) <= &f.1 * &c.2 * Int::from(65) => {
                Some((c, coarse))
            }
            (_, Some(f)) => Some((f, fine)),
            (Some(c), None) => Some((c, coarse)),
            (None, None) => None,
        };
        let ((gamma, t_num, t_den), l) = pick?;
        if t_num >= t_den {
            return None;
        }
        // t' = m / 2^j >= t with about 8 significant bits: t' exceeds t by at most 1/128
        // of t, and the vertices' denominator stays short.
        let shift = (int::bit_len(&t_den) as i64 - int::bit_len(&t_num) as i64 + 8).max(1) as usize;
        let scaled = &t_num << shift;
        let mut m = &scaled / &t_den;
        if &m * &t_den < scaled {
            m += Int::ONE;
        }
        let two_j = Int::ONE << shift;
        if m >= two_j {
            return None;
        }
        // Stored vertices at den' = den L 2^j: m gamma + (2^j - m) L y.
        let keep = (&two_j - &m) * &l;
        let g = gamma.scale(&m);
        let points: Vec<Vec3> = self
            .vertices()
            .iter()
            .map(|y| y.scale(&keep).add(&g))
            .collect();
        let facets = self
            .facets()
            .iter()
            .map(|f| (f.normal.clone(), f.cycle.clone()))
            .collect();
        let p = Polytope::from_facets(&points, facets).ok()?;
        Some(p.with_den(den * &l * &two_j))
    }

    /// The smallest `t = t_num / t_den` that moves every facet plane inward by at least
    /// `eps` when the piece is scaled by `1 - t` about `gamma / (den l)`:
    /// `t = max_f eps den r_f l / (l o_f - n_f · gamma)`. `None` when `gamma` is not
    /// strictly inside.
    fn scaling_factor(
        &self,
        gamma: &Vec3,
        l: &Int,
        eps_num: &Int,
        eps_den: &Int,
    ) -> Option<(Int, Int)> {
        let den = self.den();
        let mut t_num = Int::ZERO;
        let mut t_den = Int::ONE;
        for f in self.facets() {
            let room = l * &f.offset - f.normal.dot(gamma);
            if room <= Int::ZERO {
                return None;
            }
            let num = eps_num * den * length_bound_256(&f.normal) * l;
            let dn = Int::from(256) * eps_den * room;
            if &num * &t_den > &t_num * &dn {
                t_num = num;
                t_den = dn;
            }
        }
        Some((t_num, t_den))
    }

    /// The exact intersection of the facet half-spaces moved inward by
    /// `eps · ⌈256 |n|⌉ / 256` (see the module documentation). `None` when nothing of
    /// positive volume is left (a piece thinner than `2 eps`).
    pub fn shrunk_exact(&self, eps_num: &Int, eps_den: &Int) -> Option<Polytope> {
        assert!(
            *eps_num > Int::ZERO && *eps_den > Int::ZERO,
            "tolerance must be positive"
        );
        // Half-spaces on stored integers y = den x: n · y <= offset becomes
        // 256 eps_den n · y <= 256 eps_den offset - eps_num den ⌈256 |n|⌉.
        let den = self.den();
        let scale = Int::from(256) * eps_den;
        let mut halves: Vec<BigPlane> = self
            .facets()
            .iter()
            .map(|f| {
                BigPlane::new(
                    f.normal.scale(&scale).to_ints(),
                    &f.offset * &scale - eps_num * den * length_bound_256(&f.normal),
                )
            })
            .collect();
        let nf = halves.len() as u32;
        // Start from the piece itself, its planes numbered after the moved ones.
        let mut on_of: Vec<Vec<u32>> = vec![Vec::new(); self.vertices().len()];
        for (f, facet) in self.facets().iter().enumerate() {
            for &v in &facet.cycle {
                on_of[v as usize].push(nf + f as u32);
            }
        }
        let mut verts: Vec<Vertex> = self
            .vertices()
            .iter()
            .zip(on_of)
            .map(|(v, on)| Vertex {
                p: HPoint::from_big(v.to_ints(), Int::ONE),
                on,
            })
            .collect();
        for f in self.facets() {
            halves.push(BigPlane::new(f.normal.to_ints(), f.offset.clone()));
        }
        for hi in 0..nf {
            verts = clip(verts, &halves[hi as usize], hi)?;
        }
        // Common denominator: stored integers of the result are W y / w with W = lcm w,
        // and the result's denominator is den W.
        let mut lcm = Int::ONE;
        for v in &verts {
            let g = int::gcd(&lcm, v.p.den());
            lcm = &lcm / &g * v.p.den();
        }
        let points: Vec<Vec3> = verts
            .iter()
            .map(|v| {
                let (y, k) = (v.p.num(), &lcm / v.p.den());
                Vec3::from_ints([&y[0] * &k, &y[1] * &k, &y[2] * &k])
            })
            .collect();
        let mut facets = Vec::new();
        for hi in 0..nf {
            let on: Vec<u32> = (0..verts.len() as u32)
                .filter(|&v| verts[v as usize].on.contains(&hi))
                .collect();
            if on.len() < 3 {
                continue;
            }
            let normal = self.facets()[hi as usize].normal.clone();
            let sub: Vec<Vec3> = on.iter().map(|&v| points[v as usize].clone()).collect();
            let hull = hull_in_plane(&normal, &sub);
            if hull.len() >= 3 {
                facets.push((normal, hull.into_iter().map(|i| on[i]).collect()));
            }
        }
        let p = Polytope::from_facets(&points, facets).ok()?;
        if p.volume6() <= Int::ZERO {
            return None;
        }
        Some(p.with_den(den * &lcm))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use apart_kernel::Rational;

    fn cube(lo: i64, hi: i64) -> Polytope {
        Polytope::cuboid([lo; 3], [hi; 3]).unwrap()
    }

    #[test]
    fn axis_cube_shrinks_by_exactly_eps() {
        // Axis normals have |n| = 1 exactly, so the bound is tight.
        let c = cube(0, 10);
        let s = c.shrunk_exact(&Int::from(1), &Int::from(2)).unwrap();
        assert_eq!(s.facets().len(), 6);
        assert_eq!(s.vertices().len(), 8);
        // Side 9: volume 729.
        assert_eq!(s.volume(), Rational::from_int(Int::from(729)));
        // Too thin: nothing left.
        assert!(c.shrunk_exact(&Int::from(5), &Int::ONE).is_none());
        assert!(c.shrunk_exact(&Int::from(6), &Int::ONE).is_none());
        assert!(c.shrunk(&Int::from(5), &Int::ONE).is_none());
    }

    #[test]
    fn shrunk_tetrahedron_lies_eps_inside_and_loses_at_most_the_bound() {
        let pts = [[0, 0, 0], [12, 0, 0], [0, 12, 0], [0, 0, 12]].map(Vec3::from_i64);
        let t = Polytope::hull_of_points(&pts).unwrap();
        let s = t.shrunk_exact(&Int::ONE, &Int::ONE).unwrap();
        assert_eq!(s.vertices().len(), 4);
        // Every vertex of the shrunk piece is at distance >= 1 from every original
        // facet plane: (c - n·x)^2 >= |n|^2, exactly, with x = y / den.
        for v in s.vertices() {
            for f in t.facets() {
                let gap = &f.offset * s.den() - f.normal.dot(v); // den * (c - n·x)
                assert!(gap > Int::ZERO);
                assert!(&gap * &gap >= f.normal.dot(&f.normal) * s.den() * s.den());
            }
        }
        // And not much more: the slanted plane (1,1,1) moves by ⌈256√3⌉/256 ≈ 1.7344,
        // not more than 1 + 1/(256·√3) of eps.
        let slanted = t
            .facets()
            .iter()
            .position(|f| f.normal == Vec3::new(1, 1, 1))
            .unwrap();
        let f = &t.facets()[slanted];
        let moved = s.support(&f.normal).0; // den' · max n·x
        let shift = Rational::new(&f.offset * s.den() - moved, s.den().clone());
        let bound = Rational::new(Int::from(444), Int::from(256)); // ⌈256√3⌉ = 444
        assert_eq!(shift, bound);
    }

    #[test]
    fn shrinking_can_remove_a_facet() {
        // The box [0, 10]^3 with one vertical edge bevelled by the plane x + y = 19.
        // Every plane moves inward, and the bevel, being slanted, moves by less in
        // x and y than the box planes do: it is cut off by its neighbours and vanishes.
        let mut pts = Vec::new();
        for x in [0, 10] {
            for y in [0, 10] {
                for z in [0, 10] {
                    if x == 10 && y == 10 {
                        pts.push(Vec3::new(10, 9, z));
                        pts.push(Vec3::new(9, 10, z));
                    } else {
                        pts.push(Vec3::new(x, y, z));
                    }
                }
            }
        }
        let p = Polytope::hull_of_points(&pts).unwrap();
        assert_eq!(p.facets().len(), 7);
        let s = p.shrunk_exact(&Int::from(2), &Int::ONE).unwrap();
        // The bevel x + y <= 19 moves to x + y <= 19 - 2·⌈256√2⌉/256 ≈ 16.17, while the
        // box planes go to 8: x + y <= 16 holds at the corner (8, 8): the bevel is gone.
        assert_eq!(s.facets().len(), 6);
        assert_eq!(s.volume(), Rational::from_int(Int::from(6 * 6 * 6)));
    }

    #[test]
    fn scaling_moves_every_face_by_at_least_eps() {
        // A long slanted prism, scaled: every face plane moves inward by at least eps
        // (exactly checked on the support function), the long ends by more.
        let pts: Vec<Vec3> = [
            [0, 0, 0],
            [40, 3, 0],
            [1, 20, 0],
            [0, 0, 200],
            [40, 3, 200],
            [1, 20, 200],
        ]
        .map(Vec3::from_i64)
        .to_vec();
        let p = Polytope::hull_of_points(&pts).unwrap();
        let (num, den) = (Int::ONE, Int::from(3)); // eps = 1/3
        let s = p.shrunk_by_scaling(&num, &den).unwrap();
        assert_eq!(s.facets().len(), p.facets().len());
        for f in p.facets() {
            // Shift in true units: (offset - h_s(n) / den_s) / |n| >= eps, i.e.
            // (offset den_s - h_s)^2 >= (eps den_s)^2 |n|^2 with offset - h_s/den_s > 0.
            let h = s.support(&f.normal).0;
            let gap = &f.offset * s.den() - h;
            assert!(gap > Int::ZERO);
            let lhs = &gap * &gap * &den * &den;
            let rhs = f.normal.dot(&f.normal) * s.den() * s.den() * &num * &num;
            assert!(lhs >= rhs);
        }
        assert!(s.volume() < p.volume());
        // The denominator stays a power of two (times the piece's, 1 here).
        let d = s.den().clone();
        assert_eq!(&d & &(&d - Int::ONE), Int::ZERO);
        // The dispatcher prefers the exact shrink for this few-faced piece when its
        // denominator stays small, and otherwise scales; either way every face moves.
        assert!(p.shrunk(&num, &den).is_some());
        // Too much: nothing left.
        assert!(p.shrunk_by_scaling(&Int::from(50), &Int::ONE).is_none());
    }

    #[test]
    fn rational_pieces_shrink_too() {
        // A piece with denominator 3: the cube [0, 10/3]^3 stored as [0, 10]^3 / 3.
        let c = cube(0, 10).with_den(Int::from(3));
        let s = c.shrunk_exact(&Int::ONE, &Int::from(3)).unwrap(); // eps = 1/3
                                                                   // Side 10/3 - 2/3 = 8/3.
        let side = Rational::new(Int::from(8), Int::from(3));
        assert_eq!(s.volume(), &(&side * &side) * &side);
        // Back on the grid: cut by 1/3 + 1 to [4/3, 2], rounded to [1, 2].
        let g = c.shrunk(&Int::ONE, &Int::from(3)).unwrap();
        assert_eq!(g.den(), &Int::ONE);
        assert_eq!(g.volume(), Rational::from_int(Int::ONE));
    }

    #[test]
    fn shrunk_pieces_are_back_on_the_grid() {
        // The cube [0, 10]^3 and eps = 1/2: cut by 3/2 to [3/2, 17/2], rounded to the
        // nearest grid points [2, 9] (halves round up): every face moved by at least
        // eps (2 and 1) and by at most eps + 3/2.
        let c = cube(0, 10);
        let s = c.shrunk(&Int::ONE, &Int::from(2)).unwrap();
        assert_eq!(s.den(), &Int::ONE);
        assert_eq!(s.volume(), Rational::from_int(Int::from(7 * 7 * 7)));
        // A tessellated wedge (slanted faces, whose exact cut has long rationals): the
        // result has integer vertices and lies at least eps inside every face.
        let pts: Vec<Vec3> = [
            [0, 0, 0],
            [4000, 37, 0],
            [3990, 311, 0],
            [0, 0, 900],
            [4000, 37, 900],
            [3990, 311, 900],
        ]
        .map(Vec3::from_i64)
        .to_vec();
        let w = Polytope::hull_of_points(&pts).unwrap();
        let (num, den) = (Int::from(7), Int::from(3));
        let s = w.shrunk(&num, &den).unwrap();
        assert_eq!(s.den(), &Int::ONE);
        assert!(int::bit_len(w.shrunk_exact(&num, &den).unwrap().den()) > 16);
        for f in w.facets() {
            let gap = &f.offset - s.support(&f.normal).0;
            // gap / |n| >= eps: gap^2 den^2 >= num^2 |n|^2.
            assert!(gap > Int::ZERO);
            assert!(&gap * &gap * &den * &den >= f.normal.dot(&f.normal) * &num * &num);
        }
    }
}
