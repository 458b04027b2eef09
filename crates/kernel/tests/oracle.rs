//! Property tests of the predicates against a slow arbitrary-precision reference.
//!
//! The reference evaluates each polynomial term by term in `Int` with no filter and no
//! machine-integer path. Inputs are random, exactly degenerate (coplanar, collinear,
//! coincident, antipodal) and nearly degenerate (one unit off a degenerate input), at grid
//! sizes (30 bits) and at constructed sizes (up to ~250 bits).

use apart_kernel::predicates::{det3_sign, dot_sign, parallel, same_direction};
use apart_kernel::spherical::{arc_position, ccw_along, circle_intersection, ArcPosition};
use apart_kernel::{Int, Sign, Vec3};
use proptest::prelude::*;

fn sign(v: &Int) -> Sign {
    if *v > Int::ZERO {
        Sign::Positive
    } else if *v < Int::ZERO {
        Sign::Negative
    } else {
        Sign::Zero
    }
}

fn ints(v: &Vec3) -> [Int; 3] {
    [v.get(0), v.get(1), v.get(2)]
}

fn ref_dot(a: &Vec3, b: &Vec3) -> Int {
    let (a, b) = (ints(a), ints(b));
    &a[0] * &b[0] + &a[1] * &b[1] + &a[2] * &b[2]
}

fn ref_cross(a: &Vec3, b: &Vec3) -> [Int; 3] {
    let (a, b) = (ints(a), ints(b));
    [
        &a[1] * &b[2] - &a[2] * &b[1],
        &a[2] * &b[0] - &a[0] * &b[2],
        &a[0] * &b[1] - &a[1] * &b[0],
    ]
}

/// Rule of Sarrus, independent of the a · (b × c) form the kernel uses.
fn ref_det(a: &Vec3, b: &Vec3, c: &Vec3) -> Int {
    let (a, b, c) = (ints(a), ints(b), ints(c));
    &a[0] * &b[1] * &c[2] + &a[1] * &b[2] * &c[0] + &a[2] * &b[0] * &c[1]
        - &a[2] * &b[1] * &c[0]
        - &a[1] * &b[0] * &c[2]
        - &a[0] * &b[2] * &c[1]
}

/// A vector with components of up to `bits` bits, built from several random words so
/// that large values are not just scaled small ones.
fn vec_of(bits: u32) -> impl Strategy<Value = Vec3> {
    prop::array::uniform3(prop::collection::vec(any::<u64>(), 4)).prop_map(move |words| {
        let c = words.map(|w| {
            let mut v = Int::ZERO;
            for x in &w {
                v = (v << 64usize) + Int::from(*x);
            }
            let v = v >> (256 - bits as usize);
            if w[0] & 1 == 1 {
                -v
            } else {
                v
            }
        });
        Vec3::from_ints(c)
    })
}

fn any_size() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        vec_of(3),
        vec_of(31),
        vec_of(41),
        vec_of(45),
        vec_of(63),
        vec_of(127),
        vec_of(250)
    ]
}

/// Vectors far beyond the f64 range (about 1,500 bits), with components of very
/// different sizes now and then (the filter must stay exact or step aside).
fn huge() -> impl Strategy<Value = Vec3> {
    (vec_of(120), 1300usize..1500, 0usize..3, prop::bool::ANY).prop_map(
        |(v, shift, k, wide_range)| {
            let mut c = v.to_ints().map(|x| (x << shift) + Int::from(7));
            if wide_range {
                c[k] = Int::from(3); // a tiny component next to huge ones
            }
            Vec3::from_ints(c)
        },
    )
}

fn small_int() -> impl Strategy<Value = i64> {
    -5i64..=5
}

fn unit() -> impl Strategy<Value = Vec3> {
    prop_oneof![
        Just(Vec3::new(1, 0, 0)),
        Just(Vec3::new(0, 1, 0)),
        Just(Vec3::new(0, 0, 1)),
        Just(Vec3::new(-1, 0, 0)),
        Just(Vec3::new(0, -1, 0)),
        Just(Vec3::new(0, 0, -1)),
    ]
}

proptest! {
    #![proptest_config(ProptestConfig::with_cases(2000))]

    #[test]
    fn det3_random(a in any_size(), b in any_size(), c in any_size()) {
        prop_assert_eq!(det3_sign(&a, &b, &c), sign(&ref_det(&a, &b, &c)));
    }

    #[test]
    fn det3_coplanar(a in any_size(), b in any_size(), k in small_int(), l in small_int()) {
        // c = k a + l b lies in the plane of a and b: exactly zero.
        let c = a.scale(&Int::from(k)).add(&b.scale(&Int::from(l)));
        prop_assert_eq!(det3_sign(&a, &b, &c), Sign::Zero);
        prop_assert_eq!(det3_sign(&c, &a, &b), Sign::Zero);
        prop_assert_eq!(det3_sign(&a, &b, &c), sign(&ref_det(&a, &b, &c)));
    }

    #[test]
    fn det3_one_unit_off(a in any_size(), b in any_size(), k in small_int(), l in small_int(), e in unit()) {
        let c = a.scale(&Int::from(k)).add(&b.scale(&Int::from(l))).add(&e);
        prop_assert_eq!(det3_sign(&a, &b, &c), sign(&ref_det(&a, &b, &c)));
        prop_assert_eq!(det3_sign(&b, &c, &a), sign(&ref_det(&b, &c, &a)));
    }

    #[test]
    fn det3_collinear_coincident_antipodal(a in any_size(), b in any_size(), k in 1i64..7) {
        let ka = a.scale(&Int::from(k));
        prop_assert_eq!(det3_sign(&a, &ka, &b), Sign::Zero);
        prop_assert_eq!(det3_sign(&a, &a, &b), Sign::Zero);
        prop_assert_eq!(det3_sign(&a, &a.neg(), &b), Sign::Zero);
    }

    #[test]
    fn huge_vectors(a in huge(), b in huge(), c in any_size(), k in small_int(), l in small_int()) {
        prop_assert_eq!(det3_sign(&a, &b, &c), sign(&ref_det(&a, &b, &c)));
        prop_assert_eq!(dot_sign(&a, &b), sign(&ref_dot(&a, &b)));
        let d = a.scale(&Int::from(k)).add(&b.scale(&Int::from(l)));
        prop_assert_eq!(det3_sign(&a, &b, &d), Sign::Zero);
        let e = d.add(&Vec3::new(0, 0, 1));
        prop_assert_eq!(det3_sign(&a, &b, &e), sign(&ref_det(&a, &b, &e)));
        prop_assert_eq!(dot_sign(&a.cross(&b), &e), sign(&ref_dot(&a.cross(&b), &e)));
    }

    #[test]
    fn dot_random_and_degenerate(a in any_size(), b in any_size(), e in unit()) {
        prop_assert_eq!(dot_sign(&a, &b), sign(&ref_dot(&a, &b)));
        // a × b is perpendicular to a: exactly zero, and one unit off.
        let p = a.cross(&b);
        prop_assert_eq!(dot_sign(&a, &p), Sign::Zero);
        let q = p.add(&e);
        prop_assert_eq!(dot_sign(&a, &q), sign(&ref_dot(&a, &q)));
    }

    #[test]
    fn cross_and_parallel(a in any_size(), b in any_size(), k in 1i64..9) {
        prop_assert_eq!(ints(&a.cross(&b)), ref_cross(&a, &b));
        let ka = a.scale(&Int::from(k));
        prop_assert!(parallel(&a, &ka));
        prop_assert_eq!(same_direction(&a, &ka), !a.is_zero());
        prop_assert_eq!(same_direction(&a, &ka.neg()), false);
        let non_par = ref_cross(&a, &b).iter().any(|v| *v != Int::ZERO);
        prop_assert_eq!(parallel(&a, &b), !non_par);
    }

    #[test]
    fn primitive_is_canonical(a in any_size(), k in 1i64..1000) {
        let ka = a.scale(&Int::from(k));
        prop_assert_eq!(ka.primitive(), a.primitive());
        prop_assert!(same_direction(&a, &a.primitive()) || a.is_zero());
    }

    /// Position along an arc against barycentric coordinates: p = λ s + μ e with
    /// λ = (p × e)·(s × e) and μ = (s × p)·(s × e) (Binet–Cauchy), up to the positive
    /// factor |s × e|².
    #[test]
    fn arc_position_matches_barycentric(s in any_size(), e in any_size(), k in -3i64..=3, l in -3i64..=3, off in prop::bool::ANY) {
        let n = s.cross(&e);
        prop_assume!(!n.is_zero());
        let n = n.primitive();
        // A point on the circle: k s + l e (exactly on it), or an intersection with another
        // circle through a perturbed point.
        let p = if off {
            let other = s.add(&Vec3::new(0, 0, 1)).cross(&e.add(&Vec3::new(1, 0, 0)));
            match circle_intersection(&n, &other) { Some(p) => p, None => return Ok(()) }
        } else {
            s.scale(&Int::from(k)).add(&e.scale(&Int::from(l)))
        };
        prop_assume!(!p.is_zero());
        let se = Vec3::from_ints(ref_cross(&s, &e));
        let lam = sign(&ref_dot(&Vec3::from_ints(ref_cross(&p, &e)), &se));
        let mu = sign(&ref_dot(&Vec3::from_ints(ref_cross(&s, &p)), &se));
        let expected = match (lam, mu) {
            (Sign::Positive, Sign::Positive) => ArcPosition::Interior,
            (Sign::Positive, Sign::Zero) => ArcPosition::Start,
            (Sign::Zero, Sign::Positive) => ArcPosition::End,
            _ => ArcPosition::Outside,
        };
        prop_assert_eq!(arc_position(&n, &s, &e, &p), expected);
        prop_assert_eq!(ccw_along(&n, &s, &e), Sign::Positive);
    }
}
