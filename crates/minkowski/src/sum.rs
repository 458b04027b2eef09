//! Exact Minkowski sums of convex polytopes.
//!
//! The facets of `P ⊕ Q` come in three kinds (the overlay of the two Gaussian maps):
//! a facet of `P` plus the face of `Q` extreme in its normal; a facet of `Q` plus the
//! face of `P` extreme in its normal; and the parallelogram `e_P + e_Q` for each pair of
//! edges whose Gaussian arcs (the normals of the planes supporting the edge) cross in
//! their relative interiors. Arcs that touch at an end point or overlap give facets of
//! the first two kinds, so only strict crossings make new facets. Each facet's vertex
//! cycle is the exact convex hull of the sums of the two faces' vertices.

use apart_kernel::predicates::dot_sign;
use apart_kernel::spherical::{arc_position, ArcPosition};
use apart_kernel::{Int, Sign, Vec3};
use apart_pieces::hull2d::hull_in_plane;
use apart_pieces::{Polytope, PolytopeError};
use rustc_hash::FxHashMap as HashMap;

/// `b ⊕ (−a) = {y − x : x ∈ a, y ∈ b}`: the translations of `a` that make it meet `b`.
/// (When many sums share `a`, reflect it once and call [`minkowski_sum`].)
pub fn minkowski_difference(b: &Polytope, a: &Polytope) -> Result<Polytope, PolytopeError> {
    minkowski_sum(b, &a.reflected())
}

/// The Minkowski sum `p ⊕ q` of two convex polytopes.
pub fn minkowski_sum(p: &Polytope, q: &Polytope) -> Result<Polytope, PolytopeError> {
    sum_prepared(&Summand::new(p.clone()), &Summand::new(q.clone()))
}

/// A polytope with its Gaussian arcs precomputed, for summing it many times.
#[derive(Clone, Debug)]
pub struct Summand {
    polytope: Polytope,
    arcs: Vec<GaussArc>,
    /// Conservative boxes of the Gaussian arcs on the unit sphere, by edge.
    boxes: Vec<[[f64; 2]; 3]>,
}

impl Summand {
    /// Prepares `polytope` for [`sum_prepared`].
    pub fn new(polytope: Polytope) -> Summand {
        let arcs = gaussian_arcs(&polytope);
        let boxes = arcs
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
        Summand {
            polytope,
            arcs,
            boxes,
        }
    }

    /// The polytope.
    pub fn polytope(&self) -> &Polytope {
        &self.polytope
    }
}

/// The Minkowski sum of two prepared polytopes.
pub fn sum_prepared(sp: &Summand, sq: &Summand) -> Result<Polytope, PolytopeError> {
    if sp.polytope.den() != sq.polytope.den() {
        // Different denominators: bring both to a common one (rare: decomposed parts).
        let (p, q) = Polytope::common(&sp.polytope, &sq.polytope);
        return sum_prepared(&Summand::new(p), &Summand::new(q));
    }
    let den = sp.polytope.den().clone();
    let (p, q) = (&sp.polytope, &sq.polytope);
    let nq = q.vertices().len() as u64;
    // A vertex of a Minkowski sum decomposes uniquely into vertices of the summands, so
    // the index pair (i, j) identifies it.
    let mut points: Vec<Vec3> = Vec::new();
    let mut ids: HashMap<u64, u32> = HashMap::default();
    let mut vertex = |i: u32, j: u32, points: &mut Vec<Vec3>| -> u32 {
        *ids.entry(i as u64 * nq + j as u64).or_insert_with(|| {
            points.push(p.vertices()[i as usize].add(&q.vertices()[j as usize]));
            (points.len() - 1) as u32
        })
    };
    let mut facets: Vec<(Vec3, Vec<u32>)> = Vec::new();
    let mut normals_done: HashMap<Vec3, ()> = HashMap::default();

    // Facets of p and of q, each with the other's extreme face.
    for (x_is_p, x, y) in [(true, p, q), (false, q, p)] {
        for f in x.facets() {
            if normals_done.insert(f.normal.clone(), ()).is_some() {
                continue; // both have a facet with this normal: already summed
            }
            let (_, arg) = y.support(&f.normal);
            let pair = |a: u32, b: u32| if x_is_p { (a, b) } else { (b, a) };
            let cycle: Vec<u32> = if arg.len() == 1 {
                // Facet plus a vertex: the facet's own cycle, translated.
                f.cycle
                    .iter()
                    .map(|&a| {
                        let (i, j) = pair(a, arg[0]);
                        vertex(i, j, &mut points)
                    })
                    .collect()
            } else {
                let mut cand: Vec<(u32, u32)> = Vec::with_capacity(f.cycle.len() * arg.len());
                let mut pts = Vec::with_capacity(f.cycle.len() * arg.len());
                for &a in &f.cycle {
                    for &b in &arg {
                        let (i, j) = pair(a, b);
                        cand.push((i, j));
                        pts.push(p.vertices()[i as usize].add(&q.vertices()[j as usize]));
                    }
                }
                let hull = hull_in_plane(&f.normal, &pts);
                if hull.len() < 3 {
                    return Err(PolytopeError::NotClosed);
                }
                hull.into_iter()
                    .map(|k| vertex(cand[k].0, cand[k].1, &mut points))
                    .collect()
            };
            facets.push((f.normal.clone(), cycle));
        }
    }

    // Parallelograms of edge pairs whose Gaussian arcs cross (pairs whose boxes on the
    // unit sphere overlap, by sort and sweep; then the exact test).
    for (ip, iq) in overlapping(&sp.boxes, &sq.boxes) {
        let (ep, ap, eq, aq) = (&p.edges()[ip], &sp.arcs[ip], &q.edges()[iq], &sq.arcs[iq]);
        {
            if !crossing(ap, aq) {
                continue;
            }
            let [p0, p1] = ep.ends;
            let [q0, q1] = eq.ends;
            // The facet's normal is the crossing point of the two arcs, perpendicular to
            // both edges: ±(dp × dq), far smaller than the cross of the arcs' normals. Its
            // sign puts it on arc a (counter-clockwise after a's first normal).
            let dp = p.vertices()[p1 as usize].sub(&p.vertices()[p0 as usize]);
            let dq = q.vertices()[q1 as usize].sub(&q.vertices()[q0 as usize]);
            let n = dp.cross(&dq).primitive();
            let flip = apart_kernel::predicates::det3_sign(&ap.c, &ap.m0, &n) == Sign::Negative;
            // Counter-clockwise around n = +(dp × dq): (p0+q0, p1+q0, p1+q1, p0+q1).
            let mut cycle = vec![
                vertex(p0, q0, &mut points),
                vertex(p1, q0, &mut points),
                vertex(p1, q1, &mut points),
                vertex(p0, q1, &mut points),
            ];
            let n = if flip {
                cycle.reverse();
                n.neg()
            } else {
                n
            };
            debug_assert_eq!(
                arc_position(&ap.c, &ap.m0, &ap.m1, &n),
                ArcPosition::Interior
            );
            debug_assert_eq!(
                arc_position(&aq.c, &aq.m0, &aq.m1, &n),
                ArcPosition::Interior
            );
            facets.push((n, cycle));
        }
    }
    Ok(Polytope::from_facets(&points, facets)?.with_den(den))
}

/// Index pairs `(i, j)` whose boxes `a[i]` and `b[j]` overlap (sort and sweep on x).
fn overlapping(a: &[[[f64; 2]; 3]], b: &[[[f64; 2]; 3]]) -> Vec<(usize, usize)> {
    let mut events: Vec<(f64, bool, usize)> = Vec::with_capacity(a.len() + b.len());
    events.extend(a.iter().enumerate().map(|(i, x)| (x[0][0], false, i)));
    events.extend(b.iter().enumerate().map(|(j, x)| (x[0][0], true, j)));
    events.sort_by(|x, y| x.0.total_cmp(&y.0));
    let overlap = |x: &[[f64; 2]; 3], y: &[[f64; 2]; 3]| {
        (0..3).all(|k| x[k][0] <= y[k][1] && y[k][0] <= x[k][1])
    };
    let (mut act_a, mut act_b): (Vec<usize>, Vec<usize>) = (Vec::new(), Vec::new());
    let mut out = Vec::new();
    for (lo, from_b, i) in events {
        act_a.retain(|&k| a[k][0][1] >= lo);
        act_b.retain(|&k| b[k][0][1] >= lo);
        if from_b {
            out.extend(
                act_a
                    .iter()
                    .filter(|&&k| overlap(&a[k], &b[i]))
                    .map(|&k| (k, i)),
            );
            act_b.push(i);
        } else {
            out.extend(
                act_b
                    .iter()
                    .filter(|&&k| overlap(&a[i], &b[k]))
                    .map(|&k| (i, k)),
            );
            act_a.push(i);
        }
    }
    out
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
    p.support(n).0
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
