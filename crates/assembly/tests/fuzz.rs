//! `load` never panics on garbage files or manifests (an `Err` or error problems are
//! fine). Stable-toolchain substitute for cargo-fuzz.

use apart_assembly::{load, LoadOptions};
use apart_testkit::Scratch;
use proptest::prelude::*;

proptest! {
    #![proptest_config(ProptestConfig::with_cases(300))]

    #[test]
    fn garbage_files_never_panic(bytes in prop::collection::vec(any::<u8>(), 0..400), ext in 0usize..7) {
        apart_formats::quiet_parser_panics();
        let exts = ["off", "obj", "stl", "ply", "gltf", "glb", "json"];
        let scratch = Scratch::new("fuzz");
        let p = scratch.join(format!("x.{}", exts[ext]));
        std::fs::write(&p, &bytes).unwrap();
        let _ = load(&p, &LoadOptions::default());
    }

    #[test]
    fn mutated_manifests_never_panic(cut in 0usize..400, junk in "[\\[\\]{}\":,0-9a-z. -]{0,12}") {
        apart_formats::quiet_parser_panics();
        let scratch = Scratch::new("fuzz-m");
        let d: &std::path::Path = &scratch;
        std::fs::write(d.join("a.off"), "OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n").unwrap();
        let m = r#"{"name": "m", "parts": [{"name": "a", "mesh": "a.off", "transform": {"translation": [1, 0, 0], "rotation": {"axis": [0, 0, 1], "angle_deg": 90}}}, {"name": "b", "mesh": "a.off", "pieces": ["a.off"], "transform": {"matrix": [1,0,0,5, 0,1,0,0, 0,0,1,0, 0,0,0,1]}}]}"#;
        let cut = cut % (m.len() + 1);
        let text = format!("{}{}{}", &m[..cut], junk, &m[cut..]);
        std::fs::write(d.join("assembly.json"), text).unwrap();
        let _ = load(d, &LoadOptions::default());
    }
}
