//! A direction deep inside a face of the motion space, and its angular clearance.
//!
//! Clearance is a measurement reported to the user, not a combinatorial decision, so it
//! is computed in floating point; the direction finally reported is an integer vector
//! checked exactly (it lies on no arc and has the face's blocking graph).

use apart_sphere::overlay::RegionArrangement;

type V3 = [f64; 3];

fn dot(a: &V3, b: &V3) -> f64 {
    a[0] * b[0] + a[1] * b[1] + a[2] * b[2]
}

fn cross(a: &V3, b: &V3) -> V3 {
    [
        a[1] * b[2] - a[2] * b[1],
        a[2] * b[0] - a[0] * b[2],
        a[0] * b[1] - a[1] * b[0],
    ]
}

fn normalize(a: V3) -> V3 {
    let n = dot(&a, &a).sqrt();
    [a[0] / n, a[1] / n, a[2] / n]
}

fn angle(a: &V3, b: &V3) -> f64 {
    // atan2 of |a x b| and a.b is accurate for small and large angles alike.
    let c = cross(a, b);
    dot(&c, &c).sqrt().atan2(dot(a, b))
}

/// A boundary arc in floating point: unit end points and unit normal (left = positive).
#[derive(Clone, Copy, Debug)]
pub struct FArc {
    a: V3,
    b: V3,
    n: V3,
}

impl FArc {
    /// Angular distance from unit point `p` to the closed arc.
    pub fn distance(&self, p: &V3) -> f64 {
        let s = dot(&self.n, p);
        let q = [
            p[0] - s * self.n[0],
            p[1] - s * self.n[1],
            p[2] - s * self.n[2],
        ];
        let within =
            dot(&cross(&self.a, &q), &self.n) >= 0.0 && dot(&cross(&q, &self.b), &self.n) >= 0.0;
        if within && dot(&q, &q) > 1e-30 {
            s.abs().min(1.0).asin()
        } else {
            angle(p, &self.a).min(angle(p, &self.b))
        }
    }
}

/// The real boundary of face `f` as floating-point arcs (face on their positive side),
/// plus isolated real points inside it.
pub fn face_boundary(arr: &RegionArrangement, f: u32) -> (Vec<FArc>, Vec<V3>) {
    let mut arcs = Vec::new();
    for lp in arr.boundary_loops(f) {
        for h in lp {
            let arc = arr.half_edge_arc(h);
            arcs.push(FArc {
                a: arc.start.unit_f64(),
                b: arc.end.unit_f64(),
                n: arc.normal.unit_f64(),
            });
        }
    }
    let mut points = Vec::new();
    for v in arr.vertices() {
        if v.structural || v.around.is_empty() {
            continue;
        }
        let real = v
            .around
            .iter()
            .any(|&h| !arr.edges()[(h / 2) as usize].structural);
        if !real && arr.face_of(v.around[0]) == f {
            points.push(v.point.unit_f64());
        }
    }
    (arcs, points)
}

/// Clearance of unit point `p`: its angular distance to the nearest boundary element.
pub fn clearance(p: &V3, arcs: &[FArc], points: &[V3]) -> f64 {
    let mut c = std::f64::consts::PI;
    for a in arcs {
        c = c.min(a.distance(p));
    }
    for q in points {
        c = c.min(angle(p, q));
    }
    c
}

/// Points just inside the face next to some of its boundary arcs (at most `max`), each
/// with its clearance, best first.
pub fn starting_points(arcs: &[FArc], points: &[V3], max: usize) -> Vec<(V3, f64)> {
    let mut out = Vec::new();
    let stride = (arcs.len() / max.max(1)).max(1);
    for (k, arc) in arcs.iter().enumerate().step_by(stride) {
        let m = normalize([
            arc.a[0] + arc.b[0],
            arc.a[1] + arc.b[1],
            arc.a[2] + arc.b[2],
        ]);
        let others = arcs
            .iter()
            .enumerate()
            .filter(|(j, _)| *j != k)
            .map(|(_, o)| o.distance(&m))
            .chain(points.iter().map(|q| angle(&m, q)))
            .fold(angle(&arc.a, &arc.b) / 2.0, f64::min);
        let delta = 0.5 * others;
        if delta <= 1e-12 {
            continue;
        }
        let p = normalize([
            m[0] + delta * arc.n[0],
            m[1] + delta * arc.n[1],
            m[2] + delta * arc.n[2],
        ]);
        out.push((p, clearance(&p, arcs, points)));
    }
    out.sort_by(|a, b| b.1.total_cmp(&a.1));
    out
}

/// Moves `p` uphill in clearance. Every step is shorter than the current clearance, so
/// the path never meets the boundary and `p` stays in the face.
pub fn climb(mut p: V3, arcs: &[FArc], points: &[V3]) -> (V3, f64) {
    let mut c = clearance(&p, arcs, points);
    let mut step = 0.5 * c;
    let mut iterations = 0;
    while step > 1e-9 && iterations < 400 {
        iterations += 1;
        // Tangent basis at p.
        let helper = if p[0].abs() < 0.9 {
            [1.0, 0.0, 0.0]
        } else {
            [0.0, 1.0, 0.0]
        };
        let u = normalize(cross(&p, &helper));
        let w = cross(&p, &u);
        let mut best: Option<(V3, f64)> = None;
        for k in 0..16 {
            let t = k as f64 * std::f64::consts::PI / 8.0;
            let (s, co) = t.sin_cos();
            let d = [
                u[0] * co + w[0] * s,
                u[1] * co + w[1] * s,
                u[2] * co + w[2] * s,
            ];
            let q = normalize([p[0] + step * d[0], p[1] + step * d[1], p[2] + step * d[2]]);
            let cq = clearance(&q, arcs, points);
            if cq > c && best.is_none_or(|(_, bc)| cq > bc) {
                best = Some((q, cq));
            }
        }
        match best {
            Some((q, cq)) => {
                p = q;
                c = cq;
                step = step.min(0.9 * c);
            }
            None => step *= 0.5,
        }
    }
    (p, c)
}
