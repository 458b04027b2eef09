//! Exact Minkowski sums of convex polytopes.
//!
//! The facets of `P ⊕ Q` come in three kinds (the overlay of the two Gaussian maps):
//! a facet of `P` plus the face of `Q` extreme in its normal; a facet of `Q` plus the
//! face of `P` extreme in its normal; and the parallelogram `e_P + e_Q` for each pair of
//! edges whose Gaussian arcs (the normals of the planes supporting the edge) cross in
//! their relative interiors. Arcs that touch at an end point or overlap give facets of
//! the first two kinds, so only strict crossings make new facets.
//!
//! A facet plus a face is a sum of two convex polygons in one plane (the face a vertex,
//! an edge, or a facet with the same normal): its vertex cycle is the merge of the two
//! edge cycles by angle around the normal, each comparison the exact sign of a 3×3
//! determinant of primitive edge directions (behind the kernel's float filter). Nothing
//! depends on the summands' scale, so two pieces with different denominators are summed
//! as they are and only the sum's vertices are brought to the common denominator.

use crate::projection::{polygon_of_sides, silhouette_side};
use apart_kernel::bvh::{by_low_x, sweep_pairs_between};
use apart_kernel::fvec;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::spherical::{arc_position, ArcPosition};
use apart_kernel::{Aabb, Components, Int, Sign, Vec3};
use apart_pieces::hull2d::{hull_in_plane, plane_axes};
use apart_pieces::{Polytope, PolytopeError, Shadow};
use apart_sphere::polygon::PolygonError;
use apart_sphere::SphericalPolygon;
use rustc_hash::FxHashMap as HashMap;
use std::cmp::Ordering;

/// `b ⊕ (−a) = {y − x : x ∈ a, y ∈ b}`: the translations of `a` that make it meet `b`.
/// (When many sums share `a`, reflect it once and call [`minkowski_sum`].)
pub fn minkowski_difference(b: &Polytope, a: &Polytope) -> Result<Polytope, PolytopeError> {
    minkowski_sum(b, &a.reflected())
}

/// The Minkowski sum `p ⊕ q` of two convex polytopes.
pub fn minkowski_sum(p: &Polytope, q: &Polytope) -> Result<Polytope, PolytopeError> {
    sum_prepared(&Summand::new(p.clone()), &Summand::new(q.clone()))
}

/// A polytope with its Gaussian arcs and facet structure precomputed, for summing it
/// many times. Everything here is invariant under scaling the polytope.
#[derive(Clone, Debug)]
pub struct Summand {
    polytope: Polytope,
    arcs: Vec<GaussArc>,
    /// Conservative boxes of the Gaussian arcs on the unit sphere, by edge.
    boxes: Vec<Aabb<f64>>,
    /// Edge indices by the low x of their boxes (stable).
    by_low_x: Vec<u32>,
    /// Each edge's direction `ends[0] -> ends[1]`, primitive.
    dirs: Vec<Vec3>,
    /// Edge index by its end points (`min * vertices + max`).
    edge_of: HashMap<u64, u32>,
    /// Each facet's edges in cycle order: edge `t` runs from `cycle[t]` to
    /// `cycle[t + 1]`, and the flag tells whether that is `ends[0] -> ends[1]`.
    facet_edges: Vec<Vec<(u32, bool)>>,
    /// Each facet's position in its cycle of the vertex smallest in the lexicographic
    /// order of its plane's projection ([`plane_axes`]).
    lexmin: Vec<u32>,
    /// Facet index by (primitive) normal.
    by_normal: HashMap<Vec3, u32>,
    /// Each vertex as `y / w` in lowest terms (`w > 0`), made on first use, when the
    /// polytope's denominator is not 1: a piece cut out of a tessellated part stores
    /// every vertex over the least common multiple of its vertices' denominators,
    /// several times longer than each vertex's own (see [`PairPoints::direction`]).
    reduced: Option<Vec<std::sync::OnceLock<(Vec3, Int)>>>,
}

impl Summand {
    /// Prepares `polytope` for [`sum_prepared`].
    pub fn new(polytope: Polytope) -> Summand {
        let arcs = gaussian_arcs(&polytope);
        let boxes: Vec<Aabb<f64>> = arcs
            .iter()
            .map(|a| {
                apart_sphere::Arc {
                    normal: a.c.clone(),
                    start: a.m0.clone(),
                    end: a.m1.clone(),
                }
                .bbox()
            })
            .collect();
        let by_low_x = by_low_x(&boxes);
        let vs = polytope.vertices();
        let nv = vs.len() as u64;
        let key = |a: u32, b: u32| a.min(b) as u64 * nv + a.max(b) as u64;
        let dirs = polytope
            .edges()
            .iter()
            .map(|e| {
                vs[e.ends[1] as usize]
                    .sub(&vs[e.ends[0] as usize])
                    .primitive()
            })
            .collect();
        let edge_of: HashMap<u64, u32> = polytope
            .edges()
            .iter()
            .enumerate()
            .map(|(i, e)| (key(e.ends[0], e.ends[1]), i as u32))
            .collect();
        let facet_edges = polytope
            .facets()
            .iter()
            .map(|f| {
                let c = &f.cycle;
                (0..c.len())
                    .map(|t| {
                        let (a, b) = (c[t], c[(t + 1) % c.len()]);
                        let e = edge_of[&key(a, b)];
                        (e, polytope.edges()[e as usize].ends[0] == a)
                    })
                    .collect()
            })
            .collect();
        let lexmin = polytope
            .facets()
            .iter()
            .map(|f| {
                let (u, v) = {
                    let (u, v, _) = plane_axes(&f.normal);
                    (u, v)
                };
                let mut best = 0;
                for t in 1..f.cycle.len() {
                    let (a, b) = (&vs[f.cycle[t] as usize], &vs[f.cycle[best] as usize]);
                    if cmp_lex(a, b, u, v) == Ordering::Less {
                        best = t;
                    }
                }
                best as u32
            })
            .collect();
        let by_normal = polytope
            .facets()
            .iter()
            .enumerate()
            .map(|(i, f)| (f.normal.clone(), i as u32))
            .collect();
        let reduced = (*polytope.den() != Int::ONE)
            .then(|| (0..vs.len()).map(|_| std::sync::OnceLock::new()).collect());
        Summand {
            polytope,
            arcs,
            boxes,
            by_low_x,
            dirs,
            edge_of,
            facet_edges,
            lexmin,
            by_normal,
            reduced,
        }
    }

    /// The polytope.
    pub fn polytope(&self) -> &Polytope {
        &self.polytope
    }

    /// Vertex `k` as `(y, w)` in lowest terms (`y / w`, `w > 0`); `None` when the
    /// polytope's denominator is 1 (the vertex itself).
    fn reduced(&self, k: u32) -> Option<&(Vec3, Int)> {
        let cell = &self.reduced.as_ref()?[k as usize];
        Some(cell.get_or_init(|| {
            let (v, den) = (&self.polytope.vertices()[k as usize], self.polytope.den());
            // The denominator's gcd with one coordinate first: usually 1 already, or
            // small, which makes the others cheap.
            let c = v.to_ints();
            let mut g = apart_kernel::int::gcd(den, &c[0]);
            for x in &c[1..] {
                if g == Int::ONE {
                    break;
                }
                g = apart_kernel::int::gcd(&g, x);
            }
            if g == Int::ONE {
                (v.clone(), den.clone())
            } else {
                (Vec3::from_ints(c.map(|x| x / &g)), den / &g)
            }
        }))
    }

    /// Facet `f` as a polygon: vertices and edges counter-clockwise around its normal
    /// from its lexicographically smallest vertex (in its plane's projection).
    fn facet_polygon(&self, f: usize) -> Polygon {
        let c = &self.polytope.facets()[f].cycle;
        let (es, s, m) = (&self.facet_edges[f], self.lexmin[f] as usize, c.len());
        (
            (0..m).map(|t| c[(s + t) % m]).collect(),
            (0..m).map(|t| es[(s + t) % m]).collect(),
        )
    }

    /// The primitive direction of the edge between vertices `a` and `b` (either
    /// sign), or `None` when they span no edge.
    fn edge_dir(&self, a: u32, b: u32) -> Option<&Vec3> {
        let nv = self.polytope.vertices().len() as u64;
        let e = *self
            .edge_of
            .get(&(a.min(b) as u64 * nv + a.max(b) as u64))?;
        Some(&self.dirs[e as usize])
    }

    /// The edge between vertices `a` and `b` as a polygon in a plane of normal `n`: its
    /// two vertices from the lexicographically smallest one (in the plane's projection)
    /// and its two directed edges. `None` when `a b` is not an edge.
    fn segment_polygon(&self, n: &Vec3, a: u32, b: u32) -> Option<Polygon> {
        let vs = self.polytope.vertices();
        let nv = vs.len() as u64;
        let e = *self
            .edge_of
            .get(&(a.min(b) as u64 * nv + a.max(b) as u64))?;
        let (u, v, _) = plane_axes(n);
        let (lo, hi) = match cmp_lex(&vs[a as usize], &vs[b as usize], u, v) {
            Ordering::Less => (a, b),
            _ => (b, a),
        };
        let forward = self.polytope.edges()[e as usize].ends[0] == lo;
        Some((vec![lo, hi], vec![(e, forward), (e, !forward)]))
    }
}

/// A convex polygon as vertex indices and the edges from each to the next (edge index,
/// and whether it runs `ends[0] -> ends[1]`).
type Polygon = (Vec<u32>, Vec<(u32, bool)>);

/// Compares coordinate `i` of two vectors exactly, without copying big integers.
fn cmp_coord(a: &Vec3, b: &Vec3, i: usize) -> Ordering {
    match (a.components(), b.components()) {
        (Components::Small(x), Components::Small(y)) => x[i].cmp(&y[i]),
        (Components::Big(x), Components::Big(y)) => x[i].cmp(&y[i]),
        (Components::Small(x), Components::Big(y)) => Int::from(x[i]).cmp(&y[i]),
        (Components::Big(x), Components::Small(y)) => x[i].cmp(&Int::from(y[i])),
    }
}

/// Lexicographic order of coordinates `(u, v)`.
fn cmp_lex(a: &Vec3, b: &Vec3, u: usize, v: usize) -> Ordering {
    cmp_coord(a, b, u).then_with(|| cmp_coord(a, b, v))
}

/// The vertices of `y` attaining `max n · v`, in increasing order (as
/// [`Polytope::support`] gives them): only those whose float value comes within the
/// shadow's error bound of the float maximum can attain the exact one; a single such
/// candidate is the answer, and two joined by an edge compare by the sign of `n` along
/// the edge's primitive direction (small, filtered), both without big products.
fn extreme(sy: &Summand, n: &Vec3) -> Vec<u32> {
    let y = &sy.polytope;
    let filter = y.shadow().and_then(|s| {
        let u = n.unit_f64();
        u.iter().all(|c| c.is_finite()).then_some((s, u))
    });
    let Some((s, u)) = filter else {
        return y.support(n).1;
    };
    let dot = |p: &[f64; 3]| fvec::dot(*p, u);
    let max = s.points.iter().map(dot).fold(f64::NEG_INFINITY, f64::max);
    // Every exact value is within `error` of its float one: a vertex whose float value
    // is below `max - 2 error` is exactly below the vertex that attains `max`.
    let floor = max - 2.0 * s.error();
    let cand: Vec<u32> = (0..s.points.len() as u32)
        .filter(|&i| dot(&s.points[i as usize]) >= floor)
        .collect();
    match cand.len() {
        0 => return y.support(n).1, // (only if the floats misbehave)
        1 => return cand,
        2 => {
            // Two candidates joined by an edge: the sign of n along the edge decides.
            let nv = y.vertices().len() as u64;
            let (a, b) = (cand[0], cand[1]);
            if let Some(&e) = sy.edge_of.get(&(a as u64 * nv + b as u64)) {
                let [e0, e1] = y.edges()[e as usize].ends;
                return match dot_sign(n, &sy.dirs[e as usize]) {
                    Sign::Zero => cand,
                    Sign::Positive => vec![e1],
                    Sign::Negative => vec![e0],
                };
            }
        }
        _ => {}
    }
    let vs = y.vertices();
    let mut best: Option<Int> = None;
    let mut arg = Vec::new();
    for i in cand {
        let d = n.dot(&vs[i as usize]);
        match &best {
            Some(b) if d < *b => continue,
            Some(b) if d == *b => arg.push(i),
            _ => {
                best = Some(d);
                arg.clear();
                arg.push(i);
            }
        }
    }
    arg
}

/// The sum of two convex polygons in the plane of normal `n`, each given by vertices
/// and edges (index and whether it runs `ends[0] -> ends[1]`, directions in `xd`, `yd`)
/// counter-clockwise around `n` from a vertex extreme in one common direction (their
/// lexicographically smallest): the vertex pairs of the sum, counter-clockwise from the
/// pair of the two starting vertices, strictly convex.
///
/// Merge by angle: both edge sequences turn monotonically through less than a full turn
/// from the common start, consecutive edges of a polygon turn by less than a half turn
/// (exactly a half turn for a segment, whose second edge only comes after the other
/// polygon has passed its first), so the two current edges are always less than a half
/// turn apart and the sign of `det(n, e_x, e_y)` orders them; parallel edges advance
/// together, which drops the vertex between them.
fn merge_polygons(
    n: &Vec3,
    (xv, xe): (&[u32], &[(u32, bool)]),
    xd: &[Vec3],
    (yv, ye): (&[u32], &[(u32, bool)]),
    yd: &[Vec3],
) -> Vec<(u32, u32)> {
    let (m, k) = (xv.len(), yv.len());
    let (mut i, mut j) = (0, 0);
    let mut out = Vec::with_capacity(m + k);
    while i < m || j < k {
        out.push((xv[i % m], yv[j % k]));
        if i == m {
            j += 1;
            continue;
        }
        if j == k {
            i += 1;
            continue;
        }
        let ((ex, fx), (ey, fy)) = (xe[i], ye[j]);
        let s = det3_sign(n, &xd[ex as usize], &yd[ey as usize]);
        let s = if fx == fy { s } else { -s };
        match s {
            Sign::Positive => i += 1,
            Sign::Negative => j += 1,
            Sign::Zero => {
                i += 1;
                j += 1;
            }
        }
    }
    out
}

/// `k v` as integers (no float shadow: only the sum becomes a vector).
fn scaled(v: &Vec3, k: &Int) -> [Int; 3] {
    match v.components() {
        Components::Small(c) => c.map(|x| Int::from(x) * k),
        Components::Big(c) => [&c[0] * k, &c[1] * k, &c[2] * k],
    }
}

/// The factors `(kp, kq)` that bring the stored integers of `p` and of `q` to the
/// least common multiple of their denominators, or `None` when the two are equal.
fn den_factors(p: &Polytope, q: &Polytope) -> Option<(Int, Int)> {
    (p.den() != q.den()).then(|| {
        let g = apart_kernel::int::gcd(p.den(), q.den());
        (q.den() / &g, p.den() / &g)
    })
}

/// The points `vp + vq` of a sum, over the common denominator: each vertex of a
/// Minkowski sum decomposes uniquely into vertices of the summands, so the index pair
/// `(i, j)` names it.
struct PairPoints<'a> {
    sp: &'a Summand,
    sq: &'a Summand,
    /// The factors that bring each summand to the common denominator, when they differ.
    k: Option<(Int, Int)>,
    /// The summands' vertices times `kp` and `kq` when the denominators differ (made on
    /// first use: a projection needs only [`PairPoints::direction`]).
    scaled: std::cell::OnceCell<[Vec<[Int; 3]>; 2]>,
}

impl<'a> PairPoints<'a> {
    fn new(sp: &'a Summand, sq: &'a Summand) -> PairPoints<'a> {
        PairPoints {
            sp,
            sq,
            k: den_factors(&sp.polytope, &sq.polytope),
            scaled: std::cell::OnceCell::new(),
        }
    }

    /// The sum's denominator.
    fn den(&self) -> Int {
        match &self.k {
            None => self.sp.polytope.den().clone(),
            Some((kp, _)) => self.sp.polytope.den() * kp,
        }
    }

    /// Vertex `(i, j)` of the sum, over [`PairPoints::den`].
    fn get(&self, i: u32, j: u32) -> Vec3 {
        let (i, j) = (i as usize, j as usize);
        let (pv, qv) = (self.sp.polytope.vertices(), self.sq.polytope.vertices());
        match &self.k {
            None => pv[i].add(&qv[j]),
            Some((kp, kq)) => {
                let [sp, sq] = self.scaled.get_or_init(|| {
                    let scale = |vs: &[Vec3], k: &Int| -> Vec<[Int; 3]> {
                        vs.iter().map(|v| scaled(v, k)).collect()
                    };
                    [scale(pv, kp), scale(qv, kq)]
                });
                let (x, y) = (&sp[i], &sq[j]);
                Vec3::from_ints([&x[0] + &y[0], &x[1] + &y[1], &x[2] + &y[2]])
            }
        }
    }

    /// A positive multiple of vertex `(i, j)`: `yi wj + yj wi` for the summands'
    /// vertices `yi / wi` and `yj / wj` in lowest terms, whose sum is that over `wi wj`.
    /// Everything a central projection asks of a point (signs of dot products and
    /// determinants, the primitive direction) is the same for every positive multiple,
    /// and this one is far shorter than [`PairPoints::get`] for pieces cut out of a
    /// tessellated part, where the common denominator is the product of many.
    fn direction(&self, i: u32, j: u32) -> Vec3 {
        match (self.sp.reduced(i), self.sq.reduced(j)) {
            (None, None) => self.sp.polytope.vertices()[i as usize]
                .add(&self.sq.polytope.vertices()[j as usize]),
            (Some((yi, wi)), None) => yi.add(&self.sq.polytope.vertices()[j as usize].scale(wi)),
            (None, Some((yj, wj))) => self.sp.polytope.vertices()[i as usize].scale(wj).add(yj),
            (Some((yi, wi)), Some((yj, wj))) if wi == wj => yi.add(yj),
            (Some((yi, wi)), Some((yj, wj))) => yi.scale(wj).add(&yj.scale(wi)),
        }
    }
}

/// Receives a facet of a sum: its outward normal, its cycle of vertex pairs, and
/// whether that cycle runs clockwise ([`facets_where`]).
type Emit<'a> = dyn FnMut(&Vec3, &[(u32, u32)], bool) + 'a;

/// The facets of `sp ⊕ sq` whose plane `want(normal, i, j)` accepts (`(i, j)` a vertex
/// pair whose sum lies on the facet); a facet of `p` or `q` plus a face of the other is
/// skipped first, before that face is found, when `maybe(from_p, facet index)` says so,
/// and only the edges of `p` and of `q` listed in `edges` (in the order of `by_low_x`;
/// `None` for all) may make parallelograms. Each handed to `emit` as its outward normal and
/// its cycle of vertex pairs: counter-clockwise around the normal, or clockwise when
/// the flag is set (a parallelogram, listed before its orientation was known). Facets
/// come in a fixed order: those of `p`, those of `q`, then the parallelograms.
fn facets_where(
    sp: &Summand,
    sq: &Summand,
    points: &PairPoints,
    maybe: &dyn Fn(bool, usize) -> bool,
    edges: [Option<&[u32]>; 2],
    want: &mut dyn FnMut(&Vec3, u32, u32) -> bool,
    emit: &mut Emit,
) -> Result<(), PolytopeError> {
    let (p, q) = (&sp.polytope, &sq.polytope);
    let mut cycle: Vec<(u32, u32)> = Vec::new();
    // Facets of p and of q, each with the other's extreme face.
    for (x_is_p, sx, sy) in [(true, sp, sq), (false, sq, sp)] {
        let (x, y) = (&sx.polytope, &sy.polytope);
        for (fi, f) in x.facets().iter().enumerate() {
            if !x_is_p && sy.by_normal.contains_key(&f.normal) {
                continue; // both have a facet with this normal: already summed
            }
            if !maybe(x_is_p, fi) {
                continue;
            }
            let pair = |a: u32, b: u32| if x_is_p { (a, b) } else { (b, a) };
            // The face of y extreme along f's normal: y's facet with that normal, else
            // a vertex or an edge.
            let parallel = sy.by_normal.get(&f.normal);
            let arg = match parallel {
                Some(_) => Vec::new(),
                None => extreme(sy, &f.normal),
            };
            let on_y = match (parallel, arg.first()) {
                (Some(&g), _) => y.facets()[g as usize].cycle[0],
                (None, Some(&b)) => b,
                (None, None) => return Err(PolytopeError::NotClosed),
            };
            let (i, j) = pair(f.cycle[0], on_y);
            if !want(&f.normal, i, j) {
                continue;
            }
            let polygon = match (parallel, arg.len()) {
                (Some(&g), _) => Some(sy.facet_polygon(g as usize)),
                (None, 2) => sy.segment_polygon(&f.normal, arg[0], arg[1]),
                _ => None,
            };
            cycle.clear();
            if arg.len() == 1 {
                // Facet plus a vertex: the facet's own cycle, translated.
                cycle.extend(f.cycle.iter().map(|&a| pair(a, arg[0])));
            } else if let Some((gv, ge)) = polygon {
                // Facet plus an edge or a parallel facet: merge the two cycles from
                // their lexicographically smallest vertices (the order the 2-D hull of
                // all pairwise sums would give: counter-clockwise in the projection from
                // its smallest point, reversed when the projection flips orientation).
                let (fv, fe) = sx.facet_polygon(fi);
                let mut sum = merge_polygons(&f.normal, (&fv, &fe), &sx.dirs, (&gv, &ge), &sy.dirs);
                if plane_axes(&f.normal).2 {
                    sum.rotate_left(1);
                }
                cycle.extend(sum.into_iter().map(|(a, b)| pair(a, b)));
            } else {
                // Not a face of the expected shape (never for a valid polytope): the
                // exact hull of all pairwise sums.
                let mut cand: Vec<(u32, u32)> = Vec::with_capacity(f.cycle.len() * arg.len());
                let mut pts = Vec::with_capacity(f.cycle.len() * arg.len());
                for &a in &f.cycle {
                    for &b in &arg {
                        let (i, j) = pair(a, b);
                        cand.push((i, j));
                        pts.push(points.get(i, j));
                    }
                }
                let hull = hull_in_plane(&f.normal, &pts);
                if hull.len() < 3 {
                    return Err(PolytopeError::NotClosed);
                }
                cycle.extend(hull.into_iter().map(|k| cand[k]));
            }
            emit(&f.normal, &cycle, false);
        }
    }

    // Parallelograms of edge pairs whose Gaussian arcs cross (pairs whose boxes on the
    // unit sphere overlap, by sort and sweep; then the exact test).
    let [live_p, live_q] = edges;
    let pairs = sweep_pairs_between(
        &sp.boxes,
        live_p.unwrap_or(&sp.by_low_x),
        &sq.boxes,
        live_q.unwrap_or(&sq.by_low_x),
    );
    for (ip, iq) in pairs {
        let (ep, ap, eq, aq) = (&p.edges()[ip], &sp.arcs[ip], &q.edges()[iq], &sq.arcs[iq]);
        if !crossing(ap, aq) {
            continue;
        }
        let [p0, p1] = ep.ends;
        let [q0, q1] = eq.ends;
        // The facet's normal is the crossing point of the two arcs, perpendicular to
        // both edges: ±(dp × dq), far smaller than the cross of the arcs' normals (and
        // the same from the primitive directions). Its sign puts it on arc a
        // (counter-clockwise after a's first normal).
        let n = sp.dirs[ip].cross(&sq.dirs[iq]).primitive();
        let flip = det3_sign(&ap.c, &ap.m0, &n) == Sign::Negative;
        let n = if flip { n.neg() } else { n };
        debug_assert_eq!(
            arc_position(&ap.c, &ap.m0, &ap.m1, &n),
            ArcPosition::Interior
        );
        debug_assert_eq!(
            arc_position(&aq.c, &aq.m0, &aq.m1, &n),
            ArcPosition::Interior
        );
        if !want(&n, p0, q0) {
            continue;
        }
        // Counter-clockwise around +(dp × dq): (p0+q0, p1+q0, p1+q1, p0+q1).
        emit(&n, &[(p0, q0), (p1, q0), (p1, q1), (p0, q1)], flip);
    }
    Ok(())
}

/// The Minkowski sum of two prepared polytopes.
pub fn sum_prepared(sp: &Summand, sq: &Summand) -> Result<Polytope, PolytopeError> {
    // Different denominators: the sum's vertices are `kp vp + kq vq` over the least
    // common multiple (everything else is scale-invariant).
    let pairs = PairPoints::new(sp, sq);
    let den = pairs.den();
    let mut numbers = Numbering::new(&pairs, false);
    let mut facets: Vec<(Vec3, Vec<u32>)> = Vec::new();
    let all = &mut |_: &Vec3, _, _| true;
    facets_where(
        sp,
        sq,
        &pairs,
        &|_, _| true,
        [None, None],
        all,
        &mut |n, cycle, reversed| facets.push((n.clone(), numbers.cycle(cycle, reversed))),
    )?;
    Ok(Polytope::from_facets(&numbers.points, facets)?.with_den(den))
}

/// The vertices of some facets of a sum, numbered as they first appear in their cycles
/// (as [`PairPoints::direction`] gives them when `directions` is set).
struct Numbering<'a> {
    pairs: &'a PairPoints<'a>,
    directions: bool,
    ids: HashMap<u64, u32>,
    /// The vertices' points, by number.
    points: Vec<Vec3>,
    /// The vertices' pairs, by number.
    pairs_of: Vec<(u32, u32)>,
}

impl<'a> Numbering<'a> {
    fn new(pairs: &'a PairPoints<'a>, directions: bool) -> Numbering<'a> {
        Numbering {
            pairs,
            directions,
            ids: HashMap::default(),
            points: Vec::new(),
            pairs_of: Vec::new(),
        }
    }

    /// A cycle of vertex pairs ([`facets_where`]) as vertex numbers, counter-clockwise.
    fn cycle(&mut self, cycle: &[(u32, u32)], reversed: bool) -> Vec<u32> {
        let nq = self.pairs.sq.polytope.vertices().len() as u64;
        let (pairs, directions) = (self.pairs, self.directions);
        let mut c: Vec<u32> = cycle
            .iter()
            .map(|&(i, j)| {
                *self.ids.entry(i as u64 * nq + j as u64).or_insert_with(|| {
                    self.points.push(if directions {
                        pairs.direction(i, j)
                    } else {
                        pairs.get(i, j)
                    });
                    self.pairs_of.push((i, j));
                    (self.points.len() - 1) as u32
                })
            })
            .collect();
        if reversed {
            c.reverse();
        }
        c
    }
}

/// The central projection of `sp ⊕ sq` (as [`crate::project`] gives it) when the
/// origin lies outside the sum, made from the sum's facets that face the origin alone:
/// the sides of the projection are the edges of those facets that no second such facet
/// shares. `None` when no facet faces the origin (the origin lies in the sum: project
/// the whole sum instead). A sum of a piece with a many-sided one has as many facets,
/// but seen from a point just outside it only a few face that point.
pub fn project_apart(sp: &Summand, sq: &Summand) -> Option<Result<SphericalPolygon, PolygonError>> {
    let (p, q) = (&sp.polytope, &sq.polytope);
    let pairs = PairPoints::new(sp, sq);
    // The facing facets' vertices and cycles, counter-clockwise; only their directions
    // matter (see `PairPoints::direction`).
    let mut numbers = Numbering::new(&pairs, true);
    let mut cycles: Vec<Vec<u32>> = Vec::new();
    // A facet of one summand plus a face of the other faces the origin only when its
    // level plus the other's support value is negative, and a parallelogram on an edge
    // only when no vertex of the other summand keeps both facets at the edge clear of
    // the origin: most of a many-sided piece's facets and edges are dropped by floats.
    let (bp, bq) = (clear_of(p, q), clear_of(q, p));
    let maybe = |from_p: bool, fi: usize| -> bool {
        let (x, y, bits) = if from_p { (p, q, &bp) } else { (q, p, &bq) };
        match bits {
            Some(b) if b[fi] != 0 => false,
            // No bit: every vertex of `y` (when it has 64 or fewer, they all had one).
            Some(_) if y.vertices().len() <= 64 => true,
            _ => !clearly_positive(x, fi, y),
        }
    };
    let (live_p, live_q) = (live_edges(sp, &bp), live_edges(sq, &bq));
    let floats = p
        .shadow()
        .zip(q.shadow())
        .map(|(sx, sy)| (sx, sy, sum_margin(sx, sy)));
    let found = facets_where(
        sp,
        sq,
        &pairs,
        &maybe,
        [live_p.as_deref(), live_q.as_deref()],
        &mut |n, i, j| {
            // Floats first (as `clearly_positive` measures), then the exact sign.
            if let Some((sx, sy, margin)) = floats {
                let u = n.unit_f64();
                let v = fvec::dot(u, sx.points[i as usize]) + fvec::dot(u, sy.points[j as usize]);
                if v.is_finite() && v.abs() > margin {
                    return v < 0.0;
                }
            }
            dot_sign(n, &pairs.direction(i, j)) == Sign::Negative
        },
        &mut |_, cycle, reversed| cycles.push(numbers.cycle(cycle, reversed)),
    );
    if let Err(e) = found {
        return Some(Err(PolygonError(format!("Minkowski sum: {e}"))));
    }
    if cycles.is_empty() {
        return None;
    }
    // Each edge of a facing facet, by its ends: shared by two facing facets, or a side.
    let key = |a: u32, b: u32| (a.min(b), a.max(b));
    let mut uses: HashMap<(u32, u32), u32> = HashMap::default();
    for c in &cycles {
        for t in 0..c.len() {
            *uses.entry(key(c[t], c[(t + 1) % c.len()])).or_default() += 1;
        }
    }
    let (points, pairs_of) = (numbers.points, numbers.pairs_of);
    let mut primitive: Vec<Option<Vec3>> = vec![None; points.len()];
    let mut arcs = Vec::new();
    for c in &cycles {
        for t in 0..c.len() {
            let (a, b) = (c[t], c[(t + 1) % c.len()]);
            if uses[&key(a, b)] == 1 {
                // A side of the sum is a vertex of one summand plus an edge of the
                // other: that edge's (short, primitive) direction spans its plane.
                let ((i0, j0), (i1, j1)) = (pairs_of[a as usize], pairs_of[b as usize]);
                let dir = if i0 == i1 {
                    sq.edge_dir(j0, j1)
                } else if j0 == j1 {
                    sp.edge_dir(i0, i1)
                } else {
                    None
                };
                match silhouette_side(&points, [a, b], dir, c, &mut primitive) {
                    Ok(side) => arcs.push(side),
                    Err(e) => return Some(Err(e)),
                }
            }
        }
    }
    Some(polygon_of_sides(arcs, points.len()))
}

/// For each facet of `x`, a bit per vertex `y_k` of `y` set when the facet's plane,
/// moved by `y_k`, clearly (beyond the float error) has the origin inside: then no facet
/// of `x ⊕ y` with that normal, nor between it and the normal of a facet whose bit `k`
/// is also set, faces the origin (`h(n) ≥ n · (x_f + y_k)` is linear in `n`). A `y` of
/// more than 64 vertices is represented by 64 of them spread over its list (any vertex
/// gives a valid bound; a facet without a bit may still be clear). `None` when either
/// polytope has no float shadow.
fn clear_of(x: &Polytope, y: &Polytope) -> Option<Vec<u64>> {
    let (sx, sy) = (x.shadow()?, y.shadow()?);
    // Bit `k` stands for vertex `k` of `y`, or for vertex `k m / 64` of a larger one.
    let m = sy.points.len();
    let spread: Vec<[f64; 3]>;
    let sample: &[[f64; 3]] = if m > 64 {
        spread = (0..64).map(|k| sy.points[k * m / 64]).collect();
        &spread
    } else {
        &sy.points
    };
    let margin = sum_margin(sx, sy);
    Some(
        sx.facet_units
            .iter()
            .zip(&sx.facet_levels)
            .map(|(u, level)| {
                sample.iter().enumerate().fold(0u64, |bits, (k, y)| {
                    if level + fvec::dot(*u, *y) > margin {
                        bits | 1 << k
                    } else {
                        bits
                    }
                })
            })
            .collect(),
    )
}

/// Whether facet `fi` of `x` plus the face of `y` extreme along its normal clearly lies
/// in a plane with the origin inside (float level plus float support value, beyond the
/// error bound); false when not sure.
fn clearly_positive(x: &Polytope, fi: usize, y: &Polytope) -> bool {
    let (Some(sx), Some(sy)) = (x.shadow(), y.shadow()) else {
        return false;
    };
    let u = sx.facet_units[fi];
    let top = sy
        .points
        .iter()
        .map(|y| fvec::dot(u, *y))
        .fold(f64::NEG_INFINITY, f64::max);
    sx.facet_levels[fi] + top > sum_margin(sx, sy)
}

/// The error bound of a float value `u · x + u · y` (or a facet level plus `u · y`) for a
/// unit axis `u` and shadow points of `x` and `y`: each term is within its shadow's
/// [`Shadow::error`], doubled for the sum's rounding and a wide margin.
fn sum_margin(sx: &Shadow, sy: &Shadow) -> f64 {
    2.0 * (sx.error() + sy.error())
}

/// The edges of `sx` (in its `by_low_x` order) whose parallelograms may face the
/// origin: those whose two facets share no bit of `clear` ([`clear_of`]). `None` (all)
/// without bits.
fn live_edges(sx: &Summand, clear: &Option<Vec<u64>>) -> Option<Vec<u32>> {
    let bits = clear.as_ref()?;
    let edges = sx.polytope.edges();
    Some(
        sx.by_low_x
            .iter()
            .copied()
            .filter(|&e| {
                let [f, g] = edges[e as usize].facets;
                bits[f as usize] & bits[g as usize] == 0
            })
            .collect(),
    )
}

/// The Gaussian arc of an edge: normals `m0`, `m1` of its two facets and the normal
/// `c = m0 × m1` of the great circle through them (parallel to the edge).
#[derive(Clone, Debug)]
struct GaussArc {
    m0: Vec3,
    m1: Vec3,
    c: Vec3,
}

fn gaussian_arcs(p: &Polytope) -> Vec<GaussArc> {
    p.edges()
        .iter()
        .map(|e| {
            let m0 = p.facets()[e.facets[0] as usize].normal.clone();
            let m1 = p.facets()[e.facets[1] as usize].normal.clone();
            let c = m0.cross(&m1);
            GaussArc { m0, m1, c }
        })
        .collect()
}

/// Whether two Gaussian arcs cross in both relative interiors.
///
/// Arcs `(a0, a1)` and `(b0, b1)` (each shorter than a half circle) cross properly iff
/// `b0`, `b1` lie strictly on opposite sides of circle `a`, `a0`, `a1` strictly on
/// opposite sides of circle `b`, and `sign(c_a · b0) = −sign(c_b · a0)`.
fn crossing(a: &GaussArc, b: &GaussArc) -> bool {
    let s0 = dot_sign(&a.c, &b.m0);
    if s0 == Sign::Zero {
        return false;
    }
    dot_sign(&a.c, &b.m1) == -s0 && dot_sign(&b.c, &a.m0) == -s0 && dot_sign(&b.c, &a.m1) == s0
}

/// `max n · v` over the vertices of `p` (the support function).
pub fn support_value(p: &Polytope, n: &Vec3) -> Int {
    p.support_value(n)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn pts(c: &[[i64; 3]]) -> Vec<Vec3> {
        c.iter().map(|&v| Vec3::from(v)).collect()
    }

    /// Brute force: the hull of all pairwise sums.
    fn brute(p: &Polytope, q: &Polytope) -> Polytope {
        let mut s = Vec::new();
        for a in p.vertices() {
            for b in q.vertices() {
                s.push(a.add(b));
            }
        }
        Polytope::hull_of_points(&s).unwrap()
    }

    fn same(a: &Polytope, b: &Polytope) -> bool {
        let mut va: Vec<String> = a.vertices().iter().map(|v| format!("{v:?}")).collect();
        let mut vb: Vec<String> = b.vertices().iter().map(|v| format!("{v:?}")).collect();
        va.sort();
        vb.sort();
        let mut fa: Vec<String> = a
            .facets()
            .iter()
            .map(|f| format!("{:?} {}", f.normal, f.offset))
            .collect();
        let mut fb: Vec<String> = b
            .facets()
            .iter()
            .map(|f| format!("{:?} {}", f.normal, f.offset))
            .collect();
        fa.sort();
        fb.sort();
        va == vb && fa == fb
    }

    #[test]
    fn cube_plus_tetrahedron() {
        let cube = Polytope::hull_of_points(&pts(&[
            [0, 0, 0],
            [1, 0, 0],
            [0, 1, 0],
            [1, 1, 0],
            [0, 0, 1],
            [1, 0, 1],
            [0, 1, 1],
            [1, 1, 1],
        ]))
        .unwrap();
        let tet =
            Polytope::hull_of_points(&pts(&[[0, 0, 0], [2, 1, 0], [1, 3, 1], [0, 1, 4]])).unwrap();
        let s = minkowski_sum(&cube, &tet).unwrap();
        assert!(same(&s, &brute(&cube, &tet)));
        assert_eq!(s.volume6(), brute(&cube, &tet).volume6());
    }

    #[test]
    fn parallel_faces_and_edges() {
        // Two boxes: every facet normal is shared, every edge direction parallel.
        let a = Polytope::hull_of_points(&pts(&[
            [0, 0, 0],
            [2, 0, 0],
            [0, 3, 0],
            [2, 3, 0],
            [0, 0, 1],
            [2, 0, 1],
            [0, 3, 1],
            [2, 3, 1],
        ]))
        .unwrap();
        let d = minkowski_difference(&a, &a).unwrap();
        assert_eq!(d.vertices().len(), 8);
        assert_eq!(d.facets().len(), 6);
        assert!(same(&d, &brute(&a, &a.reflected())));
    }

    #[test]
    fn different_denominators() {
        // [0, 1]^3 stored as [0, 2]^3 / 2, minus the unit cube at x = 1..2 (den 1):
        // b ⊕ (−a) = [0, 2] x [-1, 1] x [-1, 1], stored with denominator 2.
        let cube = |lo: i64, s: i64| -> Vec<Vec3> {
            (0..8)
                .map(|i| Vec3::new(lo + (i & 1) * s, (i >> 1 & 1) * s, (i >> 2) * s))
                .collect()
        };
        let a = Polytope::hull_of_points(&cube(0, 2))
            .unwrap()
            .with_den(Int::from(2));
        let b = Polytope::hull_of_points(&cube(1, 1)).unwrap();
        let m = minkowski_difference(&b, &a).unwrap();
        assert_eq!(m.den(), &Int::from(2));
        assert_eq!(m.volume(), apart_kernel::Rational::from_int(8));
        let (_, arg) = m.support(&Vec3::new(1, 0, 0));
        assert_eq!(m.vertices()[arg[0] as usize].get(0), Int::from(4));
    }

    #[test]
    fn octahedron_and_pyramid() {
        let oct = Polytope::hull_of_points(&pts(&[
            [1, 0, 0],
            [-1, 0, 0],
            [0, 1, 0],
            [0, -1, 0],
            [0, 0, 1],
            [0, 0, -1],
        ]))
        .unwrap();
        let pyr = Polytope::hull_of_points(&pts(&[
            [-1, -1, 0],
            [1, -1, 0],
            [1, 1, 0],
            [-1, 1, 0],
            [0, 0, 2],
        ]))
        .unwrap();
        for (x, y) in [(&oct, &pyr), (&pyr, &oct), (&oct, &oct), (&pyr, &pyr)] {
            let s = minkowski_difference(x, y).unwrap();
            assert!(same(&s, &brute(x, &y.reflected())));
        }
    }
}
