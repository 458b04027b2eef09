//! Exact arrangements of great-circle arcs on the sphere of directions.
//!
//! Sphere points are integer vectors (never normalised), great circles integer normals;
//! every decision is an exact predicate of `apart-kernel`. The crate knows nothing about
//! parts or assemblies: it arranges labelled arcs and points ([`arrangement`]), computes
//! for every vertex, edge and face which of several overlaid region maps cover it
//! ([`overlay`]), and simplifies a union of regions to the arcs where its status
//! changes ([`region`]).

pub mod arc;
pub mod arrangement;
pub mod bitset;
pub mod index;
pub mod overlay;
pub mod polygon;
pub mod region;

pub use arc::Arc;
pub use arrangement::{
    ArcLabel, Arrangement, CycleId, EdgeId, FaceId, HalfEdge, InputArc, InputPoint, VertexId,
};
pub use bitset::{BitSet, MapSet};
pub use polygon::SphericalPolygon;
