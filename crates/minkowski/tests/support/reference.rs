//! The Minkowski sum as computed before the fast path (commit de98644): every facet of
//! either summand plus the other's extreme face as the exact 2-D hull of all pairwise
//! vertex sums, on both summands brought to a common denominator. Kept verbatim (up to
//! the precomputed `Summand`) as the oracle the fast path must match bit for bit; and
//! the central projection before its silhouette cached primitive vertices.

#![allow(dead_code)]

use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Sign, Vec3};
use apart_pieces::hull2d::hull_in_plane;
use apart_pieces::{Polytope, PolytopeError};
use std::collections::HashMap;

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

fn crossing(a: &GaussArc, b: &GaussArc) -> bool {
    let s0 = dot_sign(&a.c, &b.m0);
    if s0 == Sign::Zero {
        return false;
    }
    dot_sign(&a.c, &b.m1) == -s0 && dot_sign(&b.c, &a.m0) == -s0 && dot_sign(&b.c, &a.m1) == s0
}

fn boxes(arcs: &[GaussArc]) -> Vec<[[f64; 2]; 3]> {
    arcs.iter()
        .map(|a| {
            let b = apart_sphere::Arc {
                normal: a.c.clone(),
                start: a.m0.clone(),
                end: a.m1.clone(),
            }
            .bbox();
            [0, 1, 2].map(|k| [b.min[k], b.max[k]])
        })
        .collect()
}

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

/// `p ⊕ q` by the old exact path.
pub fn reference_sum(p: &Polytope, q: &Polytope) -> Result<Polytope, PolytopeError> {
    if p.den() != q.den() {
        let (p, q) = Polytope::common(p, q);
        return reference_sum(&p, &q);
    }
    let den = p.den().clone();
    let nq = q.vertices().len() as u64;
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
    for (x_is_p, x, y) in [(true, p, q), (false, q, p)] {
        for f in x.facets() {
            if normals_done.insert(f.normal.clone(), ()).is_some() {
                continue;
            }
            let (_, arg) = y.support(&f.normal);
            let pair = |a: u32, b: u32| if x_is_p { (a, b) } else { (b, a) };
            let cycle: Vec<u32> = if arg.len() == 1 {
                f.cycle
                    .iter()
                    .map(|&a| {
                        let (i, j) = pair(a, arg[0]);
                        vertex(i, j, &mut points)
                    })
                    .collect()
            } else {
                let mut cand: Vec<(u32, u32)> = Vec::new();
                let mut pts = Vec::new();
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
    let (ap_all, aq_all) = (gaussian_arcs(p), gaussian_arcs(q));
    for (ip, iq) in overlapping(&boxes(&ap_all), &boxes(&aq_all)) {
        let (ep, ap, eq, aq) = (&p.edges()[ip], &ap_all[ip], &q.edges()[iq], &aq_all[iq]);
        if !crossing(ap, aq) {
            continue;
        }
        let [p0, p1] = ep.ends;
        let [q0, q1] = eq.ends;
        let dp = p.vertices()[p1 as usize].sub(&p.vertices()[p0 as usize]);
        let dq = q.vertices()[q1 as usize].sub(&q.vertices()[q0 as usize]);
        let n = dp.cross(&dq).primitive();
        let flip = det3_sign(&ap.c, &ap.m0, &n) == Sign::Negative;
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
        facets.push((n, cycle));
    }
    Ok(Polytope::from_facets(&points, facets)?.with_den(den))
}

/// Whether two polytopes are identical: same denominator, same vertices in the same
/// order, same facets (normal, offset, cycle) in the same order, same edges.
pub fn identical(a: &Polytope, b: &Polytope) -> bool {
    a.den() == b.den()
        && a.vertices() == b.vertices()
        && a.edges() == b.edges()
        && a.facets().len() == b.facets().len()
        && a.facets()
            .iter()
            .zip(b.facets())
            .all(|(f, g)| f.normal == g.normal && f.offset == g.offset && f.cycle == g.cycle)
}

/// The central projection as computed before the silhouette's vertex cache (commit
/// 20d4246).
pub fn reference_project(
    m: &Polytope,
) -> Result<apart_minkowski::Projection, apart_sphere::polygon::PolygonError> {
    // Sign of each facet's offset: offset < 0 means the origin is outside that facet.
    let signs: Vec<Sign> = m
        .facets()
        .iter()
        .map(|f| apart_kernel::int::sign_of(&f.offset))
        .collect();
    if signs.contains(&Sign::Negative) {
        return reference_silhouette(m, &signs).map(apart_minkowski::Projection::Polygon);
    }
    let active: Vec<usize> = (0..signs.len())
        .filter(|&i| signs[i] == Sign::Zero)
        .collect();
    match active.len() {
        0 => Ok(apart_minkowski::Projection::Everything),
        1 => Ok(apart_minkowski::Projection::Polygon(
            apart_sphere::SphericalPolygon::hemisphere(&m.facets()[active[0]].normal.neg()),
        )),
        2 => {
            let (q1, q2) = (
                m.facets()[active[0]].normal.neg(),
                m.facets()[active[1]].normal.neg(),
            );
            Ok(apart_minkowski::Projection::Polygon(
                apart_sphere::SphericalPolygon::lune(&q1, &q2),
            ))
        }
        _ => reference_vertex_cone(m, &active).map(apart_minkowski::Projection::Polygon),
    }
}

/// The polygon when the origin is outside: one side per silhouette edge.
fn reference_silhouette(
    m: &Polytope,
    signs: &[Sign],
) -> Result<apart_sphere::SphericalPolygon, apart_sphere::polygon::PolygonError> {
    let mut arcs = Vec::new();
    for e in m.edges() {
        let (f, g) = (e.facets[0] as usize, e.facets[1] as usize);
        let (front, _back) = match (signs[f], signs[g]) {
            (Sign::Negative, Sign::Negative) => continue,
            (Sign::Negative, _) => (f, g),
            (_, Sign::Negative) => (g, f),
            _ => continue,
        };
        let (v0, v1) = (
            &m.vertices()[e.ends[0] as usize],
            &m.vertices()[e.ends[1] as usize],
        );
        let n = v0.cross(v1);
        if n.is_zero() {
            continue; // the edge's line passes through the origin: it projects to a point
        }
        // Inward normal: the side where the rest of the front facet lies.
        let cycle = &m.facets()[front].cycle;
        let w = cycle
            .iter()
            .map(|&i| &m.vertices()[i as usize])
            .find(|w| dot_sign(&n, w) != Sign::Zero)
            .ok_or_else(|| {
                apart_sphere::polygon::PolygonError(
                    "front facet lies in a plane through the origin".into(),
                )
            })?;
        let q = if dot_sign(&n, w) == Sign::Positive {
            n.primitive()
        } else {
            n.neg().primitive()
        };
        arcs.push(
            apart_sphere::Arc::on_circle(&q, v0, v1)
                .expect("silhouette edge endpoints are independent"),
        );
    }
    apart_sphere::SphericalPolygon::from_arcs(arcs)
}

/// The tangent cone at the vertex of `m` at the origin (three or more facets through it).
fn reference_vertex_cone(
    m: &Polytope,
    active: &[usize],
) -> Result<apart_sphere::SphericalPolygon, apart_sphere::polygon::PolygonError> {
    let origin = m
        .vertices()
        .iter()
        .position(|v| v.is_zero())
        .ok_or_else(|| {
            apart_sphere::polygon::PolygonError("origin on three facets but not a vertex".into())
        })? as u32;
    let mut arcs = Vec::new();
    for &f in active {
        let facet = &m.facets()[f];
        let c = &facet.cycle;
        let k = c.iter().position(|&v| v == origin).ok_or_else(|| {
            apart_sphere::polygon::PolygonError("active facet misses the origin".into())
        })?;
        let prev = &m.vertices()[c[(k + c.len() - 1) % c.len()] as usize];
        let next = &m.vertices()[c[(k + 1) % c.len()] as usize];
        let q = facet.normal.neg();
        arcs.push(
            apart_sphere::Arc::on_circle(&q, prev, next).ok_or_else(|| {
                apart_sphere::polygon::PolygonError("flat vertex in a facet".into())
            })?,
        );
    }
    apart_sphere::SphericalPolygon::from_arcs(arcs)
}

/// Whether two projections are identical (same arcs and normals, in the same order).
pub fn same_projection(a: &apart_minkowski::Projection, b: &apart_minkowski::Projection) -> bool {
    format!("{a:?}") == format!("{b:?}")
}
