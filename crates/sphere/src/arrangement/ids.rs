//! Typed indices of the cells of an [`Arrangement`](super::Arrangement), so that no
//! caller spells out half-edge arithmetic.
//!
//! Each id is a `u32` index (`#[repr(transparent)]`: a `Vec` of ids has the layout of a
//! `Vec<u32>`). Edge `e` has the two half-edges `2e` (running counter-clockwise around
//! its circle's normal, from `from` to `to`) and `2e + 1` (back); only this module knows.

macro_rules! id {
    ($(#[$doc:meta])* $name:ident) => {
        $(#[$doc])*
        #[derive(Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord, Debug)]
        #[repr(transparent)]
        pub struct $name(u32);

        impl $name {
            /// The id at position `i` of the arrangement's list.
            #[inline]
            pub fn new(i: usize) -> $name {
                debug_assert!(u32::try_from(i).is_ok(), "index {i} past u32");
                $name(i as u32)
            }

            /// The position in the arrangement's list (for indexing tables).
            #[inline]
            pub fn index(self) -> usize {
                self.0 as usize
            }
        }
    };
}

id!(
    /// A vertex: an index into [`Arrangement::vertices`](super::Arrangement::vertices).
    VertexId
);
id!(
    /// An undirected edge: an index into [`Arrangement::edges`](super::Arrangement::edges).
    EdgeId
);
id!(
    /// A directed half-edge; the face on its left is its face.
    HalfEdge
);
id!(
    /// A boundary cycle of half-edges (a face has one or more).
    CycleId
);
id!(
    /// A face: an index into [`Arrangement::faces`](super::Arrangement::faces).
    FaceId
);

impl HalfEdge {
    /// The same edge run the other way.
    #[inline]
    pub fn twin(self) -> HalfEdge {
        HalfEdge(self.0 ^ 1)
    }

    /// The undirected edge of this half-edge.
    #[inline]
    pub fn edge(self) -> EdgeId {
        EdgeId(self.0 >> 1)
    }

    /// True when the half-edge runs counter-clockwise around its circle's normal (from
    /// its edge's `from` to `to`): its left side is the circle's positive side.
    #[inline]
    pub fn is_forward(self) -> bool {
        self.0 & 1 == 0
    }
}

impl EdgeId {
    /// The half-edge from `from` to `to` (counter-clockwise around the circle's normal).
    #[inline]
    pub fn forward(self) -> HalfEdge {
        HalfEdge(self.0 << 1)
    }

    /// The half-edge from `to` back to `from`.
    #[inline]
    pub fn backward(self) -> HalfEdge {
        HalfEdge((self.0 << 1) | 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn half_edges_of_an_edge() {
        let e = EdgeId::new(7);
        let (f, b) = (e.forward(), e.backward());
        assert_eq!((f.index(), b.index()), (14, 15));
        assert_eq!((f.twin(), b.twin()), (b, f));
        assert_eq!((f.edge(), b.edge()), (e, e));
        assert!(f.is_forward() && !b.is_forward());
        assert_eq!(std::mem::size_of::<HalfEdge>(), 4);
    }
}
