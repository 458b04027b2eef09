//! Exact verification of a decomposition.
//!
//! Beyond the three checks that define a partition by volume (pieces convex and
//! full-dimensional, interiors pairwise disjoint, volumes summing to the solid's), it
//! checks that every piece lies in the solid: no input triangle meets a piece's open
//! interior (so the open piece is entirely inside or entirely outside), and one interior
//! point of each piece is inside (exact ray parity). Together these prove that the union
//! of the pieces is the solid: the pieces are closed subsets of it, and a point of the
//! solid missed by all would leave an open set of missing volume.

use crate::solid::Solid;
use crate::VerifyError;
use apart_kernel::bvh::sweep_pairs;
use apart_kernel::plane::{meet_big, on_segment_big, BigPlane, HPoint};
use apart_kernel::predicates::det3_sign;
use apart_kernel::{int, Aabb, Int, Rational, Sign, Vec3};
use apart_pieces::interference::interiors_disjoint;
use apart_pieces::Polytope;
use std::ops::ControlFlow;

/// Checks exactly that `pieces` decompose the solid bounded by `triangles`: every piece
/// convex and full-dimensional, interiors pairwise disjoint (bounding-box filter, then an
/// exact separating-axis test), every piece inside the solid, and the sum of piece
/// volumes equal to the solid's volume.
pub fn verify(
    points: &[Vec3],
    triangles: &[[u32; 3]],
    pieces: &[Polytope],
) -> Result<(), VerifyError> {
    let solid = Solid::new(points, triangles).map_err(VerifyError::Input)?;
    for (i, p) in pieces.iter().enumerate() {
        check_convex(p).map_err(|reason| VerifyError::NotConvex { piece: i, reason })?;
    }
    let mut total = Rational::zero();
    for p in pieces {
        total = &total + &p.volume();
    }
    let expected = Rational::new(solid.volume6.clone(), Int::from(6));
    if total != expected {
        return Err(VerifyError::VolumeMismatch {
            expected: expected.to_string(),
            found: total.to_string(),
        });
    }
    let boxes: Vec<Aabb<f64>> = pieces.iter().map(piece_box).collect();
    let overlap = sweep_pairs(&boxes, |i, j| {
        if interiors_disjoint(&pieces[i], &pieces[j]) {
            ControlFlow::Continue(())
        } else {
            ControlFlow::Break(VerifyError::Overlap {
                a: i.min(j),
                b: i.max(j),
            })
        }
    });
    if let ControlFlow::Break(e) = overlap {
        return Err(e);
    }
    let tri_boxes: Vec<Aabb<f64>> = solid
        .tris
        .iter()
        .map(|t| {
            let mut b = Aabb::EMPTY;
            for &v in t {
                b = b.with(&solid.pts[v as usize].map(|c| c as f64));
            }
            b
        })
        .collect();
    for (i, p) in pieces.iter().enumerate() {
        let facets: Vec<BigPlane> = p
            .facets()
            .iter()
            .map(|f| BigPlane::new(f.normal.to_ints(), f.offset.clone()))
            .collect();
        for (t, tb) in tri_boxes.iter().enumerate() {
            if boxes[i].overlaps(tb) && triangle_meets_interior(&solid, t, &facets, p.den()) {
                return Err(VerifyError::CrossesBoundary {
                    piece: i,
                    triangle: t,
                });
            }
        }
        match interior_point_inside(&solid, &tri_boxes, p) {
            Some(true) => {}
            Some(false) => return Err(VerifyError::Outside { piece: i }),
            None => return Err(VerifyError::Undecided { piece: i }),
        }
    }
    Ok(())
}

/// Convex, closed and full-dimensional: every vertex on the inner side of every facet,
/// each facet's cycle on its plane and strictly convex counter-clockwise, volume > 0.
fn check_convex(p: &Polytope) -> Result<(), String> {
    if p.volume6() <= Int::ZERO {
        return Err("no volume".into());
    }
    let v = p.vertices();
    for (fi, f) in p.facets().iter().enumerate() {
        if f.cycle.len() < 3 {
            return Err(format!("facet {fi} has fewer than three vertices"));
        }
        for (k, &i) in f.cycle.iter().enumerate() {
            if f.normal.dot(&v[i as usize]) != f.offset {
                return Err(format!("vertex {i} is off the plane of facet {fi}"));
            }
            let (a, b, c) = (
                &v[i as usize],
                &v[f.cycle[(k + 1) % f.cycle.len()] as usize],
                &v[f.cycle[(k + 2) % f.cycle.len()] as usize],
            );
            if det3_sign(&f.normal, &b.sub(a), &c.sub(b)) != Sign::Positive {
                return Err(format!("facet {fi} is not strictly convex at vertex {i}"));
            }
        }
        for (i, x) in v.iter().enumerate() {
            if f.normal.dot(x) > f.offset {
                return Err(format!("vertex {i} lies outside facet {fi}"));
            }
        }
    }
    Ok(())
}

/// Floating-point bounding box in true coordinates: the piece's integer box
/// ([`Polytope::integer_box`], rounded outward), widened past the rounding of its
/// integers to floats (a filter only), or everything when it does not fit.
fn piece_box(p: &Polytope) -> Aabb<f64> {
    let out = |x: i64, s: f64| x as f64 + s * ((x as f64).abs() * 1e-15 + 1.0);
    match p.integer_box() {
        Some(b) => Aabb {
            min: b.min.map(|x| out(x, -1.0)),
            max: b.max.map(|x| out(x, 1.0)),
        },
        None => Aabb {
            min: [f64::NEG_INFINITY; 3],
            max: [f64::INFINITY; 3],
        },
    }
}

#[derive(Clone, Copy)]
enum EdgeFrom {
    Side(usize),
    Facet(usize),
}

/// Whether triangle `t` meets the open interior of the piece with facets `n · x <= c`
/// (`facets`) in stored coordinates (true coordinates times `den`), by exact clipping.
fn triangle_meets_interior(s: &Solid, t: usize, facets: &[BigPlane], den: &Int) -> bool {
    let corners: Vec<[Int; 3]> = s.tris[t]
        .iter()
        .map(|&v| s.pts[v as usize].map(|c| Int::from(c) * den))
        .collect();
    let tn = s.planes[t].normal_ints();
    let tc = Int::from(s.planes[t].c) * den;
    let mut poly: Vec<(HPoint, EdgeFrom)> = (0..3)
        .map(|k| {
            (
                HPoint::from_big(corners[k].clone(), Int::ONE),
                EdgeFrom::Side(k),
            )
        })
        .collect();
    for (fi, plane) in facets.iter().enumerate() {
        let (n, c) = (&plane.n, &plane.c);
        let signs: Vec<Sign> = poly.iter().map(|(q, _)| plane.side(q)).collect();
        if !signs.contains(&Sign::Negative) {
            return false;
        }
        if !signs.contains(&Sign::Positive) {
            continue;
        }
        let m = poly.len();
        // Kept vertices and crossing points, tagged by where they come from.
        let mut out: Vec<(HPoint, bool, usize)> = Vec::with_capacity(m + 1);
        for i in 0..m {
            let j = (i + 1) % m;
            if signs[i] != Sign::Positive {
                out.push((poly[i].0.clone(), false, i));
            }
            if signs[i] * signs[j] == Sign::Negative {
                let x = match poly[i].1 {
                    EdgeFrom::Side(k) => on_segment_big(&corners[k], &corners[(k + 1) % 3], n, c),
                    EdgeFrom::Facet(g) => {
                        let gp = &facets[g];
                        meet_big(
                            &[tn.clone(), gp.n.clone(), n.clone()],
                            &[tc.clone(), gp.c.clone(), c.clone()],
                        )
                    }
                }
                .expect("a crossing edge meets the plane");
                out.push((x, true, i));
            }
        }
        // The edge after each output point: along the old edge it lies on, or along
        // this facet's plane where the polygon was cut.
        let k = out.len();
        let mut next: Vec<(HPoint, EdgeFrom)> = Vec::with_capacity(k);
        for a in 0..k {
            let (cross_a, i) = (out[a].1, out[a].2);
            let (cross_b, j) = (out[(a + 1) % k].1, out[(a + 1) % k].2);
            let along = match (cross_a, cross_b) {
                (false, false) => j == (i + 1) % m,
                (false, true) => j == i,
                (true, false) => j == (i + 1) % m,
                (true, true) => false,
            };
            let from = if along {
                poly[i].1
            } else {
                EdgeFrom::Facet(fi)
            };
            next.push((out[a].0.clone(), from));
        }
        let out = next;
        poly = out;
    }
    true
}

/// A conservative floating-point slab test: false only when the ray from `q` along `d`
/// misses the box by far more than any rounding error (a filter).
fn ray_may_hit(q: &[f64], d: &[i64; 3], b: &Aabb<f64>) -> bool {
    let (mut t0, mut t1) = (0f64, f64::INFINITY);
    for k in 0..3 {
        let slack = 1e-7 * (q[k].abs() + b.min[k].abs() + b.max[k].abs() + 1.0);
        let (lo, hi) = (b.min[k] - slack - q[k], b.max[k] + slack - q[k]);
        if d[k] == 0 {
            if lo > 0.0 || hi < 0.0 {
                return false;
            }
            continue;
        }
        let dk = d[k] as f64;
        let (a, c) = if dk > 0.0 {
            (lo / dk, hi / dk)
        } else {
            (hi / dk, lo / dk)
        };
        t0 = t0.max(a);
        t1 = t1.min(c);
    }
    t0 <= t1 * (1.0 + 1e-9) + 1e-9
}

/// Whether an interior point of `p` (its vertex average) is inside the solid, by the
/// parity of exact ray crossings; `None` if every tried ray was degenerate.
fn interior_point_inside(s: &Solid, boxes: &[Aabb<f64>], p: &Polytope) -> Option<bool> {
    let mut x = [Int::ZERO, Int::ZERO, Int::ZERO];
    for v in p.vertices() {
        for (k, xk) in x.iter_mut().enumerate() {
            *xk += v.get(k);
        }
    }
    let w = Int::from(p.vertices().len()) * p.den();
    let qf: Vec<f64> = x
        .iter()
        .map(|c| Rational::new(c.clone(), w.clone()).to_f64())
        .collect();
    let dirs: [[i64; 3]; 12] = [
        [1, 0, 0],
        [1, 2, 3],
        [-3, 7, 2],
        [5, -11, 13],
        [-17, -4, 9],
        [23, 29, -31],
        [2, -37, -41],
        [43, 3, 47],
        [-53, 59, 6],
        [61, -67, -71],
        [-73, 79, 83],
        [89, 97, -101],
    ];
    'dirs: for d in dirs {
        let dv = Vec3::from_i64(d);
        let mut hits = 0usize;
        for (t, tri) in s.tris.iter().enumerate() {
            if !ray_may_hit(&qf, &d, &boxes[t]) {
                continue;
            }
            let rel: Vec<Vec3> = tri
                .iter()
                .map(|&v| {
                    let a = s.pts[v as usize];
                    Vec3::from_ints([0, 1, 2].map(|k| Int::from(a[k]) * &w - &x[k]))
                })
                .collect();
            let n = Vec3::from_i128(s.planes[t].n);
            let na = int::sign_of(&n.dot(&rel[0]));
            let nd = int::sign_of(&n.dot(&dv));
            if nd == Sign::Zero {
                if na == Sign::Zero {
                    continue 'dirs;
                }
                continue;
            }
            if na != nd {
                continue; // behind the start, or the start is on the plane off the triangle
            }
            let e = [
                det3_sign(&rel[0], &rel[1], &dv),
                det3_sign(&rel[1], &rel[2], &dv),
                det3_sign(&rel[2], &rel[0], &dv),
            ];
            let pos = e.contains(&Sign::Positive);
            let neg = e.contains(&Sign::Negative);
            if pos && neg {
                continue;
            }
            if e.contains(&Sign::Zero) {
                continue 'dirs; // through an edge or a vertex
            }
            hits += 1;
        }
        return Some(hits % 2 == 1);
    }
    None
}
