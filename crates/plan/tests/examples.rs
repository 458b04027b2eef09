//! Partitioning of the assemblies shipped under `examples/`, through the loader.

use apart_assembly::{load, LoadOptions};
use apart_plan::{partition, CellKind, Options};
use std::path::PathBuf;

fn example(name: &str) -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
        .join("../../examples")
        .join(name)
}

/// (direction, sorted moving names) of every solution.
fn solutions(name: &str) -> Vec<(Vec<i64>, Vec<String>, CellKind)> {
    let loaded = load(&example(name), &LoadOptions::default()).unwrap();
    assert!(loaded.is_valid(), "{name}: {:?}", loaded.problems);
    let r = partition(&loaded.assembly, &Options::default()).unwrap();
    let mut out: Vec<(Vec<i64>, Vec<String>, CellKind)> = r
        .solutions
        .iter()
        .map(|s| {
            let d: Vec<i64> = s
                .direction
                .to_strings()
                .iter()
                .map(|x| x.parse().unwrap())
                .collect();
            let mut m: Vec<String> = s.moving.iter().map(|&k| r.names[k].clone()).collect();
            m.sort();
            (d, m, s.cell)
        })
        .collect();
    out.sort();
    out
}

/// The independently checked table: the sign of x picks blue (+) or purple (−), of y yellow or
/// turquoise, of z red or green; all isolated directions.
fn split_star_expected() -> Vec<(Vec<i64>, Vec<String>, CellKind)> {
    let mut want = Vec::new();
    for sx in [1, -1] {
        for sy in [1, -1] {
            for sz in [1, -1] {
                let mut m: Vec<String> = vec![
                    if sx > 0 { "blue" } else { "purple" }.into(),
                    if sy > 0 { "yellow" } else { "turquoise" }.into(),
                    if sz > 0 { "red" } else { "green" }.into(),
                ];
                m.sort();
                want.push((vec![sx, sy, sz], m, CellKind::Vertex));
            }
        }
    }
    want.sort();
    want
}

#[test]
fn split_star_with_three_five_and_eight_pieces_per_part() {
    for name in ["split-star-3", "split-star-5", "split-star-8"] {
        assert_eq!(solutions(name), split_star_expected(), "{name}");
    }
}

#[test]
fn peg_in_the_hole_leaves_along_the_axis_only() {
    let got = solutions("peg-in-the-hole");
    assert_eq!(got.len(), 2, "{got:?}");
    assert!(got.iter().all(|(_, _, c)| *c == CellKind::Vertex));
    // The two solutions are antipodal: the peg one way, the holed part the other.
    let (a, b) = (&got[0], &got[1]);
    assert_eq!(a.0.iter().map(|x| -x).collect::<Vec<_>>(), b.0);
    let mut movers: Vec<&str> = got.iter().map(|(_, m, _)| m[0].as_str()).collect();
    movers.sort();
    assert_eq!(movers, vec!["blue", "red"]);
}

#[test]
fn plain_split_star_is_decomposed_and_gives_the_same_eight() {
    // No pieces declared: every part is decomposed exactly, and the partitioning is the
    // one of the hand-decomposed versions.
    assert_eq!(solutions("split-star"), split_star_expected());
}
