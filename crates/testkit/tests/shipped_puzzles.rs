//! The shipped puzzle examples say what the oracles find: each `examples/voxel-level-*`
//! piece mesh, read back into cells, gives the level of its `expected.json` and a plan
//! that replays, and the puzzle comes apart completely whichever shortest first
//! separation is taken; each level-2 assembly of `apart_testkit::moves` is on disk exactly as
//! written from its definition.

use apart_testkit::moves::{all, write_parts};
use apart_testkit::voxel_puzzles::{
    disassembles_completely, replay, solve, Cell, Level, Separations, Steps,
};
use apart_testkit::Scratch;
use std::path::{Path, PathBuf};

fn examples() -> PathBuf {
    Path::new(env!("CARGO_MANIFEST_DIR")).join("../../examples")
}

/// The points and triangles of an OFF file.
fn read_off(path: &Path) -> (Vec<[i64; 3]>, Vec<[usize; 3]>) {
    let text = std::fs::read_to_string(path).expect("an OFF file");
    let mut words = text
        .split_whitespace()
        .skip(1)
        .map(|w| w.parse::<i64>().expect("an integer"));
    let mut next = || words.next().expect("more numbers");
    let (nv, nf, _) = (next(), next(), next());
    let points = (0..nv).map(|_| [next(), next(), next()]).collect();
    let tris = (0..nf)
        .map(|_| {
            assert_eq!(next(), 3, "triangles");
            [next() as usize, next() as usize, next() as usize]
        })
        .collect();
    (points, tris)
}

/// The unit cells (of side `scale`) whose centres the closed mesh holds: a ray up from
/// the centre crosses horizontal faces at an odd number of heights (a centre on the
/// diagonal of a face's two triangles counts that face once).
fn cells_of(points: &[[i64; 3]], tris: &[[usize; 3]], scale: i64) -> Vec<Cell> {
    let lo = [0, 1, 2].map(|a| points.iter().map(|p| p[a]).min().unwrap() / scale);
    let hi = [0, 1, 2].map(|a| points.iter().map(|p| p[a]).max().unwrap() / scale);
    let mut cells = Vec::new();
    for x in lo[0]..hi[0] {
        for y in lo[1]..hi[1] {
            for z in lo[2]..hi[2] {
                let c = [2 * x + 1, 2 * y + 1, 2 * z + 1].map(|v| v * scale);
                let mut heights: Vec<i64> = tris
                    .iter()
                    .filter_map(|t| {
                        let [a, b, d] = t.map(|i| points[i].map(|v| 2 * v));
                        if a[2] != b[2] || a[2] != d[2] || a[2] <= c[2] {
                            return None;
                        }
                        let side = |p: [i64; 3], q: [i64; 3]| {
                            (q[0] - p[0]) * (c[1] - p[1]) - (q[1] - p[1]) * (c[0] - p[0])
                        };
                        let s = [side(a, b), side(b, d), side(d, a)];
                        let inside = s.iter().all(|&v| v >= 0) || s.iter().all(|&v| v <= 0);
                        inside.then_some(a[2])
                    })
                    .collect();
                heights.sort_unstable();
                heights.dedup();
                if heights.len() % 2 == 1 {
                    cells.push([x, y, z]);
                }
            }
        }
    }
    cells
}

#[test]
fn shipped_voxel_puzzles_have_their_expected_levels() {
    let mut checked = 0;
    for entry in std::fs::read_dir(examples()).unwrap() {
        let dir = entry.unwrap().path();
        let name = dir.file_name().unwrap().to_string_lossy().to_string();
        if !name.starts_with("voxel-level-") {
            continue;
        }
        let expected = std::fs::read_to_string(dir.join("expected.json")).unwrap();
        let level: usize = expected
            .split("\"level\":")
            .nth(1)
            .and_then(|r| r.split(',').next())
            .map(|v| v.trim().parse().unwrap())
            .expect("a level");
        let mut pieces = Vec::new();
        for i in 0.. {
            let path = dir.join(format!("piece_{i}.off"));
            if !path.exists() {
                break;
            }
            let (points, tris) = read_off(&path);
            let cells = cells_of(&points, &tris, 10);
            // The mesh bounds exactly its cells: six times the volume is 6000 per cell.
            let volume6: i64 = tris
                .iter()
                .map(|t| {
                    let [a, b, c] = t.map(|i| points[i]);
                    a[0] * (b[1] * c[2] - b[2] * c[1]) - a[1] * (b[0] * c[2] - b[2] * c[0])
                        + a[2] * (b[0] * c[1] - b[1] * c[0])
                })
                .sum();
            assert_eq!(volume6, 6000 * cells.len() as i64, "{name} piece {i}");
            pieces.push(cells);
        }
        assert!((4..=8).contains(&pieces.len()), "{name}");
        let (found, plan) = solve(&pieces, Steps::Any, 10_000_000);
        assert_eq!(found, Level::Moves(level), "{name}");
        let plan = plan.unwrap();
        assert_eq!(plan.len(), level);
        assert!(replay(&pieces, &plan), "{name}");
        assert!(
            disassembles_completely(&pieces, 10_000_000, Separations::Every),
            "{name} comes apart completely"
        );
        assert_eq!(name, format!("voxel-level-{level}"));
        checked += 1;
    }
    assert!(checked >= 3, "the voxel examples are there");
}

#[test]
fn shipped_level_two_assemblies_are_written_from_their_definitions() {
    let scratch = Scratch::new("shipped-moves");
    for a in all() {
        let fresh = scratch.join(a.name);
        write_parts(&fresh, a.name, &a.parts).unwrap();
        let shipped = examples().join(a.name);
        let expected = std::fs::read_to_string(shipped.join("expected.json")).unwrap();
        assert_eq!(expected, a.expected_json(), "{}", a.name);
        assert_eq!(
            std::fs::read_to_string(shipped.join("assembly.json")).unwrap(),
            std::fs::read_to_string(fresh.join("assembly.json")).unwrap()
        );
        for part in &a.parts {
            for i in 0..part.pieces.len() {
                let file = format!("{}/piece_{i}.off", part.name);
                assert_eq!(
                    std::fs::read_to_string(shipped.join(&file)).unwrap(),
                    std::fs::read_to_string(fresh.join(&file)).unwrap(),
                    "{} {file}",
                    a.name
                );
            }
        }
    }
}
