//! Pictures of apart's results, for people.
//!
//! [`sphere_svg::motion_space_svg`] draws the sphere of directions of a (sub)assembly:
//! both hemispheres in Lambert equal-area projection, every face shaded by how many
//! ordered pairs of parts block it, the arcs of the blocked regions, and the solutions
//! (isolated directions as dots, sliding edges as thick arcs, faces as dots at their
//! deepest direction), coloured by moving subset.

pub mod sphere_svg;

pub use sphere_svg::{motion_space_svg, SphereSvgOptions};
