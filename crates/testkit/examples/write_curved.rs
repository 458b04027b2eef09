//! Writes a generated tessellated assembly as a folder of OFF files, for benchmarks and
//! trials with the CLI:
//! `cargo run --release -p apart-testkit --example write_curved -- KIND:SIZE DIR`.
//!
//! Kinds: `plug:TRIANGLES` (stepped plug in a socket), `pin:SEGMENTS` (pin in a hole,
//! same tessellation), `nut:SEGMENTS` (nut on a 3-ring bolt), `joint:SEGMENTS` (the
//! five-part bolted joint, each part a different segment count near SEGMENTS, as
//! separate CAD exports have), `joint-same:SEGMENTS` (the joint with one tessellation
//! for every part: its curved fits touch exactly), `rack:N` (an N by N rack of 64-segment
//! pins in blocks under a plate, `2 N² + 1` parts), `cubes:N` (an N by N by N lattice of
//! unit cubes, face to face, `N³` parts), `loose:N` (the same lattice with a gap of half
//! a cube between neighbours).
use apart_testkit::{curved, joints};

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let parsed = args.get(1).and_then(|a| {
        let (kind, size) = a.split_once(':')?;
        Some((kind.to_string(), size.parse::<usize>().ok()?))
    });
    let (Some((kind, size)), Some(dir)) = (parsed, args.get(2)) else {
        eprintln!("usage: write_curved plug|pin|nut|joint|joint-same|rack|cubes|loose:SIZE DIR");
        std::process::exit(2);
    };
    let parts = match kind.as_str() {
        "plug" => curved::plug_and_socket(size),
        "pin" => curved::pin_in_hole(size.max(3), size.max(3), 0.0),
        "nut" => curved::nut_on_bolt(size.max(3), 3),
        "joint" => {
            let n = size.max(8);
            joints::bolted_joint([n, n - n / 25, n + n / 25, n - n / 12, n + n / 12])
        }
        "joint-same" => joints::bolted_joint([size.max(8); 5]),
        "rack" => curved::pin_rack(size.max(1), 64),
        "cubes" => lattice(size.max(1), 1.0),
        "loose" => lattice(size.max(1), 1.5),
        _ => {
            eprintln!("unknown kind {kind}: expected plug, pin, nut, joint, joint-same, rack, cubes or loose");
            std::process::exit(2);
        }
    };
    curved::write_off_dir(&parts, std::path::Path::new(dir))?;
    println!("{} triangles in {dir}", curved::triangle_count(&parts));
    Ok(())
}

/// An `n³` lattice of unit cubes `c_X_Y_Z`, their corners `pitch` apart (1: face to face).
fn lattice(n: usize, pitch: f64) -> Vec<curved::NamedSoup> {
    let mut parts = Vec::with_capacity(n * n * n);
    for x in 0..n {
        for y in 0..n {
            for z in 0..n {
                let lo = [x, y, z].map(|k| k as f64 * pitch);
                let hi = lo.map(|k| k + 1.0);
                parts.push((
                    format!("c_{x}_{y}_{z}"),
                    apart_testkit::defects::box_soup(lo, hi),
                ));
            }
        }
    }
    parts
}
