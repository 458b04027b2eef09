//! The directions a search tries from a state, and the grid step of moves along an axis.

use apart_kernel::{int, Int, Rational, Vec3};
use apart_pieces::polytope::canonical_sign;
use apart_pieces::Polytope;

/// `+x, −x, +y, −y, +z, −z`.
pub fn axes() -> Vec<Vec3> {
    let mut out = Vec::with_capacity(6);
    for k in 0..3 {
        let mut c = [0i64; 3];
        c[k] = 1;
        out.push(Vec3::from_i64(c));
        c[k] = -1;
        out.push(Vec3::from_i64(c));
    }
    out
}

/// The candidate directions at a state with the given contact normals: the axes, then
/// each normal and each line where two contact planes meet, both ways: the extreme
/// directions of the locally free cone (bounded by the contact planes) are among them.
pub fn candidates(normals: &[Vec3]) -> Vec<Vec3> {
    let mut lines: Vec<Vec3> = normals
        .iter()
        .map(|n| canonical_sign(n.primitive()))
        .collect();
    lines.sort_by_key(|v| v.to_ints());
    lines.dedup();
    let mut extra: Vec<Vec3> = lines.clone();
    for (k, a) in lines.iter().enumerate() {
        for b in &lines[k + 1..] {
            let c = a.cross(b);
            if !c.is_zero() {
                extra.push(canonical_sign(c.primitive()));
            }
        }
    }
    extra.sort_by_key(|v| v.to_ints());
    extra.dedup();
    let mut out = axes();
    for e in extra {
        for d in [e.clone(), e.neg()] {
            if !out.contains(&d) {
                out.push(d);
            }
        }
    }
    out
}

/// The grid step along each axis: the greatest common divisor of the differences of
/// every piece's vertex coordinates along it (a voxel puzzle's cell size), or `None`
/// along an axis where every vertex has the same coordinate (impossible for solids).
pub fn lattice_steps(pieces: &[&Polytope]) -> [Option<Rational>; 3] {
    [0, 1, 2].map(|k| {
        let mut first: Option<Rational> = None;
        let mut g: Option<Rational> = None;
        for p in pieces {
            let den = Rational::from_int(p.den().clone());
            for v in p.vertices() {
                let x = &Rational::from_int(v.get(k)) / &den;
                let Some(f) = &first else {
                    first = Some(x);
                    continue;
                };
                let diff = (&x - f).abs();
                if diff.is_zero() {
                    continue;
                }
                g = Some(match g {
                    None => diff,
                    Some(g) => gcd(&g, &diff),
                });
            }
        }
        g
    })
}

/// The greatest common divisor of two positive rationals: `gcd(a d, c b) / (b d)`.
fn gcd(x: &Rational, y: &Rational) -> Rational {
    let (a, b, c, d) = (x.numer(), x.denom(), y.numer(), y.denom());
    let n: Int = int::gcd(&(&a * &d), &(&c * &b));
    Rational::new(n, &b * &d)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn two_walls_meet_along_the_diagonal_slot() {
        let n = [Vec3::new(1, -1, 0), Vec3::new(0, 0, 1)];
        let c = candidates(&n);
        assert!(c.contains(&Vec3::new(1, 1, 0)) && c.contains(&Vec3::new(-1, -1, 0)));
        assert!(c.contains(&Vec3::new(-1, 1, 0)));
        assert_eq!(c.len(), 10, "{c:?}");
    }

    #[test]
    fn cubes_of_size_three_have_step_three() {
        let a = Polytope::cuboid([0, 0, 0], [3, 6, 3]).unwrap();
        let b = Polytope::cuboid([3, 0, 9], [9, 3, 12]).unwrap();
        let s = lattice_steps(&[&a, &b]);
        assert_eq!(s, [0, 1, 2].map(|_| Some(Rational::from(3))));
    }

    #[test]
    fn rational_steps_divide_both() {
        let g = gcd(&Rational::from_i128(3, 2), &Rational::from_i128(5, 3));
        assert_eq!(g, Rational::from_i128(1, 6));
    }
}
