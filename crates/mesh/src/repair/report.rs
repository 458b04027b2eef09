//! What a repair did, counted per kind of defect, so that callers can tell users
//! exactly how their file was changed.

use serde::Serialize;
use std::fmt;

/// The repairs made to one mesh, by kind.
#[derive(Clone, Debug, Default, PartialEq, Eq, Serialize)]
pub struct RepairReport {
    /// Extra copies of a triangle (same vertices, same orientation) removed.
    pub duplicate_faces: usize,
    /// Triangles removed because an identical triangle ran the opposite way (two per
    /// cancelled pair): coincident faces with opposite normals bound nothing.
    pub cancelled_faces: usize,
    /// Zero-area triangles removed (also those left over after splitting).
    pub degenerate_faces: usize,
    /// Vertices inserted into edges that a vertex of the mesh lay strictly inside.
    pub tjunctions: usize,
    /// Boundary loops closed.
    pub holes_closed: usize,
    /// Triangles added to close them.
    pub hole_triangles: usize,
    /// Input faces (by source face: once however many triangles it became) reversed to
    /// agree with the rest of their shell.
    pub flipped_faces: usize,
    /// Shells turned inside out to face the right way (outward, or inward for a cavity).
    pub flipped_shells: usize,
}

impl RepairReport {
    /// True when nothing was repaired.
    pub fn is_empty(&self) -> bool {
        *self == RepairReport::default()
    }

    /// Adds the counts of `other` (e.g. to total the repairs over the parts of an
    /// assembly).
    pub fn add(&mut self, other: &RepairReport) {
        self.duplicate_faces += other.duplicate_faces;
        self.cancelled_faces += other.cancelled_faces;
        self.degenerate_faces += other.degenerate_faces;
        self.tjunctions += other.tjunctions;
        self.holes_closed += other.holes_closed;
        self.hole_triangles += other.hole_triangles;
        self.flipped_faces += other.flipped_faces;
        self.flipped_shells += other.flipped_shells;
    }
}

/// `"1 face"`, `"2 faces"`.
fn count(n: usize, one: &str, many: &str) -> String {
    format!("{n} {}", if n == 1 { one } else { many })
}

impl fmt::Display for RepairReport {
    /// The non-zero counts in words, e.g. "3 T-junctions split, 2 duplicate faces
    /// removed"; "nothing repaired" when empty.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        let mut parts = Vec::new();
        let r = self;
        if r.degenerate_faces > 0 {
            parts.push(count(r.degenerate_faces, "zero-area face", "zero-area faces") + " removed");
        }
        if r.duplicate_faces > 0 {
            parts.push(count(r.duplicate_faces, "duplicate face", "duplicate faces") + " removed");
        }
        if r.cancelled_faces > 0 {
            parts
                .push(count(r.cancelled_faces, "face", "faces") + " removed with an opposite copy");
        }
        if r.tjunctions > 0 {
            parts.push(count(r.tjunctions, "T-junction", "T-junctions") + " split");
        }
        if r.holes_closed > 0 {
            parts.push(format!(
                "{} closed with {}",
                count(r.holes_closed, "hole", "holes"),
                count(r.hole_triangles, "triangle", "triangles")
            ));
        }
        if r.flipped_faces > 0 {
            parts.push(count(r.flipped_faces, "face", "faces") + " flipped to match its shell");
            if r.flipped_faces > 1 {
                let last = parts.last_mut().expect("just pushed");
                *last = last.replace("its shell", "their shells");
            }
        }
        if r.flipped_shells > 0 {
            parts.push(count(r.flipped_shells, "shell", "shells") + " turned inside out");
        }
        if parts.is_empty() {
            write!(f, "nothing repaired")
        } else {
            write!(f, "{}", parts.join(", "))
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn words_and_plurals() {
        let mut r = RepairReport::default();
        assert!(r.is_empty());
        assert_eq!(r.to_string(), "nothing repaired");
        r.tjunctions = 3;
        r.duplicate_faces = 2;
        assert_eq!(
            r.to_string(),
            "2 duplicate faces removed, 3 T-junctions split"
        );
        let one = RepairReport {
            tjunctions: 1,
            holes_closed: 1,
            hole_triangles: 1,
            flipped_faces: 1,
            flipped_shells: 1,
            cancelled_faces: 2,
            degenerate_faces: 1,
            duplicate_faces: 1,
        };
        assert_eq!(
            one.to_string(),
            "1 zero-area face removed, 1 duplicate face removed, 2 faces removed with an \
             opposite copy, 1 T-junction split, 1 hole closed with 1 triangle, 1 face \
             flipped to match its shell, 1 shell turned inside out"
        );
        r.add(&one);
        assert_eq!(r.tjunctions, 4);
        assert_eq!(r.duplicate_faces, 3);
        r.flipped_faces = 2;
        assert!(r
            .to_string()
            .contains("2 faces flipped to match their shells"));
        assert!(!r.is_empty());
    }
}
