//! Pruning of polygons inside another (they add nothing to a union), behind float
//! filters that reject most pairs before the exact test.

#[cfg(test)]
mod tests;

use apart_kernel::fvec::dot;
use apart_sphere::SphericalPolygon;
use rayon::prelude::*;

/// True when the open polygon `p` lies inside the open polygon `q` (then `p` adds
/// nothing to a union containing `q`). A pointed polygon or lune is the conic hull of its
/// corners, so it suffices that every corner lies in the closed `q`; a hemisphere lies in
/// another only when they are equal.
fn contained_in(p: &SphericalPolygon, q: &SphericalPolygon) -> bool {
    if p.normals().len() == 1 {
        return q.normals().len() == 1 && q.normals()[0] == p.normals()[0];
    }
    p.corners().all(|c| q.contains_closed(c))
}

/// A floating-point bounding cap of a pointed polygon (three or more sides): the unit
/// mean `centre` of its corners, which lies inside it, and the cosine of the largest
/// angle from the centre to a corner; the cap holds the whole polygon when that angle is
/// below 90°. Only a filter: it rejects a containment that the exact test would reject.
pub(crate) struct Cap {
    pub(crate) centre: [f64; 3],
    /// Cosine of the cap's radius widened by 1e-6 rad (far beyond float rounding);
    /// `None` when the cap is not convex (no bound).
    pub(crate) cos_radius: Option<f64>,
    /// The unit corner farthest from the centre (the first of equally far ones).
    pub(crate) far: [f64; 3],
}

/// The [`Cap`] of a pointed polygon; `None` for a hemisphere or a lune, or when its
/// corners have no mean direction.
pub(crate) fn cap_of(p: &SphericalPolygon) -> Option<Cap> {
    if p.normals().len() < 3 {
        return None;
    }
    let units: Vec<[f64; 3]> = p.corners().map(|c| c.unit_f64()).collect();
    cap_of_units(&units)
}

/// [`cap_of`] from the polygon's unit corners.
fn cap_of_units(units: &[[f64; 3]]) -> Option<Cap> {
    let sum = units
        .iter()
        .fold([0.0; 3], |s, u| [s[0] + u[0], s[1] + u[1], s[2] + u[2]]);
    let len = dot(sum, sum).sqrt();
    if len.is_nan() || len <= 1e-6 {
        return None;
    }
    let centre = sum.map(|c| c / len);
    let far = *units
        .iter()
        .min_by(|a, b| dot(**a, centre).total_cmp(&dot(**b, centre)))?;
    let min_cos = dot(far, centre).min(1.0).clamp(-1.0, 1.0);
    let radius = min_cos.acos() + 1e-6;
    Some(Cap {
        centre,
        cos_radius: (radius < 1.5).then(|| radius.cos()),
        far,
    })
}

/// Floating-point data of a polygon for the containment filter of [`prune_contained`]:
/// its bounding cap, unit corners and unit inward normals, and for a polygon whose
/// corners all lie in the open hemisphere of a point `h` (the cap's centre, or the sum of
/// the inward normals), the factors `1 / (h · c)` that map each corner `c` to the
/// gnomonic plane at `h`.
struct Approx {
    cap: Option<Cap>,
    corners: Vec<[f64; 3]>,
    normals: Vec<[f64; 3]>,
    gnomonic: Vec<f64>,
}

impl Approx {
    fn new(p: &SphericalPolygon) -> Approx {
        let corners: Vec<[f64; 3]> = p.corners().map(|c| c.unit_f64()).collect();
        let pointed = p.normals().len() >= 3;
        let cap = if pointed {
            cap_of_units(&corners)
        } else {
            None
        };
        let normals: Vec<[f64; 3]> = p.normals().iter().map(|n| n.unit_f64()).collect();
        // The gnomonic centre: the cap's, or else the sum of the inward normals, which
        // has a positive product with every point of a pointed polygon (the normals
        // span space, and each has a non-negative product with the point).
        let factors = |h: [f64; 3]| -> Option<Vec<f64>> {
            let f: Vec<f64> = corners.iter().map(|u| dot(*u, h)).collect();
            f.iter()
                .all(|&x| x > 1e-6)
                .then(|| f.iter().map(|x| 1.0 / x).collect())
        };
        let normals_centre = || {
            let sum = normals
                .iter()
                .fold([0.0; 3], |s, n| [s[0] + n[0], s[1] + n[1], s[2] + n[2]]);
            let len = dot(sum, sum).sqrt();
            (pointed && len > 1e-6).then(|| sum.map(|x| x / len))
        };
        let gnomonic = cap
            .as_ref()
            .and_then(|c| factors(c.centre))
            .or_else(|| normals_centre().and_then(factors))
            .unwrap_or_default();
        Approx {
            cap,
            corners,
            normals,
            gnomonic,
        }
    }

    /// False when `self` provably cannot lie in `q`: its cap's centre or its farthest
    /// corner, two of its points, lies outside `q`'s cap (widened far beyond rounding).
    fn may_lie_in_cap(&self, q: &Approx) -> bool {
        let (
            Some(cp),
            Some(Cap {
                centre,
                cos_radius: Some(c),
                ..
            }),
        ) = (&self.cap, &q.cap)
        else {
            return true;
        };
        dot(cp.centre, *centre) >= *c && dot(cp.far, *centre) >= *c
    }

    /// False when a corner of `self` lies clearly outside the closed `q` (a unit normal
    /// of `q` with a unit corner below −1e-12, far beyond rounding): then `self` is not
    /// in `q`. True says nothing. With the gnomonic factors the corner minimising each
    /// normal is found by a walk: `n·c / (h·c)` is linear on the gnomonic image, a convex
    /// polygon, so along the boundary it falls to its minimum and rises again, and the
    /// minimiser turns with `q`'s normals; a walk stopped early only weakens the filter.
    fn may_lie_in(&self, q: &Approx) -> bool {
        const MARGIN: f64 = -1e-12;
        let m = self.corners.len();
        if m == 0 || self.gnomonic.len() != m {
            return !q
                .normals
                .iter()
                .any(|n| self.corners.iter().any(|c| dot(*n, *c) < MARGIN));
        }
        let g = |n: &[f64; 3], k: usize| dot(*n, self.corners[k]) * self.gnomonic[k];
        let mut i = 0;
        for n in &q.normals {
            let mut gi = g(n, i);
            for step in [1, m - 1] {
                loop {
                    let j = (i + step) % m;
                    let gj = g(n, j);
                    if gj < gi {
                        (i, gi) = (j, gj);
                    } else {
                        break;
                    }
                }
            }
            if dot(*n, self.corners[i]) < MARGIN {
                return false;
            }
        }
        true
    }
}

/// The indices of the polygons not contained in another (one of several equal ones
/// kept), in the order the union builds them. Float filters (caps, then a walk of the
/// corners against the other's normals) reject most pairs before the exact test. With
/// `split` `Some(s)`, the polygons before `s` and those from `s` on are each pruned
/// already (none lies in another of its group), so only pairs across the two groups are
/// compared: the same indices, as no pair within a group is contained.
pub(crate) fn prune_contained(polygons: &[SphericalPolygon], split: Option<usize>) -> Vec<usize> {
    let approx: Vec<Approx> = polygons.par_iter().map(Approx::new).collect();
    let mut keep: Vec<usize> = Vec::with_capacity(polygons.len());
    // Larger polygons (fewer, more permissive constraints) first: hemispheres, lunes.
    let mut order: Vec<usize> = (0..polygons.len()).collect();
    order.sort_by_key(|&k| polygons[k].normals().len());
    let apart = |p: usize, q: usize| split.is_some_and(|s| (p < s) == (q < s));
    let inside = |p: usize, q: usize| {
        !apart(p, q)
            && approx[p].may_lie_in_cap(&approx[q])
            && approx[p].may_lie_in(&approx[q])
            && contained_in(&polygons[p], &polygons[q])
    };
    for k in order {
        if !keep.iter().any(|&q| inside(k, q)) {
            keep.retain(|&q| !inside(q, k));
            keep.push(k);
        }
    }
    keep
}

/// The polygons not contained in another, in the union's order: the same open union,
/// and the same answers to every blocking test (an open polygon inside another adds
/// no direction), with less to store.
pub(crate) fn pruned(polygons: Vec<SphericalPolygon>) -> Vec<SphericalPolygon> {
    pruned_split(polygons, None)
}

/// [`pruned`] of polygons in two groups each pruned already ([`prune_contained`]).
pub(super) fn pruned_split(
    polygons: Vec<SphericalPolygon>,
    split: Option<usize>,
) -> Vec<SphericalPolygon> {
    let keep = prune_contained(&polygons, split);
    let mut slots: Vec<Option<SphericalPolygon>> = polygons.into_iter().map(Some).collect();
    keep.into_iter()
        .map(|k| slots[k].take().expect("each index kept once"))
        .collect()
}
