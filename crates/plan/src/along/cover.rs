//! The union of the open tangent cones at a direction of the pairs free there, and
//! from it the kind of motion-space cell the direction lies in.

use crate::motion_space::CellKind;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Sign, Vec3};

/// Orders directions `s`, `t` (square to `d`, not zero) by their counter-clockwise angle
/// around `d` from `r`, in `[0, 2π)`: the half turn from `r`, then the one from `−r`, in
/// each a direction before those counter-clockwise from it.
fn around(d: &Vec3, r: &Vec3, s: &Vec3, t: &Vec3) -> std::cmp::Ordering {
    use std::cmp::Ordering::{Equal, Greater, Less};
    let half = |v: &Vec3| match det3_sign(d, r, v) {
        Sign::Positive => 0,
        Sign::Negative => 1,
        Sign::Zero => usize::from(dot_sign(r, v) != Sign::Positive),
    };
    half(s)
        .cmp(&half(t))
        .then_with(|| match det3_sign(d, s, t) {
            Sign::Positive => Less,
            Sign::Negative => Greater,
            Sign::Zero => Equal,
        })
}

/// A direction strictly inside the open sector from ray `a` counter-clockwise to ray `b`
/// around `d` (at most a half turn): their sum, or the perpendicular on that side for
/// a half turn.
fn inside(d: &Vec3, a: &Vec3, b: &Vec3) -> Vec3 {
    match det3_sign(d, a, b) {
        Sign::Positive => a.add(b),
        _ => d.cross(a),
    }
}

/// True when `y` lies in the open cone `{y : c · y > 0 for every c}`.
fn in_cone(cone: &[Vec3], y: &Vec3) -> bool {
    cone.iter().all(|c| dot_sign(c, y) == Sign::Positive)
}

/// The union of open tangent cones at `d` of the maps free at `d`, and with it the kind
/// of motion-space cell `d` lies in. The other maps (blocked at `d`, or with no polygon
/// whose closure holds `d`) keep their status all around `d`, so only these decide
/// which statuses near `d` equal `d`'s (all of them free). Near `d` the motion space is
/// the arrangement of the cones' side lines through `d` (each a pair of rays): `d` is in
/// a face when a sector between consecutive rays is outside the union (a face beside
/// `d` has its status), else on an edge when a ray is (an arc from `d` with its status,
/// and no such face), else a vertex: what [`crate::MotionSpace::locate`] finds in the
/// overlay of the pairs' regions (a line that is no arc of the overlay has the status
/// of the sectors on both sides, so it decides nothing), without building it.
///
/// Kept as the rays around `d` (primitive, square to `d`) counter-clockwise from the
/// first, each with whether the union holds it and the open sector after it: a cone
/// added splits the sectors its rays fall in (the pieces inherit their sector's
/// status, as the earlier cones' sides are elsewhere) and covers what it holds.
pub(super) struct Cover {
    d: Vec3,
    rays: Vec<(Vec3, bool, bool)>,
    /// Normals of the half-planes in the union.
    pub(super) halves: rustc_hash::FxHashSet<Vec3>,
}

impl Cover {
    pub(super) fn new(d: &Vec3) -> Cover {
        Cover {
            d: d.clone(),
            rays: Vec::new(),
            halves: Default::default(),
        }
    }

    /// The open sector after ray `k`, as a direction inside it.
    fn sector(&self, k: usize) -> Vec3 {
        let b = &self.rays[(k + 1) % self.rays.len()].0;
        inside(&self.d, &self.rays[k].0, b)
    }

    /// True when the union holds every direction around `d`.
    pub(super) fn is_everything(&self) -> bool {
        !self.rays.is_empty() && self.rays.iter().all(|&(_, r, s)| r && s)
    }

    /// The kind of cell `d` lies in.
    pub(super) fn kind(&self) -> CellKind {
        if self.rays.is_empty() || self.rays.iter().any(|r| !r.2) {
            CellKind::Face
        } else if self.rays.iter().any(|r| !r.1) {
            CellKind::Edge
        } else {
            CellKind::Vertex
        }
    }

    /// Adds the open cone of the normals `cone` (each square to `d`).
    pub(super) fn add(&mut self, cone: &[Vec3]) {
        for c in cone {
            let t = c.cross(&self.d).primitive();
            for r in [t.neg(), t] {
                if self.rays.iter().any(|(q, _, _)| *q == r) {
                    continue;
                }
                let Some(r0) = self.rays.first().map(|q| q.0.clone()) else {
                    self.rays.push((r, false, false));
                    continue;
                };
                let at = self.rays[1..]
                    .iter()
                    .position(|(q, _, _)| around(&self.d, &r0, &r, q).is_lt())
                    .map_or(self.rays.len(), |p| p + 1);
                let status = self.rays[at - 1].2;
                self.rays.insert(at, (r, status, status));
            }
        }
        for k in 0..self.rays.len() {
            if !self.rays[k].1 && in_cone(cone, &self.rays[k].0) {
                self.rays[k].1 = true;
            }
            if !self.rays[k].2 && in_cone(cone, &self.sector(k)) {
                self.rays[k].2 = true;
            }
        }
        if let [c] = cone {
            self.halves.insert(c.primitive());
        }
    }

    /// True when the union holds the open cone of the normals `cone` (each square to
    /// `d`; none: every direction): no ray or sector outside the union meets it. A
    /// sector is cut by the cone's rays inside it into pieces each inside the cone or
    /// outside.
    pub(super) fn holds(&self, cone: &[Vec3]) -> bool {
        if self.rays.is_empty() {
            return false;
        }
        let n = self.rays.len();
        (0..n).all(|k| {
            let (a, ray, sector) = (&self.rays[k].0, self.rays[k].1, self.rays[k].2);
            if !ray && in_cone(cone, a) {
                return false;
            }
            if sector {
                return true;
            }
            let b = &self.rays[(k + 1) % n].0;
            let mut cuts: Vec<Vec3> = cone
                .iter()
                .flat_map(|c| {
                    let t = c.cross(&self.d).primitive();
                    [t.neg(), t]
                })
                .filter(|t| t != a && around(&self.d, a, t, b).is_lt())
                .collect();
            cuts.sort_by(|s, t| around(&self.d, a, s, t));
            cuts.dedup();
            let mut from = a;
            for to in cuts.iter().chain([b]) {
                if in_cone(cone, &inside(&self.d, from, to)) {
                    return false;
                }
                from = to;
            }
            true
        })
    }
}
