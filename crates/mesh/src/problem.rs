//! Problems found while reading and validating: values with context, never panics.

use serde::{Serialize, Serializer};
use std::fmt;
use std::path::{Path, PathBuf};

/// Serializes a path as text, escaped as in messages (see `apart_formats::escape`): a
/// file name that is not UTF-8 keeps its bytes as `\xNN` escapes rather than failing
/// the whole JSON answer (serde's own path serializer refuses such a name).
pub fn path_text<S: Serializer>(p: &Path, s: S) -> Result<S::Ok, S::Error> {
    s.serialize_str(&apart_formats::escape::path(p))
}

/// [`path_text`] of an optional path (`null` for none).
pub fn optional_path_text<S: Serializer>(p: &Option<PathBuf>, s: S) -> Result<S::Ok, S::Error> {
    match p {
        Some(p) => path_text(p, s),
        None => s.serialize_none(),
    }
}

/// [`path_text`] of each path of a list.
pub fn path_texts<S: Serializer>(ps: &[PathBuf], s: S) -> Result<S::Ok, S::Error> {
    s.collect_seq(ps.iter().map(|p| apart_formats::escape::path(p)))
}

/// How bad a problem is.
#[derive(Clone, Copy, Debug, PartialEq, Eq, PartialOrd, Ord, Hash, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Severity {
    /// Something worth knowing that is not wrong (a solid touching itself along an edge).
    Note,
    /// Repaired or tolerated (inside-out part flipped, zero-area face dropped).
    Warning,
    /// The input is not a valid closed solid or assembly.
    Error,
}

impl fmt::Display for Severity {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(match self {
            Severity::Note => "note",
            Severity::Warning => "warning",
            Severity::Error => "error",
        })
    }
}

/// What kind of problem it is, for code that acts on problems (the message is for
/// people). Not part of the JSON output, which carries the message.
#[derive(Clone, Debug, Default, PartialEq, Eq, Hash)]
pub enum ProblemKind {
    /// None of the kinds below.
    #[default]
    Other,
    /// The file was not read: missing, not a regular file, outside the assembly folder,
    /// not parsed, or without the object asked for.
    Unreadable,
    /// Vertices that cannot be used: not finite, off the grid, or too many.
    Vertex,
    /// A face dropped or split into triangles on snapping.
    Face,
    /// No face with a non-zero area is left.
    EmptyMesh,
    /// An edge that belongs to one face only.
    OpenBoundary,
    /// Two faces along one edge in the same direction.
    InconsistentOrientation,
    /// An edge shared by faces that do not alternate in direction.
    NonManifold,
    /// The solid touches itself along an edge or at a vertex (valid).
    SelfTouching,
    /// The solid or one of its shells has zero volume.
    ZeroVolume,
    /// The solid was inside out and flipped.
    InsideOut,
    /// Faces of the solid that cross or overlap.
    SelfIntersection,
    /// A shell nested, inside out or in the wrong region.
    Shell,
    /// A repair made on load.
    Repaired,
    /// A declared convex piece that is not usable or does not match its part.
    Piece,
    /// The exact convex decomposition of a part failed or did not verify.
    Decomposition,
    /// The part overlaps the part named `other`.
    Overlap {
        /// The name of the other part (behind one thin pointer, which keeps [`Problem`]
        /// small enough to be returned as an error).
        other: Box<String>,
    },
    /// What a stated tolerance did, or could not do.
    Tolerance,
}

/// One problem, with as much context as is known: the file, the part and the element.
#[derive(Clone, Debug, PartialEq, Eq, Serialize)]
pub struct Problem {
    /// How bad it is.
    pub severity: Severity,
    /// The file it was found in.
    #[serde(serialize_with = "optional_path_text")]
    pub file: Option<PathBuf>,
    /// The part it belongs to.
    pub part: Option<String>,
    /// The element: "face 12", "vertex 5", "edge (3, 7) at (1, 0, 2)-(1, 1, 2)".
    pub element: Option<String>,
    /// What is wrong, in words.
    pub message: String,
    /// What kind of problem it is ([`ProblemKind::Other`] unless set).
    #[serde(skip)]
    pub kind: ProblemKind,
}

impl Problem {
    /// A problem with only a severity and a message.
    pub fn new(severity: Severity, message: impl Into<String>) -> Problem {
        Problem {
            severity,
            file: None,
            part: None,
            element: None,
            message: message.into(),
            kind: ProblemKind::Other,
        }
    }

    /// The same problem, of kind `kind`.
    pub fn with_kind(mut self, kind: ProblemKind) -> Problem {
        self.kind = kind;
        self
    }

    /// An error.
    pub fn error(message: impl Into<String>) -> Problem {
        Problem::new(Severity::Error, message)
    }

    /// A warning.
    pub fn warning(message: impl Into<String>) -> Problem {
        Problem::new(Severity::Warning, message)
    }

    /// A note.
    pub fn note(message: impl Into<String>) -> Problem {
        Problem::new(Severity::Note, message)
    }

    /// The same problem, naming an element.
    pub fn at(mut self, element: impl Into<String>) -> Problem {
        self.element = Some(element.into());
        self
    }

    /// The same problem, naming the file (kept when one is already set).
    pub fn in_file(mut self, file: impl Into<PathBuf>) -> Problem {
        if self.file.is_none() {
            self.file = Some(file.into());
        }
        self
    }

    /// The same problem, naming the part (kept when one is already set).
    pub fn in_part(mut self, part: impl Into<String>) -> Problem {
        if self.part.is_none() {
            self.part = Some(part.into());
        }
        self
    }

    /// True for errors.
    pub fn is_error(&self) -> bool {
        self.severity == Severity::Error
    }
}

impl fmt::Display for Problem {
    /// `error: parts/red.off (part "red"), face 12: zero area after snapping`. The
    /// file, the part and the element are escaped (they come from file and object
    /// names): no control character reaches the terminal.
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        use apart_formats::escape::{escape, path};
        write!(f, "{}: ", self.severity)?;
        let mut context = String::new();
        match (&self.file, &self.part) {
            (Some(file), Some(part)) => {
                context = format!("{} (part \"{}\")", path(file), escape(part));
            }
            (Some(file), None) => context = path(file),
            (None, Some(part)) => context = format!("part \"{}\"", escape(part)),
            (None, None) => {}
        }
        if let Some(element) = &self.element {
            if !context.is_empty() {
                context.push_str(", ");
            }
            context.push_str(&escape(element));
        }
        if context.is_empty() {
            write!(f, "{}", self.message)
        } else {
            write!(f, "{context}: {}", self.message)
        }
    }
}

/// Collects problems of one kind, keeping the first few in full and counting the rest,
/// so that a broken million-triangle mesh yields a readable report.
pub(crate) struct Capped {
    pub(crate) kept: Vec<Problem>,
    pub(crate) extra: usize,
    limit: usize,
}

impl Capped {
    pub(crate) fn new(limit: usize) -> Capped {
        Capped {
            kept: Vec::new(),
            extra: 0,
            limit,
        }
    }

    pub(crate) fn push(&mut self, p: impl FnOnce() -> Problem) {
        if self.kept.len() < self.limit {
            self.kept.push(p());
        } else {
            self.extra += 1;
        }
    }

    /// The kept problems, followed by one summary problem when some were left out.
    pub(crate) fn finish(self, what: &str, out: &mut Vec<Problem>) {
        let severity = self.kept.first().map(|p| p.severity);
        let kind = self.kept.first().map(|p| p.kind.clone());
        out.extend(self.kept);
        if self.extra > 0 {
            out.push(
                Problem::new(
                    severity.unwrap_or(Severity::Error),
                    format!("... and {} more {what}", self.extra),
                )
                .with_kind(kind.unwrap_or_default()),
            );
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn display_with_full_context() {
        let p = Problem::error("zero area after snapping")
            .at("face 12")
            .in_file("parts/red.off")
            .in_part("red");
        assert_eq!(
            p.to_string(),
            "error: parts/red.off (part \"red\"), face 12: zero area after snapping"
        );
        assert_eq!(
            Problem::warning("flipped").in_part("a").to_string(),
            "warning: part \"a\": flipped"
        );
        assert_eq!(Problem::note("x").to_string(), "note: x");
        assert!(Severity::Error > Severity::Warning && Severity::Warning > Severity::Note);
        // Names from files never bring control characters to the terminal.
        let p = Problem::error("bad")
            .in_part("a\x1b[2Jb")
            .in_file("x\ny.off")
            .at("face 1");
        assert_eq!(
            p.to_string(),
            "error: x\\ny.off (part \"a\\x1b[2Jb\"), face 1: bad"
        );
    }
}
