//! Writes the five-part bolted joint of `apart_testkit::joints` with about `n`
//! segments per part (each part a different count, as separate CAD exports have), as OFF
//! files: `cargo run --release -p apart-testkit --example write_joint -- N DIR`.

fn main() -> std::io::Result<()> {
    let args: Vec<String> = std::env::args().collect();
    let (Some(n), Some(dir)) = (
        args.get(1).and_then(|a| a.parse::<usize>().ok()),
        args.get(2),
    ) else {
        eprintln!("usage: write_joint N DIR");
        std::process::exit(2);
    };
    let n = n.max(8);
    let segments = [n, n - n / 25, n + n / 25, n - n / 12, n + n / 12];
    let parts = apart_testkit::joints::bolted_joint(segments);
    apart_testkit::curved::write_off_dir(&parts, std::path::Path::new(dir))?;
    println!(
        "{} triangles in {}",
        apart_testkit::curved::triangle_count(&parts),
        dir
    );
    Ok(())
}
