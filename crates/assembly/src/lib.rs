//! The assembly model of apart and its loader.
//!
//! An [`Assembly`] is an ordered list of named [`Part`]s on one integer grid: each part
//! a closed solid (a validated [`apart_mesh::Mesh`]), with the convex pieces
//! ([`apart_pieces::Polytope`]) whose union it is when they are known. [`load`] accepts
//!
//! - a folder of mesh files, one part per file (name = file stem, parts sorted by
//!   name), where a sub-folder with a part's name (or alone) holds its convex pieces;
//! - one mesh file: each object (OBJ `o`/`g` group, glTF mesh node) is a part;
//! - an `assembly.json` manifest, or a folder containing one (see [`manifest`]).
//!
//! [`load_description`] accepts the same assembly held in memory, a [`Description`]:
//! in effect a manifest whose parts' meshes and pieces are files ([`MeshSource::File`],
//! read wherever they lie: the caller named them) or arrays of vertices and triangles
//! ([`MeshSource::Arrays`], named in problems by part and element only). A manifest is
//! read into a description and loaded by the same code, so both meet the same
//! validation, repair, decomposition, tolerance and overlap checks. The command line's
//! `apart separate A.off B.off` and Python's arrays go through it, without temporary
//! files.
//!
//! Only regular files are read: a folder entry with a mesh extension, or a path a
//! manifest names, that is a named pipe, a socket or a device is an error naming the
//! file and the part, and is never opened. Every mesh file of a folder or manifest must
//! resolve inside the assembly's folder (`..`, absolute paths and symbolic links
//! followed), unless [`LoadOptions::allow_outside`].
//!
//! The grid is chosen once from every coordinate of every part and piece (after
//! transforms); a part the grid collapses says which part's coordinates set the step,
//! and two parts whose relation (apart, touching, overlapping) snapping changed get a
//! warning naming both, the distance or depth, and the grid bits that keep it. Loading
//! collects every problem rather than stopping at the first: the
//! validity of each part as a solid, of each declared piece (closed, convex), of the
//! pieces of a part (disjoint interiors, volumes adding up to the part's), and of the
//! parts together (disjoint interiors, each overlap with a witness point strictly
//! inside both, verified exactly).
//!
//! [`LoadOptions::progress`] (the kernel's [`apart_kernel::progress::Progress`], as the
//! planners take) reports each phase and carries a stop flag: raised, loading ends
//! with [`LoadError::Stopped`].
//!
//! ```no_run
//! use apart_assembly::{load, LoadOptions};
//! let loaded = load(std::path::Path::new("examples/split-star"), &LoadOptions::default()).unwrap();
//! assert!(loaded.is_valid());
//! for part in &loaded.assembly.parts {
//!     println!("{}: volume {}", part.name, part.volume_units(&loaded.assembly.grid));
//! }
//! ```

mod convex;
pub mod description;
mod error;
mod inputs;
mod load;
pub mod manifest;
mod model;
mod options;
mod overlap;
mod pieces;
mod snapping;
pub mod tolerance;
mod witness;

/// Problems are defined with the meshes and shared by the loader.
pub use apart_mesh::{Problem, Severity};
pub use description::{DescribedPart, Description, MeshSource};
pub use error::LoadError;
pub use load::{load, load_description};
pub use model::{Assembly, LoadSeconds, Loaded, Part, Repairs, Skipped, WindingReport};
pub use options::{Decompose, LoadOptions};
pub use tolerance::{AppliedTolerance, Tolerance};
pub use witness::{fmt_witness, witness_units};

use apart_kernel::{Grid, Rational};

/// A volume in grid units, printed in input units as `exact (≈ decimal)`.
pub fn fmt_volume(v: &Rational, grid: &Grid) -> String {
    let u = apart_mesh::validate::volume_in_units(v, grid);
    if u.denom() == apart_kernel::Int::ONE {
        u.to_string()
    } else {
        format!("{u} (≈ {})", u.to_f64())
    }
}

/// The point strictly inside both parts, when their interiors overlap (exact, grid
/// units); `None` when they are disjoint or only touch. Exposed for the planners and
/// for tests; [`load`] already reports overlaps.
pub fn parts_overlap(a: &Part, b: &Part, grid: &Grid) -> Option<[Rational; 3]> {
    overlap::part_overlap(a, b, grid)
}
