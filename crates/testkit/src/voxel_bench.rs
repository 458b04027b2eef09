//! A fixed set of voxel interlocking puzzles for benchmarks: `data/voxel_bench.json`,
//! puzzles of 4 to 8 pieces in boxes of at most 6×6×6 cells, of levels from 2 up, each
//! of which comes apart completely whichever shortest separation a planner picks
//! ([`crate::voxel_puzzles::disassembles_completely`] with
//! [`crate::voxel_puzzles::Separations::Every`]), with the level the oracle computes.
//!
//! The file was written once by `cargo run --release -p apart-testkit --example
//! write_voxel_puzzles -- --bench` (a fixed list of boxes, piece counts, target levels
//! and seeds, see that example) and is committed, so benchmarks compare like with like;
//! the tests check every level again with the oracle.
//!
//! The format is plain JSON, one object per puzzle: `{"name": "...", "dims": [x, y, z],
//! "pieces": [[[x, y, z], ...], ...], "level": L}` (cells as in
//! [`crate::voxel_puzzles`]); the crate depends on nothing, so [`bench_puzzles`] reads it
//! with the small parser below, which knows just enough JSON for it.

use crate::voxel_generate::write_puzzle;
use crate::voxel_puzzles::Cell;
use std::fmt::Write as _;
use std::path::Path;

/// One puzzle of the fixture.
#[derive(Clone, Debug, PartialEq, Eq)]
pub struct BenchPuzzle {
    /// A short unique name (box, pieces, level).
    pub name: String,
    /// The box the cells lie in (`0..dims[a]`).
    pub dims: [i64; 3],
    /// Each piece's cells.
    pub pieces: Vec<Vec<Cell>>,
    /// The level (moves along the axes, any number of steps) the oracle computed.
    pub level: usize,
}

const FIXTURE: &str = include_str!("../data/voxel_bench.json");

/// The puzzles of `data/voxel_bench.json`, in file order.
///
/// # Panics
/// If the committed file is malformed.
pub fn bench_puzzles() -> Vec<BenchPuzzle> {
    parse_bench(FIXTURE).expect("data/voxel_bench.json is well formed")
}

/// Parses the fixture format (see the module documentation).
pub fn parse_bench(text: &str) -> Result<Vec<BenchPuzzle>, String> {
    let mut p = Parser {
        s: text.as_bytes(),
        i: 0,
    };
    let v = p.value()?;
    p.ws();
    if p.i != p.s.len() {
        return Err(format!("trailing text at byte {}", p.i));
    }
    let Json::Arr(items) = v else {
        return Err("not an array".into());
    };
    items
        .iter()
        .map(|item| {
            let get = |k: &str| item.field(k).ok_or(format!("no \"{k}\""));
            let Json::Str(name) = get("name")? else {
                return Err("name is not a string".into());
            };
            let dims = get("dims")?.cell()?;
            let Json::Arr(pieces) = get("pieces")? else {
                return Err("pieces is not an array".into());
            };
            let pieces = pieces
                .iter()
                .map(|p| match p {
                    Json::Arr(cells) => cells.iter().map(Json::cell).collect(),
                    _ => Err("a piece is not an array".to_string()),
                })
                .collect::<Result<_, _>>()?;
            let Json::Num(level) = get("level")? else {
                return Err("level is not a number".into());
            };
            Ok(BenchPuzzle {
                name: name.clone(),
                dims,
                pieces,
                level: usize::try_from(*level).map_err(|e| e.to_string())?,
            })
        })
        .collect()
}

/// The fixture text of `puzzles`: one puzzle per block, a piece per line.
pub fn bench_json(puzzles: &[BenchPuzzle]) -> String {
    let mut s = String::from("[\n");
    for (k, p) in puzzles.iter().enumerate() {
        let _ = writeln!(
            s,
            "  {{\n    \"name\": \"{}\",\n    \"dims\": [{}, {}, {}],\n    \"level\": {},\n    \"pieces\": [",
            p.name, p.dims[0], p.dims[1], p.dims[2], p.level
        );
        for (i, piece) in p.pieces.iter().enumerate() {
            let cells: Vec<String> = piece
                .iter()
                .map(|c| format!("[{},{},{}]", c[0], c[1], c[2]))
                .collect();
            let comma = if i + 1 < p.pieces.len() { "," } else { "" };
            let _ = writeln!(s, "      [{}]{comma}", cells.join(","));
        }
        let comma = if k + 1 < puzzles.len() { "," } else { "" };
        let _ = writeln!(s, "    ]\n  }}{comma}");
    }
    s.push_str("]\n");
    s
}

/// Writes `puzzle` to the folder `dir` as an assembly ([`write_puzzle`], 10 units per
/// cell) with an `expected.json` giving its level (`"axes": true`, as the shipped
/// `examples/voxel-level-*`).
pub fn write_bench_puzzle(dir: &Path, puzzle: &BenchPuzzle) -> std::io::Result<()> {
    write_puzzle(dir, &puzzle.name, &puzzle.pieces, 10)?;
    std::fs::write(
        dir.join("expected.json"),
        format!("{{ \"level\": {}, \"axes\": true }}\n", puzzle.level),
    )
}

/// The JSON values the fixture uses.
enum Json {
    Num(i64),
    Str(String),
    Arr(Vec<Json>),
    Obj(Vec<(String, Json)>),
}

impl Json {
    fn field(&self, key: &str) -> Option<&Json> {
        match self {
            Json::Obj(fields) => fields.iter().find(|(k, _)| k == key).map(|(_, v)| v),
            _ => None,
        }
    }

    fn cell(&self) -> Result<Cell, String> {
        match self {
            Json::Arr(v) if v.len() == 3 => {
                let mut c = [0; 3];
                for (a, x) in v.iter().enumerate() {
                    let Json::Num(n) = x else {
                        return Err("a coordinate is not a number".into());
                    };
                    c[a] = *n;
                }
                Ok(c)
            }
            _ => Err("not a cell [x, y, z]".into()),
        }
    }
}

struct Parser<'a> {
    s: &'a [u8],
    i: usize,
}

impl Parser<'_> {
    fn ws(&mut self) {
        while self.i < self.s.len() && self.s[self.i].is_ascii_whitespace() {
            self.i += 1;
        }
    }

    fn eat(&mut self, b: u8) -> bool {
        self.ws();
        if self.s.get(self.i) == Some(&b) {
            self.i += 1;
            true
        } else {
            false
        }
    }

    fn value(&mut self) -> Result<Json, String> {
        self.ws();
        let at = self.i;
        match self.s.get(at) {
            Some(b'[') => {
                self.i += 1;
                let mut v = Vec::new();
                if !self.eat(b']') {
                    loop {
                        v.push(self.value()?);
                        if self.eat(b']') {
                            break;
                        }
                        if !self.eat(b',') {
                            return Err(format!("expected , or ] at byte {}", self.i));
                        }
                    }
                }
                Ok(Json::Arr(v))
            }
            Some(b'{') => {
                self.i += 1;
                let mut v = Vec::new();
                if !self.eat(b'}') {
                    loop {
                        let Json::Str(k) = self.value()? else {
                            return Err(format!("expected a key at byte {}", self.i));
                        };
                        if !self.eat(b':') {
                            return Err(format!("expected : at byte {}", self.i));
                        }
                        v.push((k, self.value()?));
                        if self.eat(b'}') {
                            break;
                        }
                        if !self.eat(b',') {
                            return Err(format!("expected , or }} at byte {}", self.i));
                        }
                    }
                }
                Ok(Json::Obj(v))
            }
            Some(b'"') => {
                // Names only: no escapes.
                let end = self.s[at + 1..]
                    .iter()
                    .position(|&b| b == b'"')
                    .ok_or("an unterminated string")?;
                self.i = at + 2 + end;
                Ok(Json::Str(
                    String::from_utf8_lossy(&self.s[at + 1..at + 1 + end]).into_owned(),
                ))
            }
            Some(b'-' | b'0'..=b'9') => {
                self.i += 1;
                while self.i < self.s.len() && self.s[self.i].is_ascii_digit() {
                    self.i += 1;
                }
                let t = std::str::from_utf8(&self.s[at..self.i]).map_err(|e| e.to_string())?;
                t.parse().map(Json::Num).map_err(|e| format!("{t}: {e}"))
            }
            _ => Err(format!("unexpected text at byte {at}")),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::voxel_puzzles::{disassembles_completely, level, Level, Separations, Steps};

    #[test]
    fn the_fixture_text_reads_back() {
        let p = vec![BenchPuzzle {
            name: "two".into(),
            dims: [1, 1, 2],
            pieces: vec![vec![[0, 0, 0]], vec![[0, 0, 1]]],
            level: 1,
        }];
        assert_eq!(parse_bench(&bench_json(&p)).unwrap(), p);
        assert!(parse_bench("[{\"name\": 3}]").is_err());
        assert_eq!(
            bench_json(&bench_puzzles()),
            FIXTURE,
            "written by bench_json"
        );
    }

    #[test]
    fn fixture_puzzles_have_their_levels_and_come_apart_completely() {
        let puzzles = bench_puzzles();
        assert!((12..=16).contains(&puzzles.len()));
        let mut counts = Vec::new();
        for p in &puzzles {
            assert!((4..=8).contains(&p.pieces.len()), "{}", p.name);
            assert!(p.dims.iter().all(|&d| (1..=6).contains(&d)), "{}", p.name);
            for c in p.pieces.iter().flatten() {
                assert!((0..3).all(|a| (0..p.dims[a]).contains(&c[a])), "{}", p.name);
            }
            let mut all: Vec<Cell> = p.pieces.iter().flatten().copied().collect();
            let n = all.len();
            all.sort_unstable();
            all.dedup();
            assert_eq!(all.len(), n, "{}: disjoint pieces", p.name);
            assert_eq!(
                level(&p.pieces, Steps::Any, 10_000_000),
                Level::Moves(p.level),
                "{}",
                p.name
            );
            assert!(
                disassembles_completely(&p.pieces, 10_000_000, Separations::Every),
                "{}",
                p.name
            );
            counts.push(p.pieces.len());
        }
        for k in 4..=8 {
            assert!(counts.contains(&k), "a puzzle of {k} pieces");
        }
    }

    #[test]
    fn a_fixture_puzzle_writes_as_an_assembly() {
        let scratch = crate::Scratch::new("voxel-bench");
        let p = &bench_puzzles()[0];
        let dir = scratch.join(&p.name);
        write_bench_puzzle(&dir, p).unwrap();
        let json = std::fs::read_to_string(dir.join("assembly.json")).unwrap();
        assert!(json.contains(&format!("piece_{}.off", p.pieces.len() - 1)));
        assert!(std::fs::read_to_string(dir.join("expected.json"))
            .unwrap()
            .contains(&format!("\"level\": {}", p.level)));
    }
}
