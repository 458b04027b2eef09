//! Writes the two-part assemblies of `apart_testkit::soups` (soups that only the
//! winding-number rule makes solid), one folder per family, as OFF files:
//! `cargo run -p apart-testkit --example write_winding_soups -- <folder>`.

use apart_testkit::soups::{families, write_off_dir};
use std::path::PathBuf;

fn main() -> std::io::Result<()> {
    let root: PathBuf = std::env::args_os()
        .nth(1)
        .map_or_else(|| PathBuf::from("winding-soups"), PathBuf::from);
    for f in families() {
        let dir = root.join(f.name);
        let _ = std::fs::remove_dir_all(&dir);
        write_off_dir(&f.assembly, &dir)?;
        println!(
            "{}: part \"{}\", volume {}/{}",
            dir.display(),
            f.part,
            f.case.volume.0,
            f.case.volume.1
        );
    }
    Ok(())
}
