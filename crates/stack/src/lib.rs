//! Interference-free placement and stacking of polyhedral parts by exact c-space
//! obstacles (paper 004, Ayyadevara et al.).
//!
//! A new part made of convex pieces is placed among fixed parts by translating it after
//! one of a set of discrete orientations. For a fixed orientation the translations that
//! make a moving piece `a` overlap a fixed piece `b` form the convex c-space obstacle
//! `conv{b − a} = b ⊕ (−a)` ([`obstacle`]); the free space is a union of convex cells of
//! linear inequalities (module `free_space`); a convex quadratic cost is minimized
//! exactly in each cell (module `qp`). Only the obstacle of one pair found interfering at the
//! current candidate is built at a time (partial c-space, [`partial`]), over all orientations at once
//! with one priority queue; obstacles are extrapolated between orientations about z
//! inside constant-topology intervals ([`extrapolate`]). The stacking planner
//! ([`planner`]) adds identical parts one by one with the cost of paper 004 eq. (1),
//! accepting a candidate only if it is stable, grippable from above and can be lowered
//! into place ([`stability`]). Pictures of placements and stacks are apart-draw's
//! (`apart_draw::stack_render`); the test parts are apart-testkit's (`sheet_metal`).
//!
//! The public API is what a user of placement needs: [`partial::place`] (positions of
//! a new part among fixed ones, cheapest first) and [`planner::stack`] (a stack of
//! identical parts), their options and answers, the part model, exact orientations, and
//! for measurements the obstacle and its extrapolation; the cells, the solvers and the
//! broad phase are internal. Its numbers, points, half-spaces and boxes are apart-kernel's
//! (`Rational`, `HPoint`, `BigPlane`, `Aabb<Rational>`), its broad phase the kernel's
//! `Bvh`, its interference test apart-pieces' separating axes.
//!
//! Exactness: inputs are integers (grid points); orientations about z are exact rational
//! rotations from Pythagorean triples ([`orientation`]); positions, costs, obstacles and
//! cells are exact rationals. No epsilon decides anything; floating point appears only in
//! the broad phase (conservative boxes), in reported angles and in pictures.
//!
//! ```
//! use apart_kernel::{Aabb, Rational};
//! use apart_stack::orientation::{orientations, Base};
//! use apart_stack::partial::{place, Cost, Moving, PlaceOptions, Region};
//! use apart_stack::part::PartModel;
//! use apart_stack::scene::Scene;
//! // A unit cube on the floor at the origin; place another as close to it as possible.
//! let cube = apart_pieces::Polytope::cuboid([0, 0, 0], [1, 1, 1]).unwrap();
//! let part = PartModel::from_pieces("cube", vec![cube]).unwrap();
//! let mut scene = Scene::new();
//! scene.add_fixed_part(&part.pieces);
//! let moving = Moving::new(part, &orientations(90.0, &[Base::IDENTITY], 0.05), true);
//! let opts = PlaceOptions {
//!     region: Region::Container(Aabb {
//!         min: [-5, -5, 0].map(Rational::from),
//!         max: [5, 5, 5].map(Rational::from),
//!     }),
//!     cost: Cost::Distance([0, 0, 0].map(Rational::from)),
//!     clearance: None,
//!     extrapolate: true,
//! };
//! let best = &place(&scene, &moving, &opts, 1).unwrap().candidates[0];
//! assert_eq!(best.cost, Rational::from(1)); // touching a face of the fixed cube
//! ```

pub mod extrapolate;
mod free_space;
mod guide;
pub mod obstacle;
pub mod orientation;
pub mod part;
pub mod partial;
pub mod planner;
mod qp;
pub mod scene;
pub mod stability;

/// Shorthands for the exact numbers of the unit tests.
#[cfg(test)]
pub(crate) mod testing {
    use apart_kernel::{Rational, Vec3};
    use apart_pieces::Polytope;

    /// The unit cube with its lowest corner at `o`.
    pub(crate) fn unit(o: [i64; 3]) -> Polytope {
        let pts: Vec<Vec3> = (0..8)
            .map(|i| Vec3::new(o[0] + (i & 1), o[1] + (i >> 1 & 1), o[2] + (i >> 2 & 1)))
            .collect();
        Polytope::hull_of_points(&pts).unwrap()
    }

    /// The integer `v`.
    pub(crate) fn q(v: i64) -> Rational {
        Rational::from(v)
    }

    /// `n / d`.
    pub(crate) fn qfrac(n: i64, d: i64) -> Rational {
        Rational::from_i128(n.into(), d.into())
    }
}
