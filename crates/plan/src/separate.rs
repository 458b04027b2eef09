//! Two-part separation: every direction along which part `a` leaves part `b`.
//!
//! The free set is the complement of the open blocked set `Q_ab`: open spherical regions
//! (faces, with their exact boundary arcs), sliding arcs (free arcs between blocked
//! regions) and isolated directions (free points inside blocked regions).

use crate::clearance::{isolated_points, to_angle, FArc};
use crate::regions::BlockingRegions;
use apart_kernel::fvec::{cross, dot};
use apart_kernel::Vec3;
use apart_sphere::overlay::{cell_statuses, RegionArrangement};
use apart_sphere::region::arrangement_of;
use apart_sphere::{Arc, BitSet, FaceId};

/// An open region of separating directions.
#[derive(Clone, Debug)]
pub struct FreeFace {
    /// Boundary loops, each a cycle of exact arcs with the region on their left.
    pub loops: Vec<Vec<Arc>>,
    /// Area in steradians (floating point, by Gauss–Bonnet).
    pub area: f64,
    /// An exact direction deep inside.
    pub direction: Vec3,
    /// Its angular distance to the region's boundary, in degrees.
    pub clearance_deg: f64,
}

/// All directions along which `a` separates from `b`.
#[derive(Clone, Debug)]
pub struct Separation {
    /// The moving part.
    pub a: usize,
    /// The fixed part.
    pub b: usize,
    /// Open regions of free directions.
    pub faces: Vec<FreeFace>,
    /// Free arcs between blocked regions (sliding motions), as chains of arcs.
    pub sliding: Vec<Arc>,
    /// Free directions isolated inside blocked regions.
    pub isolated: Vec<Vec3>,
}

impl Separation {
    /// The fraction of the sphere of directions that separates (faces only: arcs and
    /// points have no area).
    pub fn area_fraction(&self) -> f64 {
        // (A sum of no floats is -0.0.)
        0.0 + self.faces.iter().map(|f| f.area).sum::<f64>() / (4.0 * std::f64::consts::PI)
    }

    /// The direction with the largest clearance and that clearance (degrees), if any
    /// region is free; otherwise a sliding or isolated direction with clearance 0.
    pub fn best(&self) -> Option<(Vec3, f64)> {
        if let Some(f) = self
            .faces
            .iter()
            .max_by(|x, y| x.clearance_deg.total_cmp(&y.clearance_deg))
        {
            return Some((f.direction.clone(), f.clearance_deg));
        }
        if let Some(a) = self.sliding.first() {
            return Some((a.interior_point().primitive(), 0.0));
        }
        self.isolated.first().map(|d| (d.clone(), 0.0))
    }
}

/// Computes the separating directions of part `a` (moving) from part `b`.
pub fn separate(regions: &BlockingRegions, a: usize, b: usize) -> Separation {
    let pair = regions.pair(a, b);
    let map = if a < b {
        pair.region.clone()
    } else {
        pair.region.antipodal()
    };
    let blocks = |x: &Vec3, y: &Vec3| {
        if a < b {
            pair.blocks_perturbed(x, y)
        } else {
            pair.blocks_perturbed(&x.neg(), &y.neg())
        }
    };
    let arr = arrangement_of(&map);
    let st = cell_statuses(&arr, 1, |x, y| {
        let mut s = BitSet::new(1);
        s.set(0, blocks(x, y));
        s
    });
    let blocked = |s: &BitSet| s.get(0);
    let isolated_pts = isolated_points(&arr);
    let mut faces = Vec::new();
    for (f, points) in isolated_pts.iter().enumerate() {
        if blocked(&st.faces[f]) {
            continue;
        }
        let loops: Vec<Vec<Arc>> = arr
            .boundary_loops(FaceId::new(f))
            .into_iter()
            .map(|lp| lp.into_iter().map(|h| arr.half_edge_arc(h)).collect())
            .collect();
        let area = face_area(&loops);
        let (direction, clearance) = deep_direction(&arr, FaceId::new(f), points, &|d| {
            !blocks(d, &Vec3::ZERO) && on_no_arc(&arr, d)
        });
        faces.push(FreeFace {
            loops,
            area,
            direction,
            clearance_deg: clearance.to_degrees(),
        });
    }
    let mut sliding = Vec::new();
    for e in arr.edge_ids() {
        if arr.edge(e).structural || blocked(&st.edges[e.index()]) {
            continue;
        }
        let (l, r) = (arr.cycle(e.forward()), arr.cycle(e.backward()));
        if blocked(&st.cycles[l.index()]) && blocked(&st.cycles[r.index()]) {
            sliding.push(arr.edge_arc(e));
        }
    }
    let mut isolated = Vec::new();
    for (v, vert) in arr.vertices().iter().enumerate() {
        if vert.structural || blocked(&st.vertices[v]) {
            continue;
        }
        let all_blocked = vert.around.iter().all(|&h| {
            let e = h.edge();
            (arr.edge(e).structural || blocked(&st.edges[e.index()]))
                && blocked(&st.cycles[arr.cycle(h).index()])
        });
        if all_blocked {
            isolated.push(vert.point.clone());
        }
    }
    Separation {
        a,
        b,
        faces,
        sliding,
        isolated,
    }
}

fn on_no_arc(arr: &RegionArrangement, d: &Vec3) -> bool {
    let p = d.primitive();
    arr.vertices().iter().all(|v| v.point != p)
        && arr.edge_ids().all(|e| {
            arr.edge(e).structural
                || arr
                    .edge_arc(e)
                    .locate(&p)
                    .is_none_or(|x| x == apart_kernel::spherical::ArcPosition::Outside)
        })
}

/// A deep exact direction of face `f` and its clearance (radians); `ok` verifies a
/// candidate exactly.
fn deep_direction(
    arr: &RegionArrangement,
    f: FaceId,
    points: &[[f64; 3]],
    ok: &dyn Fn(&Vec3) -> bool,
) -> (Vec3, f64) {
    let arcs: Vec<FArc> = arr
        .boundary_loops(f)
        .into_iter()
        .flatten()
        .map(|h| FArc::of(&arr.half_edge_arc(h)))
        .collect();
    if let Some(found) = crate::clearance::deep_direction(&arcs, points, ok) {
        return found;
    }
    // Exact fallback next to a boundary edge (see MotionSpace::face_sample).
    let h = arr
        .boundary_loops(f)
        .into_iter()
        .flatten()
        .next()
        .expect("boundary");
    let arc = arr.half_edge_arc(h);
    let m = arc.interior_point();
    let mut k = apart_kernel::Int::from(1u64 << 20);
    loop {
        let d = m.scale(&k).add(&arc.normal).primitive();
        if ok(&d) {
            let u = d.unit_f64();
            let c2 = arcs.iter().map(|a| a.distance2(&u)).fold(4.0, f64::min);
            return (d, to_angle(c2));
        }
        k = &k * apart_kernel::Int::from(1u64 << 16);
    }
}

/// Area of a spherical region from its boundary loops (Gauss–Bonnet):
/// `area = 2π(2 − loops) − Σ turning angles`, the turning angle at each corner being the
/// signed change of direction (positive when turning left, towards the region).
pub fn face_area(loops: &[Vec<Arc>]) -> f64 {
    use std::f64::consts::PI;
    if loops.is_empty() {
        return 4.0 * PI;
    }
    let mut turning = 0.0;
    for lp in loops {
        for (k, arc) in lp.iter().enumerate() {
            let next = &lp[(k + 1) % lp.len()];
            // Tangents at the shared corner v: incoming n1 × v, outgoing n2 × v.
            let v = arc.end.unit_f64();
            let t1 = cross(arc.normal.unit_f64(), v);
            let t2 = cross(next.normal.unit_f64(), v);
            let sin = dot(v, cross(t1, t2));
            let cos = dot(t1, t2);
            turning += sin.atan2(cos);
        }
    }
    2.0 * PI * (2.0 - loops.len() as f64) - turning
}
