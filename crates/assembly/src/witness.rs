//! Witnesses of overlaps: exact rational points strictly inside two solids, found by
//! moving a point of one solid's boundary (that is strictly inside the other) a little
//! into the first, and always verified by exact point location before being reported.

use apart_kernel::int::bit_len;
use apart_kernel::orient::{normal, on_triangle};
use apart_kernel::{rational, HPoint};
use apart_kernel::{Grid, Int, Rational, Sign};
use apart_mesh::locate::Locator;
use apart_pieces::Polytope;

/// Step exponents tried when moving a point: 2^-k for k in this list.
const STEPS: [u32; 16] = [1, 2, 3, 4, 6, 8, 12, 16, 24, 32, 48, 64, 96, 128, 192, 256];

/// `2^-k`.
fn pow2(k: u32) -> Rational {
    Rational::pow2(-(k as i32))
}

fn add(a: &[Rational; 3], b: &[Rational; 3], s: &Rational) -> [Rational; 3] {
    [0, 1, 2].map(|k| &a[k] + &(&b[k] * s))
}

/// A point strictly inside both solids near `c`, where `c` lies on the boundary of `a`
/// and strictly inside `b`: `c` is moved towards the centre of a face of `a` through it
/// and then slightly below that face, with ever smaller steps, until exact point
/// location confirms it is inside both.
pub(crate) fn into_both(a: &Locator, b: &Locator, c: &HPoint) -> Option<HPoint> {
    let mesh = a.mesh();
    let mut faces = Vec::new();
    a.bvh().query(&c.bbox(), |t| {
        let [p, q, r] = mesh.corners(t as usize);
        if faces.len() < 8 && on_triangle(c, p, q, r) {
            faces.push(t);
        }
    });
    let cr = c.to_rationals();
    for t in faces {
        let [p, q, r] = mesh.corners(t as usize);
        let g = [0, 1, 2].map(|k| Rational::new(Int::from(p[k]) + q[k] + r[k], Int::from(3)));
        let n = normal(p, q, r).map(Int::from);
        let nb = n.iter().map(bit_len).max().unwrap_or(0);
        let n = n.map(Rational::from_int);
        for k in STEPS {
            let c1 = add(&cr, &rational::sub(&g, &cr), &pow2(k));
            let c2 = add(&c1, &n, &(-&pow2(2 * k + nb)));
            let w = HPoint::from_rationals(&c2);
            if a.strictly_inside(&w) && b.strictly_inside(&w) {
                return Some(w);
            }
        }
    }
    None
}

/// A point strictly inside both solids just below `c`, a point in the relative interior
/// of coincident faces of both with the same outward normal `n`.
pub(crate) fn below_both(
    a: &Locator,
    b: &Locator,
    c: &[Rational; 3],
    n: [i128; 3],
) -> Option<HPoint> {
    let n = n.map(Int::from);
    let nb = n.iter().map(bit_len).max().unwrap_or(0);
    let n = n.map(Rational::from_int);
    for k in STEPS {
        let w = HPoint::from_rationals(&add(c, &n, &(-&pow2(k + nb))));
        if a.strictly_inside(&w) && b.strictly_inside(&w) {
            return Some(w);
        }
    }
    None
}

/// A simpler point than `w` that still passes `inside`: the first of the points of the
/// lattice of spacing 2^-j input units (j = 0, 1, ..., 16) nearest to `w` and its 26
/// lattice neighbours that passes; `w` itself when none does.
pub(crate) fn simplest(
    w: [Rational; 3],
    grid: &Grid,
    inside: impl Fn(&[Rational; 3]) -> bool,
) -> [Rational; 3] {
    let e = grid.exp;
    for j in 0..=16i32 {
        // Multiples of 2^-j input units = 2^(-j - e) grid units.
        let k = -j - e;
        let step = Rational::pow2(k);
        let inv = Rational::new(step.denom().clone(), step.numer().clone());
        let nearest = w.clone().map(|c| {
            let q = &c * &inv;
            // floor(q + 1/2)
            let twice = q.numer() * Int::from(2) + q.denom();
            let d = q.denom() * Int::from(2);
            let mut n = &twice / &d;
            if twice < Int::ZERO && (&n * &d) != twice {
                n -= Int::ONE;
            }
            n
        });
        for o in 0..27i64 {
            let off = [o % 3, o / 3 % 3, o / 9].map(|d| [0, 1, -1][d as usize]);
            let r = [0, 1, 2].map(|c| &Rational::from_int(&nearest[c] + Int::from(off[c])) * &step);
            if inside(&r) {
                return r;
            }
        }
    }
    w
}

/// True when `w` lies strictly inside both polytopes (every facet inequality strict:
/// `n · (den w) < offset` with the polytope's denominator `den`).
pub(crate) fn verified_in_polytopes(w: &[Rational; 3], a: &Polytope, b: &Polytope) -> bool {
    let w = HPoint::from_rationals(w);
    let (num, den) = (w.num(), w.den());
    [a, b].iter().all(|p| {
        p.facets().iter().all(|f| {
            let mut s = -(&f.offset * den);
            for (k, x) in num.iter().enumerate() {
                s += f.normal.get(k) * x * p.den();
            }
            apart_kernel::int::sign_of(&s) == Sign::Negative
        })
    })
}

/// The point in input units, exactly.
pub fn witness_units(w: &[Rational; 3], grid: &Grid) -> [Rational; 3] {
    let scale = Rational::pow2(grid.exp);
    w.clone().map(|c| &c * &scale)
}

/// `(x, y, z)` in input units (decimals, rounded to `f64` for display).
pub fn fmt_witness(w: &[Rational; 3], grid: &Grid) -> String {
    let u = witness_units(w, grid);
    let s = u.map(|c| {
        let v = c.to_f64();
        if v == 0.0 {
            "0".to_string()
        } else {
            format!("{v}")
        }
    });
    format!("({}, {}, {})", s[0], s[1], s[2])
}
