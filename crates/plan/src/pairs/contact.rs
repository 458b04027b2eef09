//! Contact cones of touching pieces from the small sum of their face neighbourhoods,
//! the same polygon as the full sum's projection.

use super::{PairPolygon, PieceInfo};
use apart_kernel::int::cmp_fractions;
use apart_kernel::{Int, Vec3};
use apart_minkowski::{project, sum_prepared, Projection, Summand};
use apart_pieces::Polytope;
use apart_sphere::SphericalPolygon;
use std::cmp::Ordering;

/// Pieces with at most this many vertices are summed whole in [`contact_polygon`]: the
/// sum of two such pieces (prepared once per piece) costs less than the exact hull of a
/// neighbourhood (for a piece cut out of a tessellated part, of vertices over a long
/// common denominator: 8 here cost the 2 x 2 rack 8 % more instructions than 64), and
/// has the same tangent cone at the origin. Many-sided pieces (a shaft's 1,250 sides)
/// still take the neighbourhood.
const SMALL_PIECE: usize = 64;

/// [`face_neighbourhood`], or the whole piece (`Some(None)`) when it is small.
fn neighbourhood(p: &Polytope, face: &[u32]) -> Option<Option<Polytope>> {
    if p.vertices().len() <= SMALL_PIECE && !face.is_empty() {
        return Some(None);
    }
    face_neighbourhood(p, face)
}

/// The hull of the vertices `face` of `p` and their neighbours: `Some(None)` when that
/// is all of `p`.
pub(super) fn face_neighbourhood(p: &Polytope, face: &[u32]) -> Option<Option<Polytope>> {
    if face.is_empty() {
        return None;
    }
    let mut keep = vec![false; p.vertices().len()];
    for &v in face {
        keep[v as usize] = true;
    }
    let mut with = keep.clone();
    for e in p.edges() {
        let [u, v] = e.ends;
        if keep[u as usize] || keep[v as usize] {
            with[u as usize] = true;
            with[v as usize] = true;
        }
    }
    let pts: Vec<Vec3> = (0..p.vertices().len())
        .filter(|&k| with[k])
        .map(|k| p.vertices()[k].clone())
        .collect();
    if pts.len() == p.vertices().len() {
        return Some(None);
    }
    Polytope::hull(&pts)
        .ok()
        .map(|h| Some(h.with_den(p.den().clone())))
}

/// The support face of `p` along `n` as a boundary cycle (a facet's cycle, an edge's two
/// ends, or one vertex), as stored integers.
fn support_face(p: &Polytope, n: &Vec3) -> Vec<u32> {
    let (_, ids) = p.support(n);
    if ids.len() >= 3 {
        let n = n.primitive();
        if let Some(f) = p.facets().iter().find(|f| f.normal == n) {
            return f.cycle.clone();
        }
    }
    ids
}

fn points(p: &Polytope, ids: &[u32]) -> Vec<Vec3> {
    ids.iter()
        .map(|&v| p.vertices()[v as usize].clone())
        .collect()
}

/// The vertices of the edges of the facet cycle `ids` of `p` that are not strictly
/// separated, in their common plane (normal `n`), from the hull of `other` (denominator
/// `dother`): every common point of the facet and `other` lies on one of these edges
/// when none lies in the facet's relative interior. All of `ids` when it has at most
/// eight vertices (nothing to gain).
fn edges_meeting(p: &Polytope, ids: &[u32], other: &[Vec3], dother: &Int, n: &Vec3) -> Vec<u32> {
    let k = ids.len();
    if k <= 8 {
        return ids.to_vec();
    }
    let dp = p.den();
    let v = |i: usize| &p.vertices()[ids[i % k] as usize];
    // Strictly on the far side of a line g·x = h (the side without `own`).
    let beyond = |g: &Vec3, h: &Int, own: Ordering, pts: &[Vec3], dp_: &Int, dh: &Int| {
        pts.iter()
            .all(|w| cmp_fractions(&g.dot(w), dp_, h, dh) == own.reverse())
    };
    // Exact boxes: an edge whose box misses the other set's box cannot meet it.
    let lo = [0, 1, 2].map(|t| other.iter().map(|w| w.get(t)).min().unwrap());
    let hi = [0, 1, 2].map(|t| other.iter().map(|w| w.get(t)).max().unwrap());
    let misses = |u: &Vec3, w: &Vec3| {
        (0..3).any(|t| {
            let (a, b) = (u.get(t), w.get(t));
            let (mn, mx) = if a < b { (a, b) } else { (b, a) };
            cmp_fractions(&mx, dp, &lo[t], dother) == Ordering::Less
                || cmp_fractions(&mn, dp, &hi[t], dother) == Ordering::Greater
        })
    };
    let mut keep = vec![false; k];
    for e in 0..k {
        let (u, w) = (v(e), v(e + 1));
        if misses(u, w) {
            continue;
        }
        let seg = [u.clone(), w.clone()];
        // The segment's line (either side), then the other hull's edge lines.
        let g = n.cross(&w.sub(u));
        let h = g.dot(u);
        let mut apart = beyond(&g, &h, Ordering::Less, other, dother, dp)
            || beyond(&g, &h, Ordering::Greater, other, dother, dp);
        let m = other.len();
        if !apart && m >= 2 {
            for i in 0..if m == 2 { 1 } else { m } {
                let (x, y) = (&other[i], &other[(i + 1) % m]);
                let g = n.cross(&y.sub(x));
                let h = g.dot(x);
                let own = other
                    .iter()
                    .map(|z| g.dot(z).cmp(&h))
                    .find(|o| *o != Ordering::Equal);
                let sides: &[Ordering] = match own {
                    Some(Ordering::Less) => &[Ordering::Less],
                    Some(_) => &[Ordering::Greater],
                    None => &[Ordering::Less, Ordering::Greater],
                };
                if sides.iter().any(|&s| beyond(&g, &h, s, &seg, dp, dother)) {
                    apart = true;
                    break;
                }
            }
        }
        if !apart {
            keep[e] = true;
            keep[(e + 1) % k] = true;
        }
    }
    (0..k).filter(|&i| keep[i]).map(|i| ids[i]).collect()
}

/// Whether the relative interior of the facet `fa` (a cycle of at least three points of
/// the plane with normal `n`, stored with denominator `da`) meets the convex hull of the
/// points `fb` of the same plane (denominator `db`). They are disjoint exactly when a line
/// of the plane separates them weakly, and then (two-dimensional separating axes) the
/// line through an edge of `fa` or of `fb` does.
fn approx(x: &Int) -> f64 {
    apart_kernel::int::to_f64(x)
}

fn meets_relative_interior(fa: &[Vec3], da: &Int, fb: &[Vec3], db: &Int, n: &Vec3) -> bool {
    let separated = |cycle: &[Vec3], dc: &Int, other: &[Vec3], dother: &Int| -> bool {
        let k = cycle.len();
        let edges = if k == 2 { 1 } else { k };
        // Edges near the other set first (the separating one, when there is one, is
        // usually there); the order changes nothing but the time.
        let (fc, fo) = (approx(dc), approx(dother));
        let target = other[0].approx().map(|t| t / fo);
        let dist = |e: usize| {
            let u = cycle[e].approx();
            (0..3).map(|t| (u[t] / fc - target[t]).powi(2)).sum::<f64>()
        };
        let order: Vec<usize> = if edges > 8 {
            // Each distance once (a many-sided cap has a thousand edges).
            let mut by: Vec<(f64, usize)> = (0..edges).map(|e| (dist(e), e)).collect();
            by.sort_by(|x, y| x.0.total_cmp(&y.0));
            by.into_iter().map(|(_, e)| e).collect()
        } else {
            (0..edges).collect()
        };
        order.into_iter().any(|e| {
            let (u, v) = (&cycle[e], &cycle[(e + 1) % k]);
            let g = n.cross(&v.sub(u));
            let h = g.dot(u);
            // The side of the cycle (a third point, when there is one), then every other
            // point weakly on the far side.
            let own = cycle
                .iter()
                .map(|w| g.dot(w).cmp(&h))
                .find(|o| *o != Ordering::Equal);
            let all_one_side = |want: Ordering| {
                other.iter().all(|w| {
                    let o = cmp_fractions(&g.dot(w), dother, &h, dc);
                    o == Ordering::Equal || o == want
                })
            };
            match own {
                Some(s) => all_one_side(s.reverse()),
                // A segment: either side of its line.
                None => all_one_side(Ordering::Less) || all_one_side(Ordering::Greater),
            }
        })
    };
    let apart = separated(fa, da, fb, db) || (fb.len() >= 2 && separated(fb, db, fa, da));
    !apart
}

/// Whether the centroid of the points `pts` (denominator `dp`), which lie in the plane of
/// the facet of `p` with outward normal `n`, lies in that facet's relative interior:
/// strictly inside every other facet's half-space. A cheap sufficient test for
/// [`meets_relative_interior`].
///
/// A facet whose plane the float centroid clears by more than the shadow's error bound
/// is decided without exact arithmetic (a many-sided piece has many such facets).
fn centroid_in_relative_interior(p: &Polytope, n: &Vec3, pts: &[Vec3], dp: &Int) -> bool {
    let n = n.primitive();
    let sum = pts.iter().skip(1).fold(pts[0].clone(), |s, w| s.add(w));
    // p's stored integers are den_p times coordinates; the centroid is sum / (k dp).
    let scale = Int::from(pts.len() as i64) * dp;
    let c = sum.scale(p.den());
    // The centroid in floats (each coordinate within a relative 2^-50).
    let filter = p.shadow().and_then(|s| {
        let d = approx(&scale) * approx(p.den());
        let x = [0, 1, 2].map(|k| approx(&c.get(k)) / d);
        let m = x.iter().fold(s.magnitude, |m, v| m.max(v.abs()));
        (d.is_finite() && d > 0.0 && x.iter().all(|v| v.is_finite())).then_some((
            s,
            x,
            m * 2f64.powi(-44),
        ))
    });
    p.facets().iter().enumerate().all(|(i, f)| {
        if let Some((s, x, err)) = &filter {
            let u = &s.facet_units[i];
            if x[0] * u[0] + x[1] * u[1] + x[2] * u[2] < s.facet_levels[i] - 2.0 * err {
                return true; // clearly strictly inside (and not the facet with normal n)
            }
        }
        f.normal == n || f.normal.dot(&c) < &f.offset * &scale
    })
}

/// The contact cone of two pieces touching across the plane with normal `n` (from `a` to
/// `b`); `None` when they do not touch (or a neighbourhood is degenerate): the caller
/// then sums the whole pieces.
///
/// When a facet of either piece in that plane meets the other piece's face in its
/// relative interior, the normal cone `N_b(c) ∩ −N_a(c)` at such a common point `c` is
/// the ray of `−n`, and the cone is the hemisphere `{n·x >= 0}` (what the full sum's
/// single facet through the origin projects to). Otherwise the contact lies on the
/// faces' boundaries and the small sum of the face neighbourhoods gives the cone (of a
/// facet with many vertices, only the edges that reach the other face: every common
/// point lies on one of them, and the tangent cones there are kept).
///
/// A neighbourhood that is the whole piece is summed through the piece's prepared
/// summand in `ia` or `ib` (made once per piece, shared by all its pairs).
pub(crate) fn contact_polygon(
    a: &Polytope,
    ia: &PieceInfo,
    b: &Polytope,
    ib: &PieceInfo,
    n: &Vec3,
) -> Option<Result<PairPolygon, String>> {
    let (ida, idb) = (support_face(a, n), support_face(b, &n.neg()));
    let (fa, fb) = (points(a, &ida), points(b, &idb));
    let face = |f: &[Vec3]| f.len() >= 3;
    if (face(&fa) && centroid_in_relative_interior(a, n, &fb, b.den()))
        || (face(&fb) && centroid_in_relative_interior(b, &n.neg(), &fa, a.den()))
        || (face(&fa) && meets_relative_interior(&fa, a.den(), &fb, b.den(), n))
        || (face(&fb) && meets_relative_interior(&fb, b.den(), &fa, a.den(), n))
    {
        return Some(Ok(PairPolygon::Polygon(
            SphericalPolygon::hemisphere(n),
            true,
        )));
    }
    // The contact lies on the faces' boundaries: only the edges of a large facet that
    // reach the other face matter (their neighbourhoods keep the tangent cones there).
    let ida = if face(&fa) {
        edges_meeting(a, &ida, &fb, b.den(), n)
    } else {
        ida
    };
    let idb = if face(&fb) {
        edges_meeting(b, &idb, &fa, a.den(), n)
    } else {
        idb
    };
    let a2 = neighbourhood(a, &ida)?.map(|a2| Summand::new(a2.reflected()));
    let b2 = neighbourhood(b, &idb)?.map(Summand::new);
    let (sa, sb) = (
        a2.as_ref().unwrap_or_else(|| ia.reflected(a)),
        b2.as_ref().unwrap_or_else(|| ib.fixed(b)),
    );
    let m = match sum_prepared(sb, sa) {
        Ok(m) => m,
        Err(e) => return Some(Err(format!("Minkowski sum: {e}"))),
    };
    if m.facets().iter().any(|f| f.offset < Int::ZERO) {
        return None; // the origin lies outside: the pieces do not touch
    }
    Some(match project(&m) {
        Ok(Projection::Polygon(p)) => Ok(PairPolygon::Polygon(p, true)),
        Ok(Projection::Everything) => Ok(PairPolygon::Overlap),
        Err(e) => Err(format!("projection: {e}")),
    })
}
