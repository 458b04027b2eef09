//! Exact convex polytopes: vertices, facet planes with integer normals, adjacency.

use crate::climb::{Climb, CLIMB_MIN};
use crate::hull2d::hull_in_plane;
use apart_kernel::fvec;
use apart_kernel::int::{self, Int};
use apart_kernel::predicates::dot_sign;
use apart_kernel::{Sign, Vec3};
use rustc_hash::FxHashMap as HashMap;
use std::fmt;

/// A facet: the plane `normal · x = offset` (outward, primitive normal) and its vertices.
#[derive(Clone, Debug)]
pub struct Facet {
    /// Outward normal, a primitive integer vector.
    pub normal: Vec3,
    /// `normal · v` for every vertex `v` of the facet; `normal · x <= offset` inside.
    pub offset: Int,
    /// Vertex indices, counter-clockwise seen from outside (around `normal`), strictly
    /// convex (no vertex in the middle of a facet edge).
    pub cycle: Vec<u32>,
}

/// An edge between two vertices and two facets.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub struct Edge {
    /// End points; `ends[0] -> ends[1]` is the direction in which `facets[0]` traverses it.
    pub ends: [u32; 2],
    /// The facet traversing the edge from `ends[0]` to `ends[1]`, then the other one.
    pub facets: [u32; 2],
}

/// A full-dimensional convex polytope with exact vertices.
///
/// Vertices are stored as integer vectors equal to `den` times the true coordinates
/// (`den = 1` for pieces of grid coordinates; exact decomposition creates rational
/// vertices and gives each piece the common denominator of its own). Facet offsets refer
/// to the stored integers: a point `x` of the polytope satisfies `n · (den x) <= offset`.
#[derive(Clone)]
pub struct Polytope {
    vertices: Vec<Vec3>,
    den: Int,
    facets: Vec<Facet>,
    edges: Vec<Edge>,
    /// Distinct edge directions, primitive, one of each `±d` pair (computed on demand:
    /// Minkowski sums never need theirs).
    edge_dirs: std::sync::OnceLock<Vec<Vec3>>,
    /// Floating-point coordinates for filters (computed on demand).
    shadow: std::sync::OnceLock<Option<Shadow>>,
    /// The vertex graph for climbing support queries (computed on demand, for
    /// polytopes of at least [`CLIMB_MIN`] vertices; it holds no coordinates, and stays
    /// valid under translation and positive scaling).
    climb: std::sync::OnceLock<Climb>,
    /// The integer box of [`Polytope::integer_box`] (computed on demand, once).
    bounds: std::sync::OnceLock<Option<apart_kernel::Aabb>>,
}

/// Floating-point true coordinates of a polytope's vertices, for filters that prune
/// exact work: every coordinate is within a relative error of 2^-51 of the exact one.
#[derive(Clone, Debug)]
pub struct Shadow {
    /// The vertices' true coordinates, in the order of [`Polytope::vertices`].
    pub points: Vec<[f64; 3]>,
    /// The mean of the vertices (a point of the polytope, up to rounding).
    pub mean: [f64; 3],
    /// The largest coordinate magnitude (between 2^-900 and 2^900, else no shadow).
    pub magnitude: f64,
    /// Each facet's unit outward normal (each component within 2^-49).
    pub facet_units: Vec<[f64; 3]>,
    /// Each facet's level `u · x` for its unit normal `u` and a point `x` of it.
    pub facet_levels: Vec<f64>,
}

impl Shadow {
    /// A bound on how far a float dot product of a unit float axis (each component
    /// within 2^-49 of the exact unit axis, as `Vec3::unit_f64` gives) with a shadow
    /// point lies from the exact value: at most `4 m 2^-49` with `m` the largest
    /// coordinate magnitude; `m 2^-44` leaves a wide margin.
    pub fn error(&self) -> f64 {
        self.magnitude * 2f64.powi(-44)
    }

    fn of(vertices: &[Vec3], den: &Int, facets: &[Facet]) -> Option<Shadow> {
        // Quotients of two correctly rounded conversions: relative error < 2^-51.
        // Denominators beyond 2^1000 are left to the exact code.
        if int::bit_len(den) > 1000 {
            return None;
        }
        let d = int::to_f64(den);
        let mut points = Vec::with_capacity(vertices.len());
        let mut sum = [0f64; 3];
        let mut magnitude = f64::MIN_POSITIVE;
        for v in vertices {
            let p = match v.as_small() {
                Some(c) => [c[0] as f64 / d, c[1] as f64 / d, c[2] as f64 / d],
                None => [0, 1, 2].map(|k| int::to_f64(&v.get(k)) / d),
            };
            for k in 0..3 {
                if !p[k].is_finite() {
                    return None;
                }
                sum[k] += p[k];
                magnitude = magnitude.max(p[k].abs());
            }
            points.push(p);
        }
        // Far from both ends of the float range, so that rounding stays relative (no
        // subnormals) and sums of coordinates stay finite.
        if !(2f64.powi(-900)..=2f64.powi(900)).contains(&magnitude) {
            return None;
        }
        let n = vertices.len().max(1) as f64;
        // Every facet gets its unit normal, or there is no shadow (a filter that skipped
        // a facet could miss a separating plane).
        let facet_units: Vec<[f64; 3]> = facets
            .iter()
            .map(|f| {
                let u = f.normal.unit_f64();
                (u.iter().all(|c| c.is_finite()) && u != [0.0; 3]).then_some(u)
            })
            .collect::<Option<_>>()?;
        let facet_levels = facets
            .iter()
            .zip(&facet_units)
            .map(|(f, u)| {
                let x = points[f.cycle[0] as usize];
                fvec::dot(x, *u)
            })
            .collect();
        Some(Shadow {
            points,
            mean: sum.map(|c| c / n),
            magnitude,
            facet_units,
            facet_levels,
        })
    }
}

/// Why a set of triangles or points is not a convex polytope.
#[derive(Clone, Debug, PartialEq, Eq)]
pub enum PolytopeError {
    /// Vertex `vertex` lies strictly outside the plane of triangle `triangle`.
    NotConvex {
        /// Index of the triangle whose plane is violated.
        triangle: usize,
        /// Index of the offending vertex.
        vertex: usize,
    },
    /// Triangle `triangle` has collinear vertices (no plane).
    DegenerateTriangle {
        /// Index of the triangle.
        triangle: usize,
    },
    /// The points do not span three dimensions (no volume).
    Flat,
    /// The facets do not close up into a sphere-like surface (inconsistent input).
    NotClosed,
}

impl fmt::Display for PolytopeError {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        match self {
            PolytopeError::NotConvex { triangle, vertex } => write!(
                f,
                "not convex: vertex {vertex} lies outside the plane of face {triangle}"
            ),
            PolytopeError::DegenerateTriangle { triangle } => {
                write!(f, "face {triangle} has collinear vertices")
            }
            PolytopeError::Flat => write!(f, "the points do not enclose any volume"),
            PolytopeError::NotClosed => write!(f, "the faces do not form a closed convex surface"),
        }
    }
}

impl std::error::Error for PolytopeError {}

/// Where a point lies with respect to a closed polytope.
#[derive(Clone, Copy, Debug, PartialEq, Eq)]
pub enum Containment {
    /// In the interior.
    Inside,
    /// On the boundary.
    Boundary,
    /// Outside.
    Outside,
}

impl Polytope {
    /// The polytope bounded by `triangles` over `points`, which must form a closed,
    /// consistently outward-oriented surface (as the mesh loader guarantees).
    /// Coplanar triangles merge into one facet; vertices in the middle of facet edges
    /// or inside facets are dropped. Fails when the surface is not convex.
    pub fn from_triangles(
        points: &[Vec3],
        triangles: &[[u32; 3]],
    ) -> Result<Polytope, PolytopeError> {
        let mut planes: HashMap<Vec3, (Int, Vec<usize>)> = HashMap::default();
        let mut order: Vec<Vec3> = Vec::new();
        for (t, tri) in triangles.iter().enumerate() {
            let [a, b, c] = tri.map(|i| &points[i as usize]);
            let n = b.sub(a).cross(&c.sub(a));
            if n.is_zero() {
                return Err(PolytopeError::DegenerateTriangle { triangle: t });
            }
            let n = n.primitive();
            let off = n.dot(a);
            match planes.get_mut(&n) {
                Some((o, ts)) => {
                    if *o != off {
                        // Two parallel faces facing the same way: one is behind the other.
                        let (t0, behind) = if *o < off {
                            (ts[0], tri[0])
                        } else {
                            (t, triangles[ts[0]][0])
                        };
                        return Err(PolytopeError::NotConvex {
                            triangle: t0,
                            vertex: behind as usize,
                        });
                    }
                    ts.push(t);
                }
                None => {
                    order.push(n.clone());
                    planes.insert(n, (off, vec![t]));
                }
            }
        }
        let mut used: Vec<u32> = triangles.iter().flatten().copied().collect();
        used.sort_unstable();
        used.dedup();
        // Every used vertex must be on the inner side of every face plane.
        for n in &order {
            let (off, ts) = &planes[n];
            for &v in &used {
                let s = int::sign_of(&(n.dot(&points[v as usize]) - off));
                if s == Sign::Positive {
                    return Err(PolytopeError::NotConvex {
                        triangle: ts[0],
                        vertex: v as usize,
                    });
                }
            }
        }
        let mut facets = Vec::with_capacity(order.len());
        for n in order {
            let (off, ts) = planes.remove(&n).unwrap();
            let mut vs: Vec<u32> = ts.iter().flat_map(|&t| triangles[t]).collect();
            vs.sort_unstable();
            vs.dedup();
            let pts: Vec<Vec3> = vs.iter().map(|&v| points[v as usize].clone()).collect();
            let hull = hull_in_plane(&n, &pts);
            if hull.len() < 3 {
                return Err(PolytopeError::NotClosed);
            }
            facets.push((
                n,
                off,
                hull.into_iter().map(|i| vs[i]).collect::<Vec<u32>>(),
            ));
        }
        Polytope::assemble(points, facets)
    }

    /// The axis-aligned box `[lo, hi]` (its eight corners' hull; an error when some
    /// `lo[k] >= hi[k]` leaves it flat).
    pub fn cuboid(lo: [i64; 3], hi: [i64; 3]) -> Result<Polytope, PolytopeError> {
        if (0..3).any(|k| lo[k] >= hi[k]) {
            return Err(PolytopeError::Flat);
        }
        // Corner i takes hi in axis k when bit k of i is set.
        let corners: Vec<Vec3> = (0..8)
            .map(|i| {
                Vec3::new(
                    if i & 1 == 1 { hi[0] } else { lo[0] },
                    if i & 2 == 2 { hi[1] } else { lo[1] },
                    if i & 4 == 4 { hi[2] } else { lo[2] },
                )
            })
            .collect();
        // The six faces, counter-clockwise around their outward normals.
        let faces: [([i64; 3], [u32; 4]); 6] = [
            ([-1, 0, 0], [0, 4, 6, 2]),
            ([1, 0, 0], [1, 3, 7, 5]),
            ([0, -1, 0], [0, 1, 5, 4]),
            ([0, 1, 0], [2, 6, 7, 3]),
            ([0, 0, -1], [0, 2, 3, 1]),
            ([0, 0, 1], [4, 5, 7, 6]),
        ];
        Polytope::from_facets(
            &corners,
            faces
                .iter()
                .map(|(n, c)| (Vec3::from_i64(*n), c.to_vec()))
                .collect(),
        )
    }

    /// The convex hull of a small set of points (at most a few dozen: the method tries
    /// every triple, O(n^4)). Meant for tests and for small generated pieces.
    pub fn hull_of_points(points: &[Vec3]) -> Result<Polytope, PolytopeError> {
        let mut pts: Vec<Vec3> = points.to_vec();
        pts.sort_by_cached_key(|p| p.to_strings());
        pts.dedup();
        let n = pts.len();
        // Outward facet planes found so far, keyed by (normal, offset).
        let mut planes: rustc_hash::FxHashSet<(Vec3, Int)> = rustc_hash::FxHashSet::default();
        let mut order = Vec::new();
        for i in 0..n {
            for j in i + 1..n {
                let dij = pts[j].sub(&pts[i]);
                for k in j + 1..n {
                    let nrm = dij.cross(&pts[k].sub(&pts[i]));
                    if nrm.is_zero() {
                        continue;
                    }
                    let nrm = nrm.primitive();
                    let off = nrm.dot(&pts[i]);
                    if planes.contains(&(nrm.clone(), off.clone()))
                        || planes.contains(&(nrm.neg(), -off.clone()))
                    {
                        continue;
                    }
                    let (mut pos, mut neg) = (false, false);
                    for p in &pts {
                        match int::sign_of(&(nrm.dot(p) - &off)) {
                            Sign::Positive => pos = true,
                            Sign::Negative => neg = true,
                            Sign::Zero => {}
                        }
                        if pos && neg {
                            break;
                        }
                    }
                    if pos && neg {
                        continue;
                    }
                    let (nrm, off) = if pos { (nrm.neg(), -off) } else { (nrm, off) };
                    order.push((nrm.clone(), off.clone()));
                    planes.insert((nrm, off));
                }
            }
        }
        if order.len() < 4 {
            return Err(PolytopeError::Flat);
        }
        let mut facets = Vec::new();
        for (nrm, off) in order {
            let on: Vec<u32> = (0..n as u32)
                .filter(|&v| nrm.dot(&pts[v as usize]) == off)
                .collect();
            let sub: Vec<Vec3> = on.iter().map(|&v| pts[v as usize].clone()).collect();
            let hull = hull_in_plane(&nrm, &sub);
            if hull.len() < 3 {
                return Err(PolytopeError::Flat);
            }
            facets.push((nrm, off, hull.into_iter().map(|i| on[i]).collect()));
        }
        Polytope::assemble(&pts, facets)
    }

    /// Builds the polytope from facet planes and strictly convex vertex cycles
    /// (counter-clockwise around the outward normal) over `points`; unused points are
    /// dropped and vertices renumbered.
    pub fn from_facets(
        points: &[Vec3],
        facets: Vec<(Vec3, Vec<u32>)>,
    ) -> Result<Polytope, PolytopeError> {
        let facets = facets
            .into_iter()
            .map(|(n, c)| {
                let off = n.dot(&points[c[0] as usize]);
                (n, off, c)
            })
            .collect();
        Polytope::assemble(points, facets)
    }

    pub(crate) fn assemble(
        points: &[Vec3],
        facets: Vec<(Vec3, Int, Vec<u32>)>,
    ) -> Result<Polytope, PolytopeError> {
        let mut remap: Vec<u32> = vec![u32::MAX; points.len()];
        let mut vertices = Vec::new();
        let facets: Vec<Facet> = facets
            .into_iter()
            .map(|(normal, offset, cycle)| {
                let cycle = cycle
                    .into_iter()
                    .map(|v| {
                        let slot = &mut remap[v as usize];
                        if *slot == u32::MAX {
                            vertices.push(points[v as usize].clone());
                            *slot = (vertices.len() - 1) as u32;
                        }
                        *slot
                    })
                    .collect();
                Facet {
                    normal,
                    offset,
                    cycle,
                }
            })
            .collect();
        // Directed edges (u, v, facet) sorted by undirected key: each undirected edge must
        // appear exactly twice, once each way.
        let mut directed: Vec<(u32, u32, u32)> =
            Vec::with_capacity(facets.iter().map(|f| f.cycle.len()).sum());
        for (f, facet) in facets.iter().enumerate() {
            let c = &facet.cycle;
            for i in 0..c.len() {
                directed.push((c[i], c[(i + 1) % c.len()], f as u32));
            }
        }
        directed.sort_unstable_by_key(|&(u, v, _)| (u.min(v), u.max(v), u));
        if directed.len() % 2 != 0 {
            return Err(PolytopeError::NotClosed);
        }
        let mut edges = Vec::with_capacity(directed.len() / 2);
        for w in directed.chunks(2) {
            let ((u0, v0, f0), (u1, v1, f1)) = (w[0], w[1]);
            if u0 != v1 || v0 != u1 || u0 == v0 {
                return Err(PolytopeError::NotClosed);
            }
            // u0 < v0 by the sort key: facet f0 runs u0 -> v0.
            edges.push(Edge {
                ends: [u0, v0],
                facets: [f0, f1],
            });
        }
        if vertices.len() + facets.len() != edges.len() + 2 || facets.len() < 4 {
            return Err(PolytopeError::NotClosed);
        }
        Ok(Polytope {
            vertices,
            den: Int::ONE,
            facets,
            edges,
            edge_dirs: std::sync::OnceLock::new(),
            shadow: std::sync::OnceLock::new(),
            climb: std::sync::OnceLock::new(),
            bounds: std::sync::OnceLock::new(),
        })
    }

    /// The vertices (extreme points only), as `den` times their coordinates.
    pub fn vertices(&self) -> &[Vec3] {
        &self.vertices
    }

    /// The vertices' true coordinates in floating point, for filters; `None` when they
    /// do not fit (computed once).
    pub fn shadow(&self) -> Option<&Shadow> {
        self.shadow
            .get_or_init(|| Shadow::of(&self.vertices, &self.den, &self.facets))
            .as_ref()
    }

    /// The common denominator of the vertices (positive; 1 for grid pieces).
    pub fn den(&self) -> &Int {
        &self.den
    }

    /// The smallest integer box holding the polytope (a rational vertex's coordinates
    /// rounded outward), or `None` when a bound exceeds 2^60 in magnitude: the one box
    /// of a piece, computed exactly once and kept.
    pub fn integer_box(&self) -> Option<apart_kernel::Aabb> {
        *self.bounds.get_or_init(|| self.compute_integer_box())
    }

    fn compute_integer_box(&self) -> Option<apart_kernel::Aabb> {
        let mut b: apart_kernel::Aabb = apart_kernel::Aabb::EMPTY;
        for v in &self.vertices {
            for k in 0..3 {
                let x = v.get(k);
                let (lo, hi) = if self.den == Int::ONE {
                    (x.clone(), x)
                } else {
                    // The truncated quotient, moved outward when inexact.
                    let q = &x / &self.den;
                    let exact = &q * &self.den == x;
                    let lo = if !exact && x < Int::ZERO {
                        &q - Int::ONE
                    } else {
                        q.clone()
                    };
                    let hi = if !exact && x > Int::ZERO {
                        &q + Int::ONE
                    } else {
                        q
                    };
                    (lo, hi)
                };
                let (lo, hi) = (int::to_i64(&lo)?, int::to_i64(&hi)?);
                if lo.unsigned_abs() > 1 << 60 || hi.unsigned_abs() > 1 << 60 {
                    return None;
                }
                b.min[k] = b.min[k].min(lo);
                b.max[k] = b.max[k].max(hi);
            }
        }
        Some(b)
    }

    /// The same polytope declared to have denominator `den` (its stored integers are
    /// `den` times its coordinates). `den` must be positive.
    pub fn with_den(mut self, den: Int) -> Polytope {
        assert!(den > Int::ZERO, "denominator must be positive");
        self.den = den;
        self.shadow = std::sync::OnceLock::new();
        self.bounds = std::sync::OnceLock::new();
        self
    }

    /// The same polytope with its stored integers multiplied by `k > 0` (and its
    /// denominator too), e.g. to bring two pieces to a common denominator.
    pub fn rescaled(&self, k: &Int) -> Polytope {
        if *k == Int::ONE {
            return self.clone();
        }
        let mut p = self.clone();
        for v in &mut p.vertices {
            *v = v.scale(k);
        }
        for f in &mut p.facets {
            f.offset *= k;
        }
        p.den *= k;
        p.edge_dirs = std::sync::OnceLock::new();
        p
    }

    /// Both polytopes brought to the least common multiple of their denominators.
    pub fn common(a: &Polytope, b: &Polytope) -> (Polytope, Polytope) {
        if a.den == b.den {
            return (a.clone(), b.clone());
        }
        let g = apart_kernel::int::gcd(&a.den, &b.den);
        (a.rescaled(&(&b.den / &g)), b.rescaled(&(&a.den / &g)))
    }

    /// The exact volume (true coordinates).
    pub fn volume(&self) -> apart_kernel::Rational {
        let d3 = &self.den * &self.den * &self.den;
        apart_kernel::Rational::new(self.volume6(), d3 * Int::from(6))
    }

    /// The facets.
    pub fn facets(&self) -> &[Facet] {
        &self.facets
    }

    /// The edges.
    pub fn edges(&self) -> &[Edge] {
        &self.edges
    }

    /// The distinct edge directions, primitive, one per `±d` pair.
    pub fn edge_directions(&self) -> &[Vec3] {
        self.edge_dirs.get_or_init(|| {
            let mut dirs: Vec<Vec3> = Vec::new();
            let mut seen = rustc_hash::FxHashSet::default();
            for e in &self.edges {
                let d = self.vertices[e.ends[1] as usize]
                    .sub(&self.vertices[e.ends[0] as usize])
                    .primitive();
                let d = canonical_sign(d);
                if seen.insert(d.clone()) {
                    dirs.push(d);
                }
            }
            dirs
        })
    }

    /// The support value `max n · v` and the vertices attaining it (in increasing
    /// order).
    pub fn support(&self, n: &Vec3) -> (Int, Vec<u32>) {
        if self.vertices.len() >= CLIMB_MIN {
            if let Some(s) = self.climb.get_or_init(|| Climb::new(self)).support(self, n) {
                return s;
            }
            // A maximal face of many vertices is a facet (an edge has two): the one
            // whose (primitive) normal is `n`'s direction.
            let m = n.primitive();
            if let Some(f) = self.facets.iter().find(|f| f.normal == m) {
                let mut arg = f.cycle.clone();
                arg.sort_unstable();
                return (n.dot(&self.vertices[arg[0] as usize]), arg);
            }
        }
        self.support_scan(n)
    }

    /// The support value `max n · v` alone ([`Polytope::support`] without the
    /// maximisers, which a big maximal face would make costly).
    pub fn support_value(&self, n: &Vec3) -> Int {
        if self.vertices.len() >= CLIMB_MIN {
            return self.climb.get_or_init(|| Climb::new(self)).value(self, n);
        }
        self.support_scan(n).0
    }

    /// [`Polytope::support`] over every vertex.
    pub(crate) fn support_scan(&self, n: &Vec3) -> (Int, Vec<u32>) {
        if let Some(nn) = n.as_small() {
            if self.vertices.iter().all(|v| v.as_small().is_some()) {
                let dot = |v: &Vec3| {
                    let c = v.as_small().unwrap();
                    nn[0] as i128 * c[0] as i128
                        + nn[1] as i128 * c[1] as i128
                        + nn[2] as i128 * c[2] as i128
                };
                let mut best = i128::MIN;
                let mut arg = Vec::new();
                for (i, v) in self.vertices.iter().enumerate() {
                    let d = dot(v);
                    if d > best {
                        best = d;
                        arg.clear();
                    }
                    if d == best {
                        arg.push(i as u32);
                    }
                }
                return (Int::from(best), arg);
            }
        }
        // Many big vertices: only those whose float value comes within the filter's
        // error bound of the float maximum can attain the exact one.
        let filter = (self.vertices.len() > 32)
            .then(|| {
                let s = self.shadow()?;
                let u = n.unit_f64();
                u.iter().all(|c| c.is_finite()).then_some((s, u))
            })
            .flatten();
        let dots: Vec<f64> = match &filter {
            Some((s, u)) => s.points.iter().map(|p| fvec::dot(*p, *u)).collect(),
            None => Vec::new(),
        };
        let floor = match &filter {
            Some((s, _)) => {
                dots.iter().copied().fold(f64::NEG_INFINITY, f64::max) - 2.0 * s.error()
            }
            None => f64::NEG_INFINITY,
        };
        let mut best: Option<Int> = None;
        let mut arg = Vec::new();
        for (i, v) in self.vertices.iter().enumerate() {
            if !dots.is_empty() && dots[i] < floor {
                continue;
            }
            let d = n.dot(v);
            match &best {
                Some(b) if d < *b => continue,
                Some(b) if d == *b => arg.push(i as u32),
                _ => {
                    best = Some(d);
                    arg.clear();
                    arg.push(i as u32);
                }
            }
        }
        (best.expect("polytope without vertices"), arg)
    }

    /// Six times the volume of the stored integer polytope (the true volume times
    /// `6 den³`), exactly.
    pub fn volume6(&self) -> Int {
        let mut total = Int::ZERO;
        for f in &self.facets {
            let c = &f.cycle;
            let p0 = &self.vertices[c[0] as usize];
            for i in 1..c.len() - 1 {
                let (p1, p2) = (
                    &self.vertices[c[i] as usize],
                    &self.vertices[c[i + 1] as usize],
                );
                total += p0.dot(&p1.cross(p2));
            }
        }
        total
    }

    /// Where the stored-integer point `p` (true point `p / den`) lies: inside, on the
    /// boundary, or outside.
    pub fn locate(&self, p: &Vec3) -> Containment {
        let mut on = false;
        for f in &self.facets {
            match int::sign_of(&(f.normal.dot(p) - &f.offset)) {
                Sign::Positive => return Containment::Outside,
                Sign::Zero => on = true,
                Sign::Negative => {}
            }
        }
        if on {
            Containment::Boundary
        } else {
            Containment::Inside
        }
    }

    /// The reflection `-P = {-x : x in P}`.
    pub fn reflected(&self) -> Polytope {
        let vertices: Vec<Vec3> = self.vertices.iter().map(Vec3::neg).collect();
        let facets = self
            .facets
            .iter()
            .map(|f| {
                let mut cycle = f.cycle.clone();
                cycle.reverse();
                (f.normal.neg(), f.offset.clone(), cycle)
            })
            .collect();
        Polytope::assemble(&vertices, facets)
            .expect("reflection of a valid polytope")
            .with_den(self.den.clone())
    }

    /// The polytope translated by `t` (true coordinates, integer).
    pub fn translated(&self, t: &Vec3) -> Polytope {
        let mut p = self.clone();
        let t = t.scale(&self.den);
        let t = &t;
        for v in &mut p.vertices {
            *v = v.add(t);
        }
        for f in &mut p.facets {
            f.offset += f.normal.dot(t);
        }
        p.shadow = std::sync::OnceLock::new();
        p.bounds = std::sync::OnceLock::new();
        p
    }

    /// Number of vertices + facets + edges, a size measure for statistics.
    pub fn complexity(&self) -> usize {
        self.vertices.len() + self.facets.len() + self.edges.len()
    }
}

impl fmt::Debug for Polytope {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        write!(
            f,
            "Polytope({} vertices, {} facets, {} edges)",
            self.vertices.len(),
            self.facets.len(),
            self.edges.len()
        )
    }
}

/// `d` or `-d`, whichever has its first non-zero component positive.
pub fn canonical_sign(d: Vec3) -> Vec3 {
    for i in 0..3 {
        match int::sign_of(&d.get(i)) {
            Sign::Positive => return d,
            Sign::Negative => return d.neg(),
            Sign::Zero => {}
        }
    }
    d
}

/// Sign of `n · p - c`: which side of the plane `n · x = c` the point lies on.
pub fn plane_side(n: &Vec3, c: &Int, p: &Vec3) -> Sign {
    if *c == Int::ZERO {
        return dot_sign(n, p);
    }
    int::sign_of(&(n.dot(p) - c))
}

#[cfg(test)]
mod tests {
    use super::*;

    pub(crate) fn cube(lo: [i64; 3], hi: [i64; 3]) -> Polytope {
        let mut pts = Vec::new();
        for x in [lo[0], hi[0]] {
            for y in [lo[1], hi[1]] {
                for z in [lo[2], hi[2]] {
                    pts.push(Vec3::new(x, y, z));
                }
            }
        }
        Polytope::hull_of_points(&pts).unwrap()
    }

    #[test]
    fn cuboid_is_the_hull_of_its_corners() {
        for (lo, hi) in [([0, 0, 0], [2, 3, 4]), ([-5, 7, -1], [-2, 9, 30])] {
            let (c, h) = (Polytope::cuboid(lo, hi).unwrap(), cube(lo, hi));
            assert_eq!(c.volume6(), h.volume6());
            assert_eq!(c.facets().len(), 6);
            assert_eq!(c.edges().len(), 12);
            let mut a: Vec<_> = c.facets().iter().map(|f| f.normal.clone()).collect();
            let mut b: Vec<_> = h.facets().iter().map(|f| f.normal.clone()).collect();
            a.sort_by_key(|v| v.to_strings());
            b.sort_by_key(|v| v.to_strings());
            assert_eq!(a, b);
        }
        assert!(Polytope::cuboid([0, 0, 0], [0, 1, 1]).is_err());
    }

    #[test]
    fn cube_structure() {
        let c = cube([0, 0, 0], [2, 3, 4]);
        assert_eq!(c.vertices().len(), 8);
        assert_eq!(c.facets().len(), 6);
        assert_eq!(c.edges().len(), 12);
        assert_eq!(c.edge_directions().len(), 3);
        assert_eq!(c.volume6(), Int::from(6 * 24));
        assert_eq!(c.locate(&Vec3::new(1, 1, 1)), Containment::Inside);
        assert_eq!(c.locate(&Vec3::new(0, 1, 1)), Containment::Boundary);
        assert_eq!(c.locate(&Vec3::new(-1, 1, 1)), Containment::Outside);
        let (h, arg) = c.support(&Vec3::new(0, 0, 1));
        assert_eq!(h, Int::from(4));
        assert_eq!(arg.len(), 4);
        let r = c.reflected();
        assert_eq!(r.volume6(), c.volume6());
        assert_eq!(r.locate(&Vec3::new(-1, -1, -1)), Containment::Inside);
        // Facet cycles are counter-clockwise around the outward normal.
        for p in [&c, &r] {
            for f in p.facets() {
                let v: Vec<&Vec3> = f.cycle.iter().map(|&i| &p.vertices()[i as usize]).collect();
                let s = apart_kernel::predicates::det3_sign(
                    &f.normal,
                    &v[1].sub(v[0]),
                    &v[2].sub(v[1]),
                );
                assert_eq!(s, Sign::Positive);
            }
        }
    }

    #[test]
    fn triangulated_cube_with_extra_vertices() {
        // A cube of side 2 whose top face is split into four triangles around its centre
        // and whose front face has a vertex in the middle of an edge.
        let pts: Vec<Vec3> = [
            [0, 0, 0],
            [2, 0, 0],
            [2, 2, 0],
            [0, 2, 0],
            [0, 0, 2],
            [2, 0, 2],
            [2, 2, 2],
            [0, 2, 2],
            [1, 1, 2], // 8: centre of the top
        ]
        .iter()
        .map(|&c| Vec3::from(c))
        .collect();
        let tris = [
            [0, 2, 1],
            [0, 3, 2],
            [4, 5, 8],
            [5, 6, 8],
            [6, 7, 8],
            [7, 4, 8],
            [0, 1, 5],
            [0, 5, 4],
            [1, 2, 6],
            [1, 6, 5],
            [2, 3, 7],
            [2, 7, 6],
            [3, 0, 4],
            [3, 4, 7],
        ];
        let p = Polytope::from_triangles(&pts, &tris).unwrap();
        assert_eq!(p.vertices().len(), 8);
        assert_eq!(p.facets().len(), 6);
        assert_eq!(p.volume6(), Int::from(48));
    }

    #[test]
    fn rejects_non_convex() {
        // A tetrahedron with one face pushed in is not convex.
        let pts: Vec<Vec3> = [[0, 0, 0], [4, 0, 0], [0, 4, 0], [0, 0, 4], [1, 1, 1]]
            .iter()
            .map(|&c| Vec3::from(c))
            .collect();
        // Faces around the dent at vertex 4 replacing the slanted face (1,2,3).
        let tris = [
            [0, 2, 1],
            [0, 1, 3],
            [0, 3, 2],
            [1, 2, 4],
            [2, 3, 4],
            [3, 1, 4],
        ];
        assert!(matches!(
            Polytope::from_triangles(&pts, &tris),
            Err(PolytopeError::NotConvex { .. })
        ));
    }
}
