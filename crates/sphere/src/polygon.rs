//! Spherically convex polygons: the central projections of convex sums.

use crate::arc::Arc;
use apart_kernel::predicates::{det3_sign, dot_sign};
use apart_kernel::{Sign, Vec3};

/// A closed spherically convex polygon, given both ways: by its *inward* great-circle
/// normals (the polygon is `{x : q · x >= 0 for every q}`, its interior the same with
/// strict inequalities) and by its boundary as a cycle of minor arcs, each running
/// counter-clockwise around its inward normal (interior on the left). A hemisphere has one
/// normal and a lune two; their boundaries are split into minor arcs by extra points.
#[derive(Clone, Debug)]
pub struct SphericalPolygon {
    normals: Vec<Vec3>,
    boundary: Vec<Arc>,
}

/// What went wrong assembling a polygon from its arcs (an internal inconsistency).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct PolygonError(pub String);

impl std::fmt::Display for PolygonError {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "inconsistent spherical polygon: {}", self.0)
    }
}

impl std::error::Error for PolygonError {}

impl SphericalPolygon {
    /// The closed hemisphere `{q · x >= 0}` (boundary split into four quarter arcs).
    pub fn hemisphere(q: &Vec3) -> SphericalPolygon {
        let q = q.primitive();
        let u = perpendicular(&q);
        let v = q.cross(&u).primitive();
        let pts = [u.clone(), v.clone(), u.neg(), v.neg()];
        let boundary = (0..4)
            .map(|i| Arc {
                normal: q.clone(),
                start: pts[i].clone(),
                end: pts[(i + 1) % 4].clone(),
            })
            .collect();
        SphericalPolygon {
            normals: vec![q],
            boundary,
        }
    }

    /// The lune `{q1 · x >= 0, q2 · x >= 0}` for non-parallel `q1`, `q2`; its two corners
    /// are `±(q1 × q2)` and each half-circle side is split at its midpoint.
    pub fn lune(q1: &Vec3, q2: &Vec3) -> SphericalPolygon {
        let (q1, q2) = (q1.primitive(), q2.primitive());
        let u = q1.cross(&q2).primitive();
        debug_assert!(!u.is_zero());
        let mut boundary = Vec::new();
        for (a, b) in [(&q1, &q2), (&q2, &q1)] {
            // Midpoint of the side on circle a: perpendicular to u, on the inner side of b.
            let mut m = a.cross(&u).primitive();
            if dot_sign(b, &m) == Sign::Negative {
                m = m.neg();
            }
            for (s, e) in [(u.clone(), m.clone()), (m.clone(), u.neg())] {
                boundary.push(Arc::on_circle(a, &s, &e).expect("lune side"));
            }
        }
        let boundary = chain(boundary).expect("lune boundary");
        SphericalPolygon {
            normals: vec![q1, q2],
            boundary,
        }
    }

    /// A pointed polygon (contained in an open hemisphere) from its boundary arcs in any
    /// order, each counter-clockwise around its inward normal. Consecutive arcs on the
    /// same circle are merged; the arcs must form one closed cycle.
    pub fn from_arcs(arcs: Vec<Arc>) -> Result<SphericalPolygon, PolygonError> {
        let arcs = merge_cocircular(arcs)?;
        let boundary = chain(arcs)?;
        if boundary.len() < 3 {
            return Err(PolygonError(format!("only {} sides", boundary.len())));
        }
        let normals = boundary.iter().map(|a| a.normal.clone()).collect();
        Ok(SphericalPolygon { normals, boundary })
    }

    /// [`SphericalPolygon::from_arcs`] for arcs already in boundary order (each ends where
    /// the next starts, the last where the first starts), without hashing their points:
    /// consecutive arcs on one circle are merged, the first side is the one holding
    /// `arcs[0]`, as `from_arcs` gives it.
    pub fn from_cycle(mut arcs: Vec<Arc>) -> Result<SphericalPolygon, PolygonError> {
        let n = arcs.len();
        for (k, a) in arcs.iter().enumerate() {
            let next = (k + 1) % n;
            if a.end != arcs[next].start {
                return Err(PolygonError(format!(
                    "side {k} does not end where {next} starts"
                )));
            }
        }
        // The arcs of the first side's circle at the end of the cycle belong to it.
        let mut tail = n;
        while tail > 1 && arcs[tail - 1].normal == arcs[0].normal {
            tail -= 1;
        }
        if tail == 1 && n > 1 {
            return Err(PolygonError(
                "arcs on one circle close a full circle".into(),
            ));
        }
        arcs.rotate_left(tail % n.max(1));
        let mut boundary: Vec<Arc> = Vec::with_capacity(n);
        let mut merged = Vec::new();
        for a in arcs {
            match boundary.last_mut() {
                Some(last) if last.normal == a.normal => {
                    last.end = a.end;
                    merged.push(boundary.len() - 1);
                }
                _ => boundary.push(a),
            }
        }
        if boundary.len() < 3 {
            return Err(PolygonError(format!("only {} sides", boundary.len())));
        }
        if merged.iter().any(|&k| {
            let a = &boundary[k];
            det3_sign(&a.normal, &a.start, &a.end) != Sign::Positive
        }) {
            return Err(PolygonError("merged side is not a minor arc".into()));
        }
        let normals = boundary.iter().map(|a| a.normal.clone()).collect();
        Ok(SphericalPolygon { normals, boundary })
    }

    /// The inward normals.
    pub fn normals(&self) -> &[Vec3] {
        &self.normals
    }

    /// The boundary as a cycle of minor arcs, interior on the left.
    pub fn boundary(&self) -> &[Arc] {
        &self.boundary
    }

    /// The corner points (ends of the boundary arcs), including the extra points that
    /// split hemisphere and lune sides.
    pub fn corners(&self) -> impl Iterator<Item = &Vec3> {
        self.boundary.iter().map(|a| &a.start)
    }

    /// True when `x` lies in the open polygon.
    pub fn contains_open(&self, x: &Vec3) -> bool {
        self.normals
            .iter()
            .all(|q| dot_sign(q, x) == Sign::Positive)
    }

    /// True when `x` lies in the closed polygon.
    pub fn contains_closed(&self, x: &Vec3) -> bool {
        self.normals
            .iter()
            .all(|q| dot_sign(q, x) != Sign::Negative)
    }

    /// Whether the symbolic point `x + ε y` (ε → 0⁺) lies in the open polygon: each
    /// constraint is decided by `q · x`, or by `q · y` when that is zero.
    pub fn contains_open_perturbed(&self, x: &Vec3, y: &Vec3) -> bool {
        self.normals.iter().all(|q| match dot_sign(q, x) {
            Sign::Positive => true,
            Sign::Negative => false,
            Sign::Zero => dot_sign(q, y) == Sign::Positive,
        })
    }

    /// The antipodal polygon `{-x}`: inward normals negate, and each side `(q, s, e)`
    /// becomes `(-q, -e, -s)` (counter-clockwise around `-q`), in reverse cyclic order.
    pub fn antipodal(&self) -> SphericalPolygon {
        let mut boundary: Vec<Arc> = self
            .boundary
            .iter()
            .map(|a| Arc {
                normal: a.normal.neg(),
                start: a.end.neg(),
                end: a.start.neg(),
            })
            .collect();
        boundary.reverse();
        SphericalPolygon {
            normals: self.normals.iter().map(Vec3::neg).collect(),
            boundary,
        }
    }
}

/// A primitive vector perpendicular to `q` (non-zero).
pub fn perpendicular(q: &Vec3) -> Vec3 {
    let a = q.approx();
    let k = if a[0].abs() <= a[1].abs() && a[0].abs() <= a[2].abs() {
        0
    } else if a[1].abs() <= a[2].abs() {
        1
    } else {
        2
    };
    let mut e = [0i64; 3];
    e[k] = 1;
    let u = q.cross(&Vec3::from_i64(e));
    if !u.is_zero() {
        return u.primitive();
    }
    // q is parallel to that axis; any other axis works.
    e[k] = 0;
    e[(k + 1) % 3] = 1;
    q.cross(&Vec3::from_i64(e)).primitive()
}

/// Merges arcs lying on the same circle (same inward normal) that chain end to start.
fn merge_cocircular(arcs: Vec<Arc>) -> Result<Vec<Arc>, PolygonError> {
    use rustc_hash::FxHashMap as HashMap;
    let mut by_circle: HashMap<Vec3, Vec<Arc>> = HashMap::default();
    let mut order = Vec::new();
    for a in arcs {
        let key = a.normal.clone();
        if !by_circle.contains_key(&key) {
            order.push(key.clone());
        }
        by_circle.entry(key).or_default().push(a);
    }
    let mut out = Vec::new();
    for key in order {
        let group = by_circle.remove(&key).unwrap();
        if group.len() == 1 {
            out.extend(group);
            continue;
        }
        // Chain the group: start at the arc whose start is no other arc's end.
        let ends: rustc_hash::FxHashSet<&Vec3> = group.iter().map(|a| &a.end).collect();
        let first = group
            .iter()
            .position(|a| !ends.contains(&a.start))
            .ok_or_else(|| PolygonError("arcs on one circle close a full circle".into()))?;
        let starts: HashMap<&Vec3, usize> = group
            .iter()
            .enumerate()
            .map(|(i, a)| (&a.start, i))
            .collect();
        let mut cur = first;
        let mut count = 1;
        while let Some(&next) = starts.get(&group[cur].end) {
            cur = next;
            count += 1;
            if count > group.len() {
                return Err(PolygonError("cycle within one circle".into()));
            }
        }
        if count != group.len() {
            return Err(PolygonError("arcs on one circle are not contiguous".into()));
        }
        let merged = Arc {
            normal: key,
            start: group[first].start.clone(),
            end: group[cur].end.clone(),
        };
        if det3_sign(&merged.normal, &merged.start, &merged.end) != Sign::Positive {
            return Err(PolygonError("merged side is not a minor arc".into()));
        }
        out.push(merged);
    }
    Ok(out)
}

/// Orders arcs into one closed cycle (end of each = start of the next).
fn chain(arcs: Vec<Arc>) -> Result<Vec<Arc>, PolygonError> {
    use rustc_hash::FxHashMap as HashMap;
    let starts: HashMap<&Vec3, usize> = arcs
        .iter()
        .enumerate()
        .map(|(i, a)| (&a.start, i))
        .collect();
    if starts.len() != arcs.len() {
        return Err(PolygonError("two sides start at one point".into()));
    }
    let mut order = Vec::with_capacity(arcs.len());
    let mut cur = 0;
    for _ in 0..arcs.len() {
        order.push(cur);
        cur = *starts.get(&arcs[cur].end).ok_or_else(|| {
            PolygonError(format!(
                "side ending at {:?} has no successor",
                arcs[cur].end
            ))
        })?;
    }
    if cur != 0 {
        return Err(PolygonError("sides form more than one cycle".into()));
    }
    let mut slots: Vec<Option<Arc>> = arcs.into_iter().map(Some).collect();
    Ok(order
        .into_iter()
        .map(|i| slots[i].take().unwrap())
        .collect())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn hemisphere_and_lune() {
        let h = SphericalPolygon::hemisphere(&Vec3::new(0, 0, 3));
        assert_eq!(h.boundary().len(), 4);
        assert!(h.contains_open(&Vec3::new(1, 2, 1)));
        assert!(!h.contains_open(&Vec3::new(1, 2, 0)));
        assert!(h.contains_closed(&Vec3::new(1, 2, 0)));
        for a in h.boundary() {
            assert_eq!(det3_sign(&a.normal, &a.start, &a.end), Sign::Positive);
        }
        let l = SphericalPolygon::lune(&Vec3::new(0, 0, 1), &Vec3::new(0, 1, 0));
        assert_eq!(l.boundary().len(), 4);
        assert!(l.contains_open(&Vec3::new(5, 1, 1)));
        assert!(!l.contains_open(&Vec3::new(5, -1, 1)));
        // Interior on the left of every side: the midpoint of (0,1,1) is inside.
        for a in l.boundary() {
            assert_eq!(dot_sign(&a.normal, &Vec3::new(0, 1, 1)), Sign::Positive);
        }
        let anti = l.antipodal();
        assert!(anti.contains_open(&Vec3::new(-5, -1, -1)));
        for a in anti.boundary() {
            assert_eq!(det3_sign(&a.normal, &a.start, &a.end), Sign::Positive);
            assert_eq!(dot_sign(&a.normal, &Vec3::new(0, -1, -1)), Sign::Positive);
        }
    }

    #[test]
    fn triangle_from_shuffled_split_arcs() {
        // Octant triangle x, y, z >= 0 with one side given in two pieces.
        let (x, y, z) = (Vec3::new(1, 0, 0), Vec3::new(0, 1, 0), Vec3::new(0, 0, 1));
        let m = Vec3::new(1, 1, 0);
        let arcs = vec![
            Arc::between(&y, &z).unwrap(),
            Arc::between(&m, &y).unwrap(),
            Arc::between(&z, &x).unwrap(),
            Arc::between(&x, &m).unwrap(),
        ];
        let p = SphericalPolygon::from_arcs(arcs).unwrap();
        assert_eq!(p.boundary().len(), 3);
        assert!(p.contains_open(&Vec3::new(1, 1, 1)));
        assert!(!p.contains_open(&Vec3::new(1, 1, 0)));
        assert!(p.contains_open_perturbed(&Vec3::new(1, 1, 0), &Vec3::new(0, 0, 1)));
        assert!(!p.contains_open_perturbed(&Vec3::new(1, 1, 0), &Vec3::new(0, 0, -1)));
    }

    proptest::proptest! {
        /// A convex k-gon around +z, some sides cut into several cocircular pieces, given
        /// in boundary order from any piece: `from_cycle` gives what `from_arcs` gives
        /// (the same sides, starting at the same one), and refuses a broken cycle.
        #[test]
        fn from_cycle_matches_from_arcs(
            k in 3usize..12,
            cuts in proptest::collection::vec(0usize..4, 12),
            rotate in 0usize..64,
            r in 50i64..1000,
        ) {
            // Corners on a circle of radius r at height 1000 (convex, pointed).
            let corner = |t: f64| {
                let a = t * std::f64::consts::TAU;
                [(r as f64 * a.cos()).round() as i64, (r as f64 * a.sin()).round() as i64]
            };
            let mut arcs = Vec::new();
            for (i, &cut) in cuts.iter().enumerate().take(k) {
                let (p, q) = (corner(i as f64 / k as f64), corner((i + 1) as f64 / k as f64));
                // Points along the chord p..q (exactly on it: integer steps times the
                // denominator), so the pieces share the side's great circle.
                let m = cut as i64 + 1;
                let pts: Vec<Vec3> = (0..=m)
                    .map(|j| Vec3::new(p[0] * (m - j) + q[0] * j, p[1] * (m - j) + q[1] * j, 1000 * m))
                    .collect();
                for w in pts.windows(2) {
                    arcs.push(Arc::between(&w[0], &w[1]).unwrap());
                }
            }
            let n = arcs.len();
            arcs.rotate_left(rotate % n);
            let a = SphericalPolygon::from_arcs(arcs.clone()).unwrap();
            let c = SphericalPolygon::from_cycle(arcs.clone()).unwrap();
            proptest::prop_assert_eq!(a.boundary(), c.boundary());
            proptest::prop_assert_eq!(a.normals(), c.normals());
            proptest::prop_assert_eq!(c.boundary().len(), k);
            // Two arcs swapped: no longer a cycle.
            arcs.swap(0, 1);
            proptest::prop_assert!(SphericalPolygon::from_cycle(arcs).is_err());
        }
    }
}
