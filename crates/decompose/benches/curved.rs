//! Decomposition of tessellated curved parts (apart-testkit's `curved`, snapped on a
//! 30-bit grid as the loader does): prints a markdown table of pieces and times.
//!
//! `cargo bench -p apart-decompose --bench curved [-- socket:20000 sleeve:1000 ... [noverify]]`;
//! without arguments, the rows of PIECES.md.

#[path = "../tests/common/mod.rs"]
mod common;

use apart_decompose::{decompose, verify, Options};
use apart_testkit::curved as gen;
use std::time::Instant;

/// The named part of a generated assembly: `kind:size`.
fn shape(case: &str) -> (String, common::Snapped) {
    let (kind, size) = case.split_once(':').expect("kind:size");
    let size: usize = size.parse().expect("a size");
    let (parts, name, label) = match kind {
        "socket" => (
            gen::plug_and_socket(size),
            "socket",
            format!("socket of plug_and_socket({size})"),
        ),
        "plug" => (
            gen::plug_and_socket(size),
            "plug",
            format!("plug of plug_and_socket({size})"),
        ),
        "block" => (
            gen::pin_in_hole(size, size, 0.0),
            "block",
            format!("block of pin_in_hole({size}, {size})"),
        ),
        "nut" => (
            gen::nut_on_bolt(size, 3),
            "nut",
            format!("nut of nut_on_bolt({size}, 3)"),
        ),
        "bolt" => (
            gen::nut_on_bolt(size, 3),
            "bolt",
            format!("bolt of nut_on_bolt({size}, 3)"),
        ),
        "sleeve" => (
            // A ring-like part: a tube of radii 5 and 8, z from 0 to 10.
            vec![(
                "sleeve".to_string(),
                gen::lathe(
                    &[[5.0, 10.0], [5.0, 0.0], [8.0, 0.0], [8.0, 10.0]],
                    size,
                    0.0,
                ),
            )],
            "sleeve",
            format!("sleeve of {size} segments"),
        ),
        _ => panic!("unknown kind {kind}"),
    };
    (label, common::part(&parts, name))
}

fn main() {
    let mut args: Vec<String> = std::env::args()
        .skip(1)
        .filter(|a| !a.starts_with('-'))
        .collect();
    // `noverify` skips the (slower) verification.
    let check = !args.iter().any(|a| a == "noverify");
    args.retain(|a| a != "noverify");
    let cases: Vec<String> = if args.is_empty() {
        [
            "socket:2000",
            "socket:20000",
            "socket:60000",
            "block:1000",
            "sleeve:1000",
            "sleeve:4000",
            "nut:256",
            "bolt:256",
        ]
        .map(String::from)
        .to_vec()
    } else {
        args
    };
    println!(
        "| shape | triangles | reflex edges r | pieces | before merging | splits | den bits (vertex / piece) | integral pieces | sequential s | parallel s | verify s |"
    );
    println!("|---|---:|---:|---:|---:|---:|---:|---:|---:|---:|---:|");
    for case in cases {
        let (label, s) = shape(&case);
        let seq = Options {
            parallel: false,
            ..Options::default()
        };
        let t = Instant::now();
        let d = decompose(&s.points, &s.tris, &seq).expect("decompose");
        let ts = t.elapsed().as_secs_f64();
        let t = Instant::now();
        let dp = decompose(&s.points, &s.tris, &Options::default()).expect("decompose");
        let tp = t.elapsed().as_secs_f64();
        assert_eq!(d.pieces.len(), dp.pieces.len());
        let t = Instant::now();
        if check {
            verify(&s.points, &s.tris, &d.pieces).expect("verify");
        }
        let tv = t.elapsed().as_secs_f64();
        let bits = d
            .pieces
            .iter()
            .map(|p| apart_kernel::int::bit_len(p.den()))
            .max()
            .unwrap_or(0);
        let integral = d
            .pieces
            .iter()
            .filter(|p| p.den() == &apart_kernel::Int::ONE)
            .count();
        println!(
            "| {label} | {} | {} | {} | {} | {} | {} / {} | {integral} | {ts:.3} | {tp:.3} | {tv:.3} |",
            s.tris.len(),
            d.reflex_edges,
            d.pieces.len(),
            d.stats.partition_pieces,
            d.stats.splits,
            d.stats.max_den_bits,
            bits.saturating_sub(1),
        );
    }
}
