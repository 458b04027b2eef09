//! Generators of test inputs for apart, modelled on what CAD exporters produce, and an
//! independent blocking oracle.
//!
//! Everything here is plain data ([`Soup`]: `f64` vertices and polygons;
//! [`solids::IntMesh`]: integer points and triangles; [`assemblies::Piece`]: boxes and
//! hulls of integer points) with no apart dependency, so that the tests, examples and
//! benchmarks of every crate can use it without a dependency cycle; each crate turns it
//! into its own types in a small adapter of its own. Each generator documents the answer
//! it is built to have, so tests compare apart's results with that known answer, never
//! with apart's own output.
//!
//! - [`defects`]: meshes with the defects of real exports (T-junction seams,
//!   float32-rounded coordinates, duplicated and flipped faces, holes, several bodies
//!   in one file, self-crossing folds).
//! - [`curved`]: tessellated curved parts (pins in holes with different segment counts,
//!   plugs and sockets, a nut on a bolt), whose fits interpenetrate by a known depth.
//! - [`joints`]: a five-part bolted joint whose parts are tessellated differently.
//! - [`solids`]: integer meshes from grids (voxel unions, unions of grid cells) and
//!   polygons (ear clipping), and the seeded generator [`solids::Lcg`].
//! - [`sheet_metal`]: the parametric parts of the stacking paper (cube, channel,
//!   triangle, complex part) as integer meshes.
//! - [`shapes`]: integer solids with their volume, reflex edges and classified sample
//!   points known by hand (grid unions, a polygonal ring, the Schönhardt prism, terrains).
//! - [`assemblies`]: assemblies of convex pieces (the Split Star, a dovetail, a peg in a
//!   hole, linked rings, cube lattices, random boxes, rows of bricks).
//! - [`torus`]: a large closed torus as binary STL, for loading benchmarks.
//! - [`soups`]: triangle soups that only the winding-number rule makes solid (a rim
//!   of doubled-back faces, a thread of crossing rings with open seams and slivers, gear
//!   flanks that cross, a fillet folded over itself, overlapping shells), each with
//!   the exact volume of its solid and a two-part assembly with a known plan.
//! - [`winding`]: the independent oracle for that rule: exact winding numbers of
//!   points (`i128`, a symbolically perturbed ray) and a seeded Monte Carlo volume
//!   with a confidence bound.
//! - [`voxel_puzzles`]: the level of voxel interlocking puzzles by exhaustive search
//!   over moves of whole steps, with a witness plan; [`voxel_generate`]: puzzles of a
//!   chosen level by hill climbing on that level (optionally only puzzles that come
//!   apart completely), and their boundary meshes; [`voxel_bench`]: a committed
//!   fixture of complete puzzles of 4 to 8 pieces and levels 2 and up, for benchmarks.
//! - [`moves`]: two-part assemblies off the grid that come apart in two moves and not
//!   in one (a slot at 45°, a keyhole, a drawer behind a lip, a slanted channel), with
//!   the first move's direction and extent known by construction.
//! - [`oracle`]: whether one convex piece sweeping along a direction meets another's
//!   interior, by an exact linear program generic over the caller's rationals.

pub mod assemblies;
pub mod curved;
pub mod defects;
pub mod joints;
pub mod moves;
pub mod oracle;
mod scratch;
pub mod shapes;
pub mod sheet_metal;
pub mod solids;
mod soup;
pub mod soups;
pub mod torus;
pub mod voxel_bench;
pub mod voxel_generate;
pub mod voxel_puzzles;
pub mod winding;

pub use scratch::Scratch;
pub use soup::{base64, Soup};
