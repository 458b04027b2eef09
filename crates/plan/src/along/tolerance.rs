//! Motions found under a tolerance, checked against the parts as given.

use super::DirectionQuery;
use crate::regions::Part;
use crate::PlanError;
use apart_kernel::Vec3;
use rustc_hash::FxHashMap;

/// A motion found by a planner: a set of parts moving along a direction away from the
/// other parts of a subassembly (`among`; `None`: the whole assembly).
pub type Motion<'a> = (&'a [usize], Option<&'a [usize]>, &'a Vec3);

/// For motions found under a tolerance: whether each also holds for the parts as given,
/// decided exactly from the unshrunk pieces (the moving parts against the others of the
/// subassembly, per-piece-pair tests). A motion that separates parts whose unshrunk
/// pieces overlap never holds. `None` without a tolerance.
pub fn holds_without_tolerance(
    asm: &apart_assembly::Assembly,
    motions: &[Motion],
) -> Result<Option<Vec<bool>>, PlanError> {
    if asm.tolerance.is_none() {
        return Ok(None);
    }
    let mut out = vec![false; motions.len()];
    // The motions by their (moving set, subassembly), in the order first met.
    type Key<'a> = (&'a [usize], Option<&'a [usize]>);
    let mut index: FxHashMap<Key, usize> = FxHashMap::default();
    let mut groups: Vec<(Key, Vec<usize>)> = Vec::new();
    for (k, (moving, among, _)) in motions.iter().enumerate() {
        let key = (*moving, *among);
        let g = *index.entry(key).or_insert_with(|| {
            groups.push((key, Vec::new()));
            groups.len() - 1
        });
        groups[g].1.push(k);
    }
    let overlapping = asm
        .tolerance
        .as_ref()
        .map_or(&[][..], |t| &t.overlapping[..]);
    // Each part's side in the group at hand: 0 not in its subassembly, 1 moving, 2
    // staying (reset after each group).
    let mut side = vec![0u8; asm.parts.len()];
    for ((moving, among), ks) in groups {
        let mut members: Vec<usize> =
            among.map_or_else(|| (0..asm.parts.len()).collect(), <[usize]>::to_vec);
        members.sort_unstable();
        members.dedup();
        for &k in &members {
            side[k] = 2;
        }
        for &k in moving {
            if side[k] == 2 {
                side[k] = 1;
            }
        }
        // A moving part whose interior overlapped a part of the rest before shrinking
        // starts inside it: nothing holds without the tolerance (as the query below would
        // find, after building it).
        let starts_inside = overlapping
            .iter()
            .any(|&(i, j)| side[i] != 0 && side[j] != 0 && side[i] != side[j]);
        // Two sides, each the union of its parts' unshrunk pieces.
        let mut sides = [Vec::new(), Vec::new()];
        if !starts_inside {
            for &k in &members {
                let p = &asm.parts[k];
                let pieces = if p.unshrunk_pieces.is_empty() {
                    &p.pieces
                } else {
                    &p.unshrunk_pieces
                };
                sides[usize::from(side[k] == 2)].extend(pieces.iter().cloned());
            }
        }
        for &k in &members {
            side[k] = 0;
        }
        if starts_inside {
            continue;
        }
        let [a, b] = sides;
        let two = [Part::from_pieces("moving", a), Part::from_pieces("rest", b)];
        let query = match DirectionQuery::new(&two) {
            Ok(q) => q,
            Err(PlanError::Overlap { .. }) => continue,
            Err(e) => return Err(e),
        };
        for k in ks {
            // The moving side (part 0) moves along d unless it hits the rest (part 1).
            out[k] = match query.hits(0, 1, motions[k].2) {
                Ok(hit) => !hit,
                Err(PlanError::Overlap { .. }) => false,
                Err(e) => return Err(e),
            };
        }
    }
    Ok(Some(out))
}
