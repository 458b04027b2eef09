//! Minor arcs of great circles.

use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::spherical::{arc_position, ArcPosition};
use apart_kernel::{Aabb, Sign, Vec3};

/// A minor arc (shorter than a half circle) of the great circle with normal `normal`,
/// running counter-clockwise around `normal` from `start` to `end`
/// (`det(normal, start, end) > 0`). The positive side of the arc's circle
/// (`normal · x > 0`) lies to the left when travelling from `start` to `end`, seen from
/// outside the sphere.
#[derive(Clone, Debug, PartialEq, Eq, Hash)]
pub struct Arc {
    /// Normal of the great circle (primitive).
    pub normal: Vec3,
    /// Start point (primitive).
    pub start: Vec3,
    /// End point (primitive).
    pub end: Vec3,
}

impl Arc {
    /// The minor arc from `start` to `end` on the great circle through them, oriented
    /// from `start` to `end`. `None` when the points coincide or are antipodal.
    pub fn between(start: &Vec3, end: &Vec3) -> Option<Arc> {
        let n = start.cross(end);
        if n.is_zero() {
            return None;
        }
        Some(Arc {
            normal: n.primitive(),
            start: start.primitive(),
            end: end.primitive(),
        })
    }

    /// The arc from `start` to `end` on the circle with normal `normal`, oriented so that
    /// it runs counter-clockwise around `normal`: the end points are swapped when needed.
    /// `None` when they are not distinct, non-antipodal points of that circle.
    pub fn on_circle(normal: &Vec3, a: &Vec3, b: &Vec3) -> Option<Arc> {
        match det3_sign(normal, a, b) {
            Sign::Positive => Some(Arc {
                normal: normal.primitive(),
                start: a.primitive(),
                end: b.primitive(),
            }),
            Sign::Negative => Some(Arc {
                normal: normal.primitive(),
                start: b.primitive(),
                end: a.primitive(),
            }),
            Sign::Zero => None,
        }
    }

    /// The arc cut exactly at the quarter points `normal × start`, `−start`, … into
    /// pieces of at most 90° each (the arc itself when it is no longer), in order. The
    /// cut works for any counter-clockwise run from `start` to `end` on the circle, even
    /// one of half a turn or more, so float filters and the minor-arc parametrisation
    /// `(1 − t) start + t end` can rely on short pieces.
    pub fn quarters(&self) -> Vec<Arc> {
        let n = &self.normal;
        let mut out = Vec::new();
        let mut cur = self.start.clone();
        for _ in 0..4 {
            let q = n.cross(&cur).primitive();
            // A point of the circle lies on the closed quarter from `cur` to `q` exactly
            // when it is on the non-negative side of both.
            if self.end != cur
                && dot_sign(&cur, &self.end) != Sign::Negative
                && dot_sign(&q, &self.end) != Sign::Negative
            {
                break;
            }
            out.push(Arc {
                normal: n.clone(),
                start: cur,
                end: q.clone(),
            });
            cur = q;
        }
        out.push(Arc {
            normal: n.clone(),
            start: cur,
            end: self.end.clone(),
        });
        out
    }

    /// The same set of points traversed the other way (normal negated).
    pub fn reversed(&self) -> Arc {
        Arc {
            normal: self.normal.neg(),
            start: self.end.clone(),
            end: self.start.clone(),
        }
    }

    /// The antipodal image `{-x}` of the arc (still counter-clockwise around the same
    /// normal; the positive side maps to the negative side).
    pub fn antipodal(&self) -> Arc {
        Arc {
            normal: self.normal.clone(),
            start: self.start.neg(),
            end: self.end.neg(),
        }
    }

    /// Where `p` lies relative to this closed arc (`None` when `p` is not on its circle).
    pub fn locate(&self, p: &Vec3) -> Option<ArcPosition> {
        if apart_kernel::predicates::dot_sign(&self.normal, p) != Sign::Zero {
            return None;
        }
        Some(arc_position(&self.normal, &self.start, &self.end, p))
    }

    /// An integer point strictly inside the arc (`start + end`, a positive combination).
    pub fn interior_point(&self) -> Vec3 {
        self.start.add(&self.end)
    }

    /// Conservative floating-point bounding box of the arc on the unit sphere, padded
    /// for rounding.
    pub fn bbox(&self) -> Aabb<f64> {
        let s = self.start.unit_f64();
        let e = self.end.unit_f64();
        // The arc lies within distance (1 - cos(θ/2)) <= |s - e|^2 / 2 (+ rounding) of its
        // chord, where θ is its angle; pad every side by that sagitta.
        let d2 = (s[0] - e[0]).powi(2) + (s[1] - e[1]).powi(2) + (s[2] - e[2]).powi(2);
        let pad = d2 * 0.5 + 1e-9;
        Aabb {
            min: [0, 1, 2].map(|k| s[k].min(e[k]) - pad),
            max: [0, 1, 2].map(|k| s[k].max(e[k]) + pad),
        }
    }
}

/// Conservative floating-point box of a single sphere point.
pub fn point_bbox(p: &Vec3) -> Aabb<f64> {
    let u = p.unit_f64();
    let pad = 1e-9;
    Aabb {
        min: u.map(|c| c - pad),
        max: u.map(|c| c + pad),
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn quarters_cut_any_run_into_pieces_of_at_most_90_degrees() {
        // Runs counter-clockwise around a tilted normal from one point to points all
        // around the circle (including exactly 90°, 180°, 270° and a full turn): the
        // pieces chain from start to end, each is at most 90°, and their angles add up
        // to the run's angle measured independently with atan2.
        let n = Vec3::new(1, 2, 3);
        let u = Vec3::new(3, 0, -1); // ⊥ n
        let v = n.cross(&u); // u rotated by 90° counter-clockwise
        let angle = |a: &Vec3, b: &Vec3| {
            let (x, y) = (
                a.unit_f64()
                    .iter()
                    .zip(b.unit_f64())
                    .map(|(p, q)| p * q)
                    .sum::<f64>(),
                det3_like(&n, a, b),
            );
            let t = y.atan2(x);
            if t < 0.0 {
                t + std::f64::consts::TAU
            } else {
                t
            }
        };
        fn det3_like(n: &Vec3, a: &Vec3, b: &Vec3) -> f64 {
            let (n, a, b) = (n.unit_f64(), a.unit_f64(), b.unit_f64());
            let c = [
                a[1] * b[2] - a[2] * b[1],
                a[2] * b[0] - a[0] * b[2],
                a[0] * b[1] - a[1] * b[0],
            ];
            n[0] * c[0] + n[1] * c[1] + n[2] * c[2]
        }
        let mut runs = 0;
        for (i, j) in [
            (1, 0),
            (1, 1),
            (0, 1),
            (-1, 1),
            (-1, 0),
            (-3, -1),
            (0, -1),
            (2, -1),
            (1, 0),
        ] {
            let end = Vec3::from_ints([0, 1, 2].map(|k| u.get(k) * i + v.get(k) * j)).primitive();
            let run = Arc {
                normal: n.clone(),
                start: u.clone(),
                end: end.clone(),
            };
            let want = if end == u {
                std::f64::consts::TAU
            } else {
                angle(&u, &end)
            };
            let pieces = run.quarters();
            assert_eq!(pieces.first().unwrap().start, u);
            assert_eq!(pieces.last().unwrap().end, end);
            for w in pieces.windows(2) {
                assert_eq!(w[0].end, w[1].start);
            }
            let mut total = 0.0;
            for p in &pieces {
                assert_ne!(p.start, p.end);
                assert_ne!(dot_sign(&p.start, &p.end), Sign::Negative, "{p:?}");
                assert_eq!(
                    det3_sign(&p.normal, &p.start, &p.end),
                    Sign::Positive,
                    "{p:?}"
                );
                total += angle(&p.start, &p.end);
            }
            assert!((total - want).abs() < 1e-9, "{total} vs {want}");
            runs += 1;
        }
        assert_eq!(runs, 9);
    }

    #[test]
    fn orientation_helpers() {
        let a = Arc::between(&Vec3::new(1, 0, 0), &Vec3::new(0, 2, 0)).unwrap();
        assert_eq!(a.normal, Vec3::new(0, 0, 1));
        assert_eq!(a.end, Vec3::new(0, 1, 0));
        let r = Arc::on_circle(
            &Vec3::new(0, 0, 1),
            &Vec3::new(0, 1, 0),
            &Vec3::new(1, 0, 0),
        )
        .unwrap();
        assert_eq!(r, a);
        assert_eq!(a.locate(&Vec3::new(1, 1, 0)), Some(ArcPosition::Interior));
        assert_eq!(a.locate(&Vec3::new(1, 1, 1)), None);
        let anti = a.antipodal();
        assert_eq!(
            anti.locate(&Vec3::new(-1, -1, 0)),
            Some(ArcPosition::Interior)
        );
        assert!(Arc::between(&Vec3::new(1, 0, 0), &Vec3::new(-3, 0, 0)).is_none());
    }

    #[test]
    fn bbox_contains_the_arc() {
        let a = Arc::between(&Vec3::new(1, 0, 0), &Vec3::new(-1, 1, 0)).unwrap();
        let b = a.bbox();
        // The arc passes through (0, 1, 0), outside the chord's box in y.
        assert!(b.max[1] >= 1.0);
    }
}

/// True when two closed minor arcs share at least one point. Exact.
pub fn arcs_intersect(a: &Arc, b: &Arc) -> bool {
    use apart_kernel::spherical::circle_intersection;
    match circle_intersection(&a.normal, &b.normal) {
        None => {
            // One circle: the arcs meet iff an end point of one lies on the other.
            [&b.start, &b.end]
                .iter()
                .any(|p| a.locate(p) != Some(ArcPosition::Outside))
                || [&a.start, &a.end]
                    .iter()
                    .any(|p| b.locate(p) != Some(ArcPosition::Outside))
        }
        Some(p) => [p.clone(), p.neg()].iter().any(|q| {
            arc_position(&a.normal, &a.start, &a.end, q) != ArcPosition::Outside
                && arc_position(&b.normal, &b.start, &b.end, q) != ArcPosition::Outside
        }),
    }
}

#[cfg(test)]
mod intersect_tests {
    use super::*;

    #[test]
    fn crossing_touching_disjoint() {
        let eq = Arc::between(&Vec3::new(1, -1, 0), &Vec3::new(1, 1, 0)).unwrap();
        let mer = Arc::between(&Vec3::new(1, 0, -1), &Vec3::new(1, 0, 1)).unwrap();
        assert!(arcs_intersect(&eq, &mer));
        let far = Arc::between(&Vec3::new(-1, 0, -1), &Vec3::new(-1, 0, 1)).unwrap();
        assert!(!arcs_intersect(&eq, &far));
        let touching = Arc::between(&Vec3::new(1, 1, 0), &Vec3::new(0, 1, 1)).unwrap();
        assert!(arcs_intersect(&eq, &touching));
        let overlap = Arc::between(&Vec3::new(2, 1, 0), &Vec3::new(0, 1, 0)).unwrap();
        assert!(arcs_intersect(&eq, &overlap));
        let beyond = Arc::between(&Vec3::new(1, 2, 0), &Vec3::new(0, 1, 0)).unwrap();
        assert!(!arcs_intersect(&eq, &beyond));
    }
}
