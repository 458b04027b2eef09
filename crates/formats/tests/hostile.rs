//! Hostile and careless inputs through the public reading API (issue 10): every case
//! ends quickly with a clear error naming the file and the element, or reads right.
//! The inputs are built here, small; nothing big is committed.

use apart_formats::{read_file, read_file_with, ReadOptions, MAX_FILE_BYTES};
use apart_testkit::Scratch;
use std::path::Path;
use std::sync::mpsc;
use std::time::Duration;

fn scratch(name: &str) -> Scratch {
    Scratch::new(&format!("fhostile-{}", name))
}

/// `read_file(path)`'s error message, failing the test if reading takes more than ten
/// seconds (a blocked open of a FIFO would otherwise hang the suite).
fn error_within(path: &Path, options: ReadOptions) -> String {
    let (tx, rx) = mpsc::channel();
    let p = path.to_path_buf();
    std::thread::spawn(move || {
        let _ = tx.send(read_file_with(&p, &options).map(|o| o.len()));
    });
    match rx.recv_timeout(Duration::from_secs(10)) {
        Ok(Ok(n)) => panic!("{}: read {n} objects", path.display()),
        Ok(Err(e)) => e.to_string(),
        Err(_) => panic!("{}: still reading after 10 s", path.display()),
    }
}

const TETRA: &[u8] =
    b"OFF\n4 4 0\n0 0 0\n1 0 0\n0 1 0\n0 0 1\n3 0 2 1\n3 0 1 3\n3 1 2 3\n3 0 3 2\n";

#[test]
fn only_regular_files_are_read() {
    apart_formats::quiet_parser_panics();
    let d = scratch("regular");
    std::fs::write(d.join("ok.off"), TETRA).unwrap();
    assert_eq!(read_file(&d.join("ok.off")).unwrap().len(), 1);
    std::fs::create_dir_all(d.join("folder.stl")).unwrap();
    let e = error_within(&d.join("folder.stl"), ReadOptions::default());
    assert!(
        e.contains("folder.stl: it is a folder, not a regular file"),
        "{e}"
    );
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink("/dev/zero", d.join("zero.stl")).unwrap();
        let e = error_within(&d.join("zero.stl"), ReadOptions::default());
        assert!(
            e.contains("zero.stl: it is a character device, not a regular file"),
            "{e}"
        );
        let fifo = d.join("pipe.obj");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let e = error_within(&fifo, ReadOptions::default());
            assert!(
                e.contains("pipe.obj: it is a named pipe (FIFO), not a regular file"),
                "{e}"
            );
        }
    }
    // One byte more than the limit, as a sparse file: refused before reading.
    let big = d.join("big.stl");
    let f = std::fs::File::create(&big).unwrap();
    if f.set_len(MAX_FILE_BYTES + 1).is_ok() {
        let e = error_within(&big, ReadOptions::default());
        assert!(
            e.contains(
                "big.stl: it holds 4294967297 bytes, more than the limit of 4294967296 bytes"
            ),
            "{e}"
        );
    }
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn file_names_are_escaped() {
    let d = scratch("names");
    let name = d.join("a\x1b[2Jb.step");
    std::fs::write(&name, b"x").unwrap();
    let e = read_file(&name).unwrap_err().to_string();
    assert!(e.contains("a\\x1b[2Jb.step") && !e.contains('\x1b'), "{e}");
    let _ = std::fs::remove_dir_all(&d);
}

#[test]
fn huge_declared_counts_fail_fast() {
    let d = scratch("counts");
    let mut ply = b"ply\nformat binary_little_endian 1.0\nelement vertex 3\nproperty float x\nproperty float y\nproperty float z\nelement face 4000000000\nproperty list uchar int vertex_indices\nend_header\n".to_vec();
    ply.resize(250, 0);
    std::fs::write(d.join("face.ply"), &ply).unwrap();
    let e = error_within(&d.join("face.ply"), ReadOptions::default());
    assert!(
        e.contains("element \"face\" declares 4000000000 entries"),
        "{e}"
    );
    let mut ply =
        b"ply\nformat binary_little_endian 1.0\nelement vertex 4000000000\nend_header\n".to_vec();
    ply.resize(250, 0);
    std::fs::write(d.join("vertex.ply"), &ply).unwrap();
    let e = error_within(&d.join("vertex.ply"), ReadOptions::default());
    assert!(
        e.contains("element \"vertex\" declares 4000000000 entries"),
        "{e}"
    );
    let mut stl = vec![0u8; 84];
    stl[80..84].copy_from_slice(&4_000_000_000u32.to_le_bytes());
    std::fs::write(d.join("t.stl"), &stl).unwrap();
    let e = error_within(&d.join("t.stl"), ReadOptions::default());
    assert!(
        e.contains("declares 4000000000 triangles but holds only 0"),
        "{e}"
    );
    std::fs::write(d.join("t.off"), b"OFF\n4000000000 1 0\n").unwrap();
    let e = error_within(&d.join("t.off"), ReadOptions::default());
    assert!(
        e.contains("4000000000 vertices and 1 faces declared"),
        "{e}"
    );
    let _ = std::fs::remove_dir_all(&d);
}

/// A `.gltf` whose one buffer is the file `uri`, holding one triangle.
fn gltf_with_buffer(uri: &str) -> String {
    format!(
        r#"{{"asset":{{"version":"2.0"}},"scene":0,"scenes":[{{"nodes":[0]}}],"nodes":[{{"mesh":0}}],
"meshes":[{{"primitives":[{{"attributes":{{"POSITION":0}}}}]}}],
"buffers":[{{"byteLength":36,"uri":"{uri}"}}],
"bufferViews":[{{"buffer":0,"byteOffset":0,"byteLength":36}}],
"accessors":[{{"bufferView":0,"componentType":5126,"count":3,"type":"VEC3","min":[0,0,0],"max":[1,1,0]}}]}}"#
    )
}

fn triangle_bin() -> Vec<u8> {
    [[0f32, 0.0, 0.0], [1.0, 0.0, 0.0], [0.0, 1.0, 0.0]]
        .iter()
        .flatten()
        .flat_map(|c| c.to_le_bytes())
        .collect()
}

#[test]
fn gltf_buffers_stay_in_the_folder_of_the_file() {
    let d = scratch("gltf");
    std::fs::create_dir_all(d.join("model")).unwrap();
    std::fs::write(d.join("model/tri.bin"), triangle_bin()).unwrap();
    std::fs::write(d.join("outside.bin"), triangle_bin()).unwrap();
    let write = |name: &str, uri: &str| {
        let p = d.join("model").join(name);
        std::fs::write(&p, gltf_with_buffer(uri)).unwrap();
        p
    };
    let ok = write("ok.gltf", "tri.bin");
    assert_eq!(read_file(&ok).unwrap()[0].vertices[1], [1.0, 0.0, 0.0]);
    let up = write("up.gltf", "../outside.bin");
    let e = error_within(&up, ReadOptions::default());
    assert_eq!(
        e,
        format!(
            "buffer 0 (\"../outside.bin\"): \"../outside.bin\" lies outside the folder {} (a \"..\" component leaves the folder); --allow-outside reads it anyway",
            d.join("model").display()
        )
    );
    // Lifted explicitly.
    let lifted = ReadOptions {
        allow_outside: true,
    };
    assert_eq!(read_file_with(&up, &lifted).unwrap().len(), 1);
    // A bare file name: its folder is shown as ".".
    let cwd = std::env::current_dir().unwrap();
    std::env::set_current_dir(d.join("model")).unwrap();
    let e = error_within(Path::new("up.gltf"), ReadOptions::default());
    std::env::set_current_dir(cwd).unwrap();
    assert!(e.contains("lies outside the folder . (a"), "{e}");
    let abs = write("abs.gltf", "/etc/passwd");
    let e = error_within(&abs, ReadOptions::default());
    assert!(e.contains("it is an absolute path"), "{e}");
    #[cfg(unix)]
    {
        std::os::unix::fs::symlink(d.join("outside.bin"), d.join("model/link.bin")).unwrap();
        let link = write("link.gltf", "link.bin");
        let e = error_within(&link, ReadOptions::default());
        assert!(e.contains("a symbolic link leads to"), "{e}");
        let fifo = d.join("model/pipe.bin");
        if std::process::Command::new("mkfifo")
            .arg(&fifo)
            .status()
            .is_ok_and(|s| s.success())
        {
            let p = write("pipe.gltf", "pipe.bin");
            let e = error_within(&p, ReadOptions::default());
            assert!(e.contains("named pipe (FIFO), not a regular file"), "{e}");
        }
    }
    let _ = std::fs::remove_dir_all(&d);
}
