//! Writes a generated tessellated assembly as a folder of OFF files, for benchmarks and
//! trials with the CLI:
//! `cargo run --release -p apart-testkit --example write_curved -- KIND:SIZE DIR`.
//!
//! Kinds: `plug:TRIANGLES` (stepped plug in a socket), `pin:SEGMENTS` (pin in a hole,
//! same tessellation), `nut:SEGMENTS` (nut on a 3-ring bolt), `joint:SEGMENTS` (the
//! five-part bolted joint, each part a different segment count near SEGMENTS, as
//! separate CAD exports have), `joint-same:SEGMENTS` (the joint with one tessellation
//! for every part: its curved fits touch exactly), `rack:N` (an N by N rack of 64-segment
//! pins in blocks under a plate, `2 N² + 1` parts).
use apart_testkit::{curved, joints};

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let parsed = args.get(1).and_then(|a| {
        let (kind, size) = a.split_once(':')?;
        Some((kind.to_string(), size.parse::<usize>().ok()?))
    });
    let (Some((kind, size)), Some(dir)) = (parsed, args.get(2)) else {
        eprintln!("usage: write_curved plug|pin|nut|joint|joint-same|rack:SIZE DIR");
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
        _ => {
            eprintln!("unknown kind {kind}: expected plug, pin, nut, joint, joint-same or rack");
            std::process::exit(2);
        }
    };
    curved::write_off_dir(&parts, std::path::Path::new(dir))?;
    println!("{} triangles in {dir}", curved::triangle_count(&parts));
    Ok(())
}
