//! Free space as closed convex cells of linear inequalities, and the subtraction of an
//! obstacle from a cell (paper 004 §VI-A.3).
//!
//! A cell is the intersection of half-spaces: the permissible region Ω (a box, or a
//! plane written as two opposite inequalities) and the splitting planes added so far.
//! Subtracting the open obstacle `int(O)`, `O = ∩ {n_k · p <= c_k}`, splits the cell
//! `C` into `C ∩ {n_1 · p >= c_1}`, `C ∩ {n_1 · p <= c_1} ∩ {n_2 · p >= c_2}`, …; what
//! remains inside `O` is dropped. Pieces are closed, so points on the obstacle's boundary
//! (the part touching a fixed part) stay free; a piece can be flat (a face of the
//! obstacle with nothing beyond it, e.g. a slot exactly as wide as a flange). The
//! splitting stops as soon as the rest lies beyond one facet plane, which also skips
//! cells the obstacle does not reach. Every decision is an exact linear program.

use crate::obstacle::Obstacle;
use crate::qp::{lexmin, lexmin_box, min_linear, min_linear_box, Objective};
use apart_kernel::{Aabb, BigPlane, HPoint, Int, Rational, Sign};

/// A closed convex cell `{p : every constraint}`.
#[derive(Clone, Debug, PartialEq, Eq)]
pub(crate) struct Cell {
    /// Its half-spaces.
    pub(crate) constraints: Vec<BigPlane>,
    /// A box containing the cell (Ω's box tightened by axis-aligned constraints).
    pub(crate) bbox: Aabb<Rational>,
    /// Every constraint is axis-aligned: the cell is exactly `bbox` (obstacles of box
    /// pieces in quarter-turn orientations), and its quadratic and linear programs have
    /// closed forms.
    pub(crate) is_box: bool,
}

/// The result of subtracting an obstacle from a cell.
#[derive(Clone, Debug)]
pub(crate) enum Split {
    /// The obstacle's interior does not meet the cell: keep it.
    Unchanged,
    /// The cell minus the open obstacle, as closed convex pieces (possibly none), each
    /// with the half-space that cut it off (none for the last piece when the rest was
    /// found beyond a facet).
    Pieces(Vec<(Cell, Option<BigPlane>)>),
}

/// Counters of the exact work done by subtractions.
#[derive(Clone, Copy, Debug, Default)]
pub(crate) struct SplitStats {
    /// Subtractions decided by the obstacle's vertices alone.
    pub(crate) quick_rejects: usize,
    /// Linear programs solved.
    pub(crate) linear_programs: usize,
    /// Subtractions that went past the quick rejections.
    pub(crate) full: usize,
    /// Pieces produced.
    pub(crate) pieces: usize,
}

impl Cell {
    /// The cell of a box.
    pub(crate) fn of_box(b: &Aabb<Rational>) -> Cell {
        Cell {
            constraints: b.halfspaces(),
            bbox: b.clone(),
            is_box: true,
        }
    }

    /// The lexicographic minimizer of `obj` over the cell ([`lexmin`]; in closed form
    /// for a box cell and a diagonal objective, the same point).
    pub(crate) fn lexmin(&self, obj: &Objective) -> Option<[Rational; 3]> {
        if self.is_box {
            let b = &self.bbox;
            if let Some(p) = lexmin_box(
                [0, 1, 2].map(|i| Some(&b.min[i])),
                [0, 1, 2].map(|i| Some(&b.max[i])),
                obj,
            ) {
                return p;
            }
        }
        lexmin(&self.constraints, obj)
    }

    /// The minimum of `n · p` over the cell and a point attaining it ([`min_linear`];
    /// a corner of a box cell).
    pub(crate) fn min_linear(
        &self,
        n: &[Int; 3],
        lower: &Rational,
    ) -> Option<(Rational, [Rational; 3])> {
        if self.is_box {
            return min_linear_box(&self.bbox, n);
        }
        min_linear(&self.constraints, n, lower)
    }

    /// Adds a half-space (see [`add_constraint`]), tightening the box when it is
    /// axis-aligned.
    pub(crate) fn add(&mut self, h: BigPlane) {
        let axis = (0..3).filter(|&i| h.n[i] != Int::ZERO).collect::<Vec<_>>();
        if axis.len() != 1 {
            self.is_box = false;
        }
        if let [i] = axis[..] {
            let v = Rational::new(h.c.clone(), h.n[i].clone());
            if h.n[i] > Int::ZERO {
                if v < self.bbox.max[i] {
                    self.bbox.max[i] = v;
                }
            } else if v > self.bbox.min[i] {
                self.bbox.min[i] = v;
            }
        }
        add_constraint(&mut self.constraints, h);
    }
}

/// Adds `h` to a list of half-spaces, keeping only the tightest of parallel ones with
/// the same orientation (stacked identical parts give many such planes; without this a
/// cell's list would grow with every obstacle subtracted from it).
pub(crate) fn add_constraint(list: &mut Vec<BigPlane>, h: BigPlane) {
    for g in list.iter_mut() {
        if let Some(cmp) = parallel_offsets(g, &h) {
            if cmp == std::cmp::Ordering::Greater {
                *g = h; // the new one is tighter
            }
            return;
        }
    }
    list.push(h);
}

/// For half-spaces with positively parallel normals, the comparison of their offsets
/// scaled to the same normal (`Less`: `a` is the tighter); `None` otherwise.
fn parallel_offsets(a: &BigPlane, b: &BigPlane) -> Option<std::cmp::Ordering> {
    // b.n = (s / t) a.n with s/t > 0  <=>  a.n × b.n = 0 and a.n · b.n > 0.
    let (x, y) = (&a.n, &b.n);
    let cross_zero = &x[1] * &y[2] == &x[2] * &y[1]
        && &x[2] * &y[0] == &x[0] * &y[2]
        && &x[0] * &y[1] == &x[1] * &y[0];
    if !cross_zero {
        return None;
    }
    // Compare a.c / |a.n| and b.c / |b.n| through one non-zero component i:
    // with b.n_i = k a.n_i, a is tighter when a.c · b.n_i < b.c · a.n_i (same sign).
    let i = (0..3).find(|&i| x[i] != Int::ZERO)?;
    if (x[i] > Int::ZERO) != (y[i] > Int::ZERO) {
        return None;
    }
    let l = &a.c * &y[i];
    let r = &b.c * &x[i];
    Some(if x[i] > Int::ZERO {
        l.cmp(&r)
    } else {
        r.cmp(&l)
    })
}

/// `cell` minus the interior of `obstacle`. `bounds` is a box containing the cell (the
/// region Ω's box): it gives the linear programs a strict lower bound. `known` are
/// points of the cell (e.g. its optimum): signs at known points settle many of the
/// minimum and maximum questions without a linear program.
pub(crate) fn subtract(
    cell: &Cell,
    obstacle: &Obstacle,
    bounds: &Aabb<Rational>,
    known: &[HPoint],
    stats: &mut SplitStats,
) -> Split {
    // Quick rejections: boxes whose interiors are disjoint; the whole obstacle on or
    // beyond one of the cell's own planes.
    if let Some(ob) = &obstacle.bbox {
        if (0..3).any(|i| ob.max[i] <= cell.bbox.min[i] || cell.bbox.max[i] <= ob.min[i]) {
            stats.quick_rejects += 1;
            return Split::Unchanged;
        }
    }
    if let Some(vs) = &obstacle.vertices {
        if cell
            .constraints
            .iter()
            .any(|h| vs.iter().all(|v| h.side(v) != Sign::Negative))
        {
            stats.quick_rejects += 1;
            return Split::Unchanged;
        }
    }
    stats.full += 1;
    let lower = |h: &BigPlane| -> Rational { &bounds.min_dot(&h.n) - &Rational::from(1) };
    let mut rest = cell.clone();
    let mut witnesses: Vec<HPoint> = known.to_vec();
    let mut pieces = Vec::new();
    // Facets in decreasing float distance of a point of the cell beyond them (its known
    // point, or its box centre): a facet separating the cell from the obstacle is then
    // usually tried first, and one linear program settles the subtraction.
    let probe: [f64; 3] = match known.first() {
        Some(p) => p.to_rationals().map(|v| v.to_f64()),
        None => [0, 1, 2].map(|i| (cell.bbox.min[i].to_f64() + cell.bbox.max[i].to_f64()) / 2.0),
    };
    let mut order: Vec<(f64, usize)> = obstacle
        .halfspaces
        .iter()
        .enumerate()
        .map(|(k, h)| {
            let n = h.n.clone().map(|c| apart_kernel::int::to_f64(&c));
            let len = (n[0] * n[0] + n[1] * n[1] + n[2] * n[2]).sqrt();
            let d = (n[0] * probe[0] + n[1] * probe[1] + n[2] * probe[2]
                - apart_kernel::int::to_f64(&h.c))
                / len;
            (if d.is_finite() { -d } else { 0.0 }, k)
        })
        .collect();
    order.sort_by(|a, b| a.0.total_cmp(&b.0));
    for h in order.iter().map(|&(_, k)| &obstacle.halfspaces[k]) {
        // Some point of the rest strictly inside this facet's half-space: the rest is not
        // beyond it. Otherwise the minimum of n · p decides.
        let below = witnesses.iter().any(|w| h.side(w) == Sign::Negative);
        if !below {
            stats.linear_programs += 1;
            let Some((vmin, arg)) = rest.min_linear(&h.n, &lower(h)) else {
                // The rest is empty: only possible for an empty input cell.
                return if pieces.is_empty() {
                    Split::Unchanged
                } else {
                    Split::Pieces(pieces)
                };
            };
            if vmin >= Rational::from_int(h.c.clone()) {
                if pieces.is_empty() {
                    return Split::Unchanged;
                }
                pieces.push((rest, None));
                return Split::Pieces(pieces);
            }
            witnesses.push(HPoint::from_rationals(&arg));
        }
        // A point of the rest on or beyond the plane: a (possibly flat) piece lies beyond.
        let f = h.flipped();
        let beyond = witnesses.iter().any(|w| h.side(w) != Sign::Negative) || {
            stats.linear_programs += 1;
            let (neg_max, arg) = rest
                .min_linear(&f.n, &lower(&f))
                .expect("the rest is not empty");
            witnesses.push(HPoint::from_rationals(&arg));
            -&neg_max >= Rational::from_int(h.c.clone())
        };
        if beyond {
            let mut piece = rest.clone();
            piece.add(f.clone());
            if (0..3).all(|i| piece.bbox.min[i] <= piece.bbox.max[i]) {
                stats.pieces += 1;
                pieces.push((piece, Some(f)));
            }
        }
        witnesses.retain(|w| h.side(w) != Sign::Positive);
        rest.add(h.clone());
    }
    Split::Pieces(pieces)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::testing::q;

    fn cube(lo: i64, hi: i64) -> Aabb<Rational> {
        Aabb {
            min: [q(lo), q(lo), q(lo)],
            max: [q(hi), q(hi), q(hi)],
        }
    }

    fn obstacle(b: &Aabb<Rational>) -> Obstacle {
        let mut vertices = Vec::new();
        for i in 0..8 {
            let p = [0, 1, 2].map(|k| {
                if i >> k & 1 == 1 {
                    b.max[k].clone()
                } else {
                    b.min[k].clone()
                }
            });
            vertices.push(HPoint::from_rationals(&p));
        }
        Obstacle {
            halfspaces: b.halfspaces(),
            vertices: Some(vertices),
            bbox: Some(b.clone()),
        }
    }

    #[test]
    fn subtracting_a_box_from_a_box() {
        let omega = cube(0, 10);
        let cell = Cell::of_box(&omega);
        let mut st = SplitStats::default();
        // Far away: unchanged, decided by the vertices.
        assert!(matches!(
            subtract(&cell, &obstacle(&cube(20, 30)), &omega, &[], &mut st),
            Split::Unchanged
        ));
        assert_eq!(st.quick_rejects, 1);
        // Inside: six pieces around the hole, each avoiding the open obstacle.
        let hole = cube(4, 6);
        let Split::Pieces(pieces) = subtract(&cell, &obstacle(&hole), &omega, &[], &mut st) else {
            panic!()
        };
        assert_eq!(pieces.len(), 6);
        // The nearest free point to the hole's centre lies on its boundary.
        let obj = Objective::distance(&[q(5), q(5), q(5)]);
        let best = pieces
            .iter()
            .filter_map(|(c, _)| lexmin(&c.constraints, &obj))
            .map(|p| obj.value(&p))
            .min()
            .unwrap();
        assert_eq!(best, q(1));
        // An obstacle reaching beyond Ω on every side leaves nothing.
        let Split::Pieces(none) = subtract(&cell, &obstacle(&cube(-1, 11)), &omega, &[], &mut st)
        else {
            panic!()
        };
        assert!(none.is_empty());
    }

    #[test]
    fn parallel_constraints_keep_the_tightest() {
        let h = |n: [i64; 3], off: i64| BigPlane::reduced(n.map(Int::from), Int::from(off));
        let mut list = vec![h([1, 0, 0], 5)];
        add_constraint(&mut list, h([2, 0, 0], 8)); // x <= 4: tighter
        assert_eq!(list, vec![h([2, 0, 0], 8)]);
        add_constraint(&mut list, h([3, 0, 0], 15)); // x <= 5: looser
        assert_eq!(list.len(), 1);
        add_constraint(&mut list, h([-1, 0, 0], 5)); // x >= -5: opposite, kept
        add_constraint(&mut list, h([-2, 0, 0], -3)); // x >= 3/2: tighter than x >= -5
        assert_eq!(list, vec![h([2, 0, 0], 8), h([-2, 0, 0], -3)]);
    }

    #[test]
    fn touching_obstacle_leaves_a_flat_piece() {
        // Ω = [0, 10]^3, obstacle exactly [0, 10] x [0, 10] x [0, 10]: the whole cell is
        // the closed obstacle; its boundary is free but lies on Ω's boundary, so flat
        // pieces remain.
        let omega = cube(0, 10);
        let cell = Cell::of_box(&omega);
        let mut st = SplitStats::default();
        let Split::Pieces(pieces) = subtract(&cell, &obstacle(&omega), &omega, &[], &mut st) else {
            panic!()
        };
        assert!(!pieces.is_empty());
        let obj = Objective::distance(&[q(5), q(5), q(5)]);
        for (c, _) in &pieces {
            let p = lexmin(&c.constraints, &obj).unwrap();
            assert!(!obstacle(&omega).contains_open(&HPoint::from_rationals(&p)));
        }
    }
}
