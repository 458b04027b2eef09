//! The assembly model: an ordered list of named parts on one integer grid.

use crate::tolerance::AppliedTolerance;
use apart_kernel::Aabb;
use apart_kernel::{Grid, Rational};
use apart_mesh::repair::RepairReport;
use apart_mesh::validate::{volume_in_units, MeshInfo};
use apart_mesh::{Mesh, Problem};
use apart_pieces::Polytope;
use std::path::PathBuf;

/// One part: a closed solid, with the convex pieces whose union it is when known.
#[derive(Clone, Debug)]
pub struct Part {
    /// The part's name (unique in the assembly).
    pub name: String,
    /// Where the part came from: its mesh file, or its pieces' folder or manifest; empty
    /// for a part whose mesh was given as arrays (or that was built in code).
    pub source: PathBuf,
    /// The boundary, snapped and validated; `None` when only pieces were given (or the
    /// mesh could not be read).
    pub mesh: Option<Mesh>,
    /// What validating the boundary learnt (counts, volume, bounding box, convexity).
    pub info: Option<MeshInfo>,
    /// Convex pieces with disjoint interiors whose union is the part: the declared
    /// pieces, or the part itself when it is convex, or empty for a non-convex part
    /// without declared pieces.
    pub pieces: Vec<Polytope>,
    /// The file of each declared piece (empty when the pieces were not declared; an
    /// empty path for a piece given as arrays).
    pub piece_sources: Vec<PathBuf>,
    /// The pieces were declared in the input (not derived from a convex part).
    pub declared_pieces: bool,
    /// The pieces come from an exact convex decomposition of the mesh.
    pub decomposed: bool,
    /// The part is convex.
    pub convex: bool,
    /// Exact volume in grid units (zero when unknown because the input is invalid).
    pub volume: Rational,
    /// Edges whose dihedral angle inside the part exceeds 180 degrees.
    pub reflex_edges: usize,
    /// Bounding box in grid units (of the mesh, or of the pieces).
    pub bbox: Option<Aabb>,
    /// The pieces before a tolerance shrank them (empty when no tolerance applies):
    /// what the part really is, for telling which answers hold only under the
    /// tolerance.
    pub unshrunk_pieces: Vec<Polytope>,
    /// How the part's solid was made from a surface that is not a closed manifold (the
    /// points its faces wind around at least once), when it was.
    pub winding: Option<WindingReport>,
}

/// What making a solid of a surface that is not a closed manifold did: the points its
/// faces wind around at least once, after closing the boundary loops that are planar
/// or nearly so, or seams.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct WindingReport {
    /// The part.
    pub part: String,
    /// Edges of the net boundary (used more often one way than the other), counted
    /// with that difference.
    pub open_edges: usize,
    /// Edges used by more than two faces.
    pub nonmanifold_edges: usize,
    /// Pairs of faces that cross.
    pub crossing_pairs: usize,
    /// Boundary loops closed (planar or nearly so, or seams).
    pub loops_closed: usize,
    /// Of those, the seams.
    pub seams_closed: usize,
    /// Triangles added to close them.
    pub cap_triangles: usize,
    /// Faces with the solid on both sides or on neither: they enclose nothing.
    pub faces_dropped: usize,
    /// Convex cells of winding number at least 1 kept.
    pub cells_kept: usize,
    /// Convex pieces they were merged into.
    pub pieces: usize,
    /// The surface was inside out (negative signed volume) and was reversed.
    pub inside_out: bool,
    /// The least and greatest winding numbers met.
    pub lowest_winding: i64,
    /// See `lowest_winding`.
    pub highest_winding: i64,
    /// The surface's signed volume (the integral of its winding number), grid units.
    pub volume_before: Rational,
    /// The solid's volume, grid units.
    pub volume_after: Rational,
}

impl Part {
    /// A part known only by declared convex pieces (no mesh, volume unknown): for
    /// assemblies built in code.
    pub fn from_pieces(name: impl Into<String>, pieces: Vec<Polytope>) -> Part {
        Part {
            name: name.into(),
            source: PathBuf::new(),
            mesh: None,
            info: None,
            pieces,
            piece_sources: Vec::new(),
            declared_pieces: true,
            decomposed: false,
            convex: false,
            volume: Rational::zero(),
            reflex_edges: 0,
            bbox: None,
            unshrunk_pieces: Vec::new(),
            winding: None,
        }
    }

    /// The exact volume in input units.
    pub fn volume_units(&self, grid: &Grid) -> Rational {
        volume_in_units(&self.volume, grid)
    }

    /// True when the volume is known (a valid closed mesh, or declared pieces).
    pub fn volume_known(&self) -> bool {
        self.info.as_ref().is_some_and(|i| i.volume6.is_some()) || !self.pieces.is_empty()
    }
}

/// An assembly in its assembled pose, snapped to one grid.
#[derive(Clone, Debug)]
pub struct Assembly {
    /// Its name (from the manifest or description, or the file or folder name).
    pub name: String,
    /// The grid every coordinate was snapped to.
    pub grid: Grid,
    /// The largest distance (in input units) snapping moved any coordinate.
    pub max_snap_displacement: f64,
    /// The parts, in input order (by name for a folder).
    pub parts: Vec<Part>,
    /// The tolerance every answer holds under: parts made this much smaller (`None`:
    /// the parts as given).
    pub tolerance: Option<AppliedTolerance>,
}

impl Assembly {
    /// The part named `name`.
    pub fn part(&self, name: &str) -> Option<&Part> {
        self.parts.iter().find(|p| p.name == name)
    }
}

/// What repair on load did to one mesh file (or object).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Repairs {
    /// The file (empty for a mesh given as arrays).
    pub file: PathBuf,
    /// The parts made of it (several when it held separate solids).
    pub parts: Vec<String>,
    /// The repairs, by kind.
    pub report: RepairReport,
    /// The parts made by the winding rule, and how.
    pub winding: Vec<WindingReport>,
}

/// A file or folder inside an assembly folder that was not read, and why (hidden
/// entries, whose names start with a dot, are passed over without a word).
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct Skipped {
    /// The file or folder.
    pub path: PathBuf,
    /// Why it was not read.
    pub reason: String,
}

/// A loaded assembly and every problem found while loading it.
#[derive(Clone, Debug)]
pub struct Loaded {
    /// The assembly (possibly with invalid parts: see `problems`).
    pub assembly: Assembly,
    /// Every problem, in the order found (per part in part order, then across parts).
    pub problems: Vec<Problem>,
    /// Every repair made on load, per mesh (empty with `--strict`, or when nothing
    /// needed repair).
    pub repairs: Vec<Repairs>,
    /// Entries of the assembly folder (and of its piece folders) that were not read;
    /// empty for a manifest or a single mesh file, which name what is read.
    pub skipped: Vec<Skipped>,
    /// Wall time of each stage of loading.
    pub seconds: LoadSeconds,
}

/// Wall time of each stage of [`crate::load`], in seconds.
#[derive(Clone, Copy, Debug, Default, PartialEq)]
pub struct LoadSeconds {
    /// Reading the files.
    pub read: f64,
    /// Snapping, repairing and validating the parts and given pieces.
    pub validate: f64,
    /// The automatic convex decompositions.
    pub decompose: f64,
    /// Finding relations between parts that snapping changed.
    pub snapping: f64,
    /// The overlap check between parts, or applying the tolerance.
    pub overlaps: f64,
}

impl Loaded {
    /// True when no problem is an error: the assembly can be partitioned.
    pub fn is_valid(&self) -> bool {
        !self.problems.iter().any(Problem::is_error)
    }
}
