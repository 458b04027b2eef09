//! Exact orientations: quarter turns about x and y, then a rational rotation about z.
//!
//! Paper 004 rotates parts in floating point. Here every rotation is exact so that
//! rotated pieces stay exact polytopes: a turn about z by θ is realised as the rotation
//! with `cos θ' = a/c`, `sin θ' = b/c` where `a² + b² = c²` (a Pythagorean triple), the
//! one with the smallest `c` whose angle `θ'` is within a tolerance of the wanted `θ`
//! (default 0.05°). Every rational point `(cos, sin)` of the unit circle is
//! `((m² − n²), 2mn) / (m² + n²)` for `t = n/m = tan(θ'/2)`, so the search runs over
//! rational approximations of `tan(θ/2)`. Multiples of 90° are exact (`c = 1`). A
//! rotated piece is stored with its vertices multiplied by `c` (its denominator grows by
//! the factor `c`). Base orientations φ (about x) and ψ (about y) are quarter turns,
//! integer matrices.

use apart_kernel::{int, Int, Vec3};
use apart_pieces::Polytope;

/// An exact rotation about z: `cos = a/c`, `sin = b/c`, `a² + b² = c²`, `c > 0`,
/// `gcd(a, b, c) = 1`.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash)]
pub struct ZRotation {
    /// Numerator of the cosine.
    pub a: i64,
    /// Numerator of the sine.
    pub b: i64,
    /// Common denominator.
    pub c: i64,
}

impl ZRotation {
    /// No rotation.
    pub const IDENTITY: ZRotation = ZRotation { a: 1, b: 0, c: 1 };

    /// The exact rotation closest to `angle_deg` among those with the smallest
    /// denominator within `max_error_deg` (`c <= 2^24`; if none is that close, the
    /// closest found).
    pub fn nearest(angle_deg: f64, max_error_deg: f64) -> ZRotation {
        let turns = angle_deg.rem_euclid(360.0);
        let quarter = (turns / 90.0).floor();
        let mut rest = turns - quarter * 90.0;
        let mut quarter = quarter as i64;
        if 90.0 - rest < 1e-9 {
            rest = 0.0;
            quarter += 1;
        }
        let base = if rest < 1e-9 {
            ZRotation::IDENTITY
        } else {
            let t = (rest.to_radians() / 2.0).tan(); // in (0, 1)
            let mut best: Option<(f64, ZRotation)> = None;
            let mut m = 1i64;
            while m * m <= 1 << 24 {
                let n0 = (t * m as f64).round() as i64;
                for n in [n0 - 1, n0, n0 + 1] {
                    if n <= 0 || n > m {
                        continue;
                    }
                    let r = ZRotation::from_half_tangent(n, m);
                    let err = (r.angle_deg() - rest).abs();
                    if err <= max_error_deg {
                        // The first m reaching the tolerance has the smallest c among
                        // the candidates of this search: c grows with m.
                        return r.quarter_turns(quarter);
                    }
                    if best.as_ref().is_none_or(|(e, _)| err < *e) {
                        best = Some((err, r));
                    }
                }
                m += 1;
            }
            best.expect("some rotation").1
        };
        base.quarter_turns(quarter)
    }

    /// The rotation by `2 atan(n/m)`.
    pub(crate) fn from_half_tangent(n: i64, m: i64) -> ZRotation {
        let (a, b, c) = (m * m - n * n, 2 * m * n, m * m + n * n);
        ZRotation::reduced(a, b, c)
    }

    fn reduced(a: i64, b: i64, c: i64) -> ZRotation {
        let g = int::gcd_u128(
            int::gcd_u128(a.unsigned_abs() as u128, b.unsigned_abs() as u128),
            c.unsigned_abs() as u128,
        ) as i64;
        let s = if c < 0 { -g } else { g };
        ZRotation {
            a: a / s,
            b: b / s,
            c: c / s,
        }
    }

    /// `self` followed by `k` quarter turns (counter-clockwise).
    pub(crate) fn quarter_turns(self, k: i64) -> ZRotation {
        let mut r = self;
        for _ in 0..k.rem_euclid(4) {
            r = ZRotation {
                a: -r.b,
                b: r.a,
                c: r.c,
            };
        }
        r
    }

    /// The rotation by the sum of both angles.
    pub(crate) fn then(self, o: ZRotation) -> ZRotation {
        ZRotation::reduced(
            self.a * o.a - self.b * o.b,
            self.a * o.b + self.b * o.a,
            self.c * o.c,
        )
    }

    /// The inverse rotation.
    pub(crate) fn inverse(self) -> ZRotation {
        ZRotation {
            a: self.a,
            b: -self.b,
            c: self.c,
        }
    }

    /// The angle in degrees, in `[0, 360)`.
    pub fn angle_deg(&self) -> f64 {
        (self.b as f64)
            .atan2(self.a as f64)
            .to_degrees()
            .rem_euclid(360.0)
    }

    /// `c` times the rotated integer vector: `(a x − b y, b x + a y, c z)`.
    pub(crate) fn apply_scaled(&self, v: &Vec3) -> Vec3 {
        let [x, y, z] = v.to_ints();
        let (a, b, c) = (Int::from(self.a), Int::from(self.b), Int::from(self.c));
        Vec3::from_ints([&a * &x - &b * &y, &b * &x + &a * &y, &c * &z])
    }
}

/// A quarter-turn base orientation: `phi` quarter turns about x, then `psi` about y.
#[derive(Clone, Copy, Debug, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub struct Base {
    /// Quarter turns about x (0–3).
    pub phi: u8,
    /// Quarter turns about y (0–3).
    pub psi: u8,
}

impl Base {
    /// No rotation.
    pub const IDENTITY: Base = Base { phi: 0, psi: 0 };

    /// Applies the base rotation to an integer vector (exact, no scaling).
    pub(crate) fn apply(&self, v: &Vec3) -> Vec3 {
        let [mut x, mut y, mut z] = v.to_ints();
        for _ in 0..self.phi % 4 {
            // About x: (x, y, z) -> (x, −z, y).
            let ny = -z.clone();
            z = y;
            y = ny;
        }
        for _ in 0..self.psi % 4 {
            // About y: (x, y, z) -> (z, y, −x).
            let nx = z.clone();
            z = -x;
            x = nx;
        }
        Vec3::from_ints([x, y, z])
    }
}

/// An orientation of a part: the base quarter turns, then the exact turn about z.
#[derive(Clone, Copy, Debug, PartialEq)]
pub struct Orientation {
    /// Quarter turns about x and y, applied first.
    pub base: Base,
    /// The exact rotation about z, applied last.
    pub theta: ZRotation,
    /// The angle asked for, in degrees (`theta` is within the tolerance of it).
    pub wanted_deg: f64,
}

impl Orientation {
    /// The identity.
    pub const IDENTITY: Orientation = Orientation {
        base: Base::IDENTITY,
        theta: ZRotation::IDENTITY,
        wanted_deg: 0.0,
    };

    /// `[phi, psi, theta]` in degrees (theta the exact rotation's angle).
    pub fn degrees(&self) -> [f64; 3] {
        [
            90.0 * self.base.phi as f64,
            90.0 * self.base.psi as f64,
            self.theta.angle_deg(),
        ]
    }

    /// `|theta − wanted|` in degrees.
    pub fn angular_error_deg(&self) -> f64 {
        let d = (self.theta.angle_deg() - self.wanted_deg).rem_euclid(360.0);
        d.min(360.0 - d)
    }

    /// `c` times the rotated integer vector.
    pub(crate) fn apply_scaled(&self, v: &Vec3) -> Vec3 {
        self.theta.apply_scaled(&self.base.apply(v))
    }

    /// The polytope rotated: stored integers times `c`, denominator times `c`.
    pub(crate) fn rotate(&self, p: &Polytope) -> Polytope {
        rotate_polytope(p, |v| self.apply_scaled(v), self.theta.c)
    }
}

/// Applies a rotation given as `v -> c R v` (integers) to a polytope.
pub(crate) fn rotate_polytope(p: &Polytope, f: impl Fn(&Vec3) -> Vec3, c: i64) -> Polytope {
    let points: Vec<Vec3> = p.vertices().iter().map(&f).collect();
    let facets: Vec<(Vec3, Vec<u32>)> = p
        .facets()
        .iter()
        .map(|fc| (f(&fc.normal).primitive(), fc.cycle.clone()))
        .collect();
    Polytope::from_facets(&points, facets)
        .expect("a rotation keeps a polytope valid")
        .with_den(p.den() * Int::from(c))
}

/// The orientations `θ_k = k·Δθ` (k = 0, 1, … while below 360°) for each base
/// orientation, as exact rotations within `max_error_deg` of the wanted angles.
pub fn orientations(dtheta_deg: f64, bases: &[Base], max_error_deg: f64) -> Vec<Orientation> {
    let steps = if dtheta_deg <= 0.0 || dtheta_deg >= 360.0 {
        1
    } else {
        (360.0 / dtheta_deg - 1e-9).ceil() as usize
    };
    let mut out = Vec::new();
    for &base in bases {
        for k in 0..steps {
            let wanted = k as f64 * dtheta_deg;
            out.push(Orientation {
                base,
                theta: ZRotation::nearest(wanted, max_error_deg),
                wanted_deg: wanted,
            });
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn pythagorean_rotations() {
        for k in 0..360 {
            let r = ZRotation::nearest(k as f64, 0.05);
            assert_eq!(r.a * r.a + r.b * r.b, r.c * r.c);
            let d = (r.angle_deg() - k as f64).rem_euclid(360.0);
            assert!(d.min(360.0 - d) <= 0.05, "{k}: {r:?}");
        }
        assert_eq!(
            ZRotation::nearest(90.0, 0.05),
            ZRotation { a: 0, b: 1, c: 1 }
        );
        assert_eq!(
            ZRotation::nearest(180.0, 0.05),
            ZRotation { a: -1, b: 0, c: 1 }
        );
        let r = ZRotation::nearest(36.87, 0.01); // the 3-4-5 triangle
        assert_eq!(r, ZRotation { a: 4, b: 3, c: 5 });
    }

    #[test]
    fn composition_and_inverse() {
        let r = ZRotation::from_half_tangent(1, 2); // (3, 4, 5)
        assert_eq!(r.then(r.inverse()), ZRotation::IDENTITY);
        let v = Vec3::new(5, 0, 1);
        assert_eq!(r.apply_scaled(&v), Vec3::new(15, 20, 5));
    }

    #[test]
    fn base_quarter_turns() {
        let b = Base { phi: 1, psi: 0 };
        assert_eq!(b.apply(&Vec3::new(0, 1, 0)), Vec3::new(0, 0, 1));
        let b = Base { phi: 0, psi: 1 };
        assert_eq!(b.apply(&Vec3::new(1, 0, 0)), Vec3::new(0, 0, -1));
        let b = Base { phi: 2, psi: 0 };
        assert_eq!(b.apply(&Vec3::new(1, 2, 3)), Vec3::new(1, -2, -3));
    }
}
