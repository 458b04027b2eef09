//! What a reader returns: named objects with floating-point vertices and polygons.

/// Polygons as index lists, stored flat (one allocation for the whole object, however
/// many faces it has).
#[derive(Clone, Debug, Default, PartialEq, Eq)]
pub struct Polygons {
    indices: Vec<u32>,
    ends: Vec<u32>,
}

impl Polygons {
    /// No polygons.
    pub fn new() -> Polygons {
        Polygons::default()
    }

    /// Room for `faces` polygons with `indices` indices in total.
    pub fn with_capacity(faces: usize, indices: usize) -> Polygons {
        Polygons {
            indices: Vec::with_capacity(indices),
            ends: Vec::with_capacity(faces),
        }
    }

    /// Triangles `[a, b, c]`, without copying polygon by polygon.
    pub fn from_triangles(triangles: &[[u32; 3]]) -> Polygons {
        Polygons {
            indices: triangles.iter().flatten().copied().collect(),
            ends: (1..=triangles.len() as u32).map(|i| 3 * i).collect(),
        }
    }

    /// `n` triangles over `3n` vertices: `[0, 1, 2], [3, 4, 5], ...` (a triangle soup).
    pub fn triangle_soup(n: usize) -> Polygons {
        Polygons {
            indices: (0..3 * n as u32).collect(),
            ends: (1..=n as u32).map(|i| 3 * i).collect(),
        }
    }

    /// Appends one polygon.
    pub fn push(&mut self, polygon: &[u32]) {
        self.indices.extend_from_slice(polygon);
        self.ends.push(self.indices.len() as u32);
    }

    /// Number of polygons.
    pub fn len(&self) -> usize {
        self.ends.len()
    }

    /// True when there is no polygon.
    pub fn is_empty(&self) -> bool {
        self.ends.is_empty()
    }

    /// Polygon `i`.
    pub fn get(&self, i: usize) -> &[u32] {
        let start = if i == 0 { 0 } else { self.ends[i - 1] as usize };
        &self.indices[start..self.ends[i] as usize]
    }

    /// The polygons in order.
    pub fn iter(&self) -> impl ExactSizeIterator<Item = &[u32]> + '_ {
        (0..self.len()).map(move |i| self.get(i))
    }

    /// Every index of every polygon, flat.
    pub fn all_indices(&self) -> &[u32] {
        &self.indices
    }

    /// True when every polygon is a triangle.
    pub fn all_triangles(&self) -> bool {
        self.indices.len() == 3 * self.ends.len()
            && self
                .ends
                .iter()
                .enumerate()
                .all(|(i, &e)| e as usize == 3 * (i + 1))
    }

    /// Reverses every polygon (turns the surface inside out).
    pub fn reverse_each(&mut self) {
        let mut start = 0;
        for &end in &self.ends {
            self.indices[start..end as usize].reverse();
            start = end as usize;
        }
    }

    /// Appends `other`, shifting its indices by `offset`.
    pub fn extend_shifted(&mut self, other: &Polygons, offset: u32) {
        for p in other.iter() {
            self.indices.extend(p.iter().map(|&i| i + offset));
            self.ends.push(self.indices.len() as u32);
        }
    }
}

impl From<Vec<Vec<u32>>> for Polygons {
    fn from(faces: Vec<Vec<u32>>) -> Polygons {
        let mut p = Polygons::with_capacity(faces.len(), faces.iter().map(Vec::len).sum());
        for f in &faces {
            p.push(f);
        }
        p
    }
}

/// One object read from a file: an optional name, vertices in input units, and
/// polygons indexing them (counter-clockwise seen from outside).
#[derive(Clone, Debug, Default, PartialEq)]
pub struct RawObject {
    /// The object's name in the file (OBJ `o`/`g`, glTF node name), if any.
    pub name: Option<String>,
    /// Vertex coordinates in input units, as read (the nearest `f64` of the text).
    pub vertices: Vec<[f64; 3]>,
    /// Faces as polygons of vertex indices.
    pub faces: Polygons,
}

impl RawObject {
    /// Applies `f` to every vertex.
    pub fn map_vertices(&mut self, f: impl Fn([f64; 3]) -> [f64; 3]) {
        for v in &mut self.vertices {
            *v = f(*v);
        }
    }

    /// Appends `other`'s vertices and faces (its name is dropped).
    pub fn append(&mut self, other: &RawObject) {
        let offset = self.vertices.len() as u32;
        self.vertices.extend_from_slice(&other.vertices);
        self.faces.extend_shifted(&other.faces, offset);
    }

    /// All objects merged into one, named `name`.
    pub fn merged(objects: &[RawObject], name: Option<String>) -> RawObject {
        let mut out = RawObject {
            name,
            ..RawObject::default()
        };
        for o in objects {
            out.append(o);
        }
        out
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn flat_polygons_round_trip() {
        let p = Polygons::from(vec![vec![0, 1, 2, 3], vec![4, 5, 6]]);
        assert_eq!(p.len(), 2);
        assert_eq!(p.get(0), &[0, 1, 2, 3]);
        assert_eq!(p.get(1), &[4, 5, 6]);
        assert!(!p.all_triangles());
        let t = Polygons::from_triangles(&[[0, 1, 2], [2, 1, 3]]);
        assert!(t.all_triangles());
        assert_eq!(
            t.iter().collect::<Vec<_>>(),
            vec![&[0, 1, 2][..], &[2, 1, 3]]
        );
        let mut r = p.clone();
        r.reverse_each();
        assert_eq!(r.get(0), &[3, 2, 1, 0]);
        let mut a = RawObject {
            name: None,
            vertices: vec![[0.0; 3]; 3],
            faces: Polygons::from_triangles(&[[0, 1, 2]]),
        };
        a.append(&a.clone());
        assert_eq!(a.faces.get(1), &[3, 4, 5]);
    }
}
