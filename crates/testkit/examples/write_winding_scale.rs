//! Writes large soups that only the winding-number rule makes solid, for timing the
//! loader on them: `cargo run --release -p apart-testkit --example write_winding_scale
//! -- <folder>` writes `<folder>/gear-<teeth>/gear.off` (an extruded gear whose flanks
//! cross at every root) and `<folder>/thread-<layers>/bolt.off` (a core through stacked
//! crossing rings with open seams and slivers), each alone in its folder, at several
//! sizes, and prints each file's triangle count and volume: the thread's known one, and
//! for the gears the independent Monte Carlo estimate with its bound (the gear's closed
//! form falls short of it at these sizes).

use apart_testkit::soups::{gear, thread, write_off_dir, Case};
use apart_testkit::winding::monte_carlo_volume;
use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let root: PathBuf = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("winding-scale"), PathBuf::from);
    let mut cases: Vec<(String, &str, Case)> = Vec::new();
    for teeth in [100usize, 300, 900, 1250] {
        // A pitch of about 40 grid units at the tips.
        let tip = (teeth as i64 * 40 / 6).max(60);
        cases.push((
            format!("gear-{teeth}"),
            "gear",
            gear(teeth, tip * 9 / 10, tip, 50, 1),
        ));
    }
    for layers in [100usize, 500, 1500] {
        cases.push((format!("thread-{layers}"), "bolt", thread(layers, 1)));
    }
    for (name, part, case) in cases {
        let dir = root.join(&name);
        let _ = std::fs::remove_dir_all(&dir);
        let triangles = case.soup.triangles.len();
        let volume = if part == "gear" {
            let e = monte_carlo_volume(&case.soup, 400_000, 3);
            format!("≈ {:.4e} ± {:.1e} (Monte Carlo)", e.volume, e.bound)
        } else {
            format!("{}/{}", case.volume.0, case.volume.1)
        };
        write_off_dir(&[(part.to_string(), case.soup)], &dir)?;
        println!("{}: {triangles} triangles, volume {volume}", dir.display());
    }
    Ok(())
}
