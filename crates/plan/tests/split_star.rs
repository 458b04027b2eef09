//! The Split Star has exactly eight partitioning motions, all isolated directions
//! (±1, ±1, ±1), each moving three parts (an independently checked table).

mod common;

use apart_kernel::Vec3;
use apart_plan::{partition_pieces, CellKind, Options};

#[test]
fn eight_isolated_directions() {
    let parts = common::split_star();
    let names: Vec<&str> = parts.iter().map(|p| p.name.as_str()).collect();
    let r = partition_pieces(&parts, &Options::default()).unwrap();
    assert!(!r.interlocked);
    let mut got: Vec<(Vec3, Vec<&str>)> = r
        .solutions
        .iter()
        .map(|s| {
            assert_eq!(s.cell, CellKind::Vertex, "{s:?}");
            let mut m: Vec<&str> = s.moving.iter().map(|&k| names[k]).collect();
            m.sort();
            (s.direction.clone(), m)
        })
        .collect();
    got.sort_by_key(|(d, _)| d.to_strings());
    // The sign of x picks blue (+) or purple (-), of y yellow or turquoise, of z red or green.
    let mut want: Vec<(Vec3, Vec<&str>)> = Vec::new();
    for sx in [1, -1] {
        for sy in [1, -1] {
            for sz in [1, -1] {
                let mut m = vec![
                    if sx > 0 { "blue" } else { "purple" },
                    if sy > 0 { "yellow" } else { "turquoise" },
                    if sz > 0 { "red" } else { "green" },
                ];
                m.sort();
                want.push((Vec3::new(sx, sy, sz), m));
            }
        }
    }
    want.sort_by_key(|(d, _)| d.to_strings());
    assert_eq!(got, want);
}
