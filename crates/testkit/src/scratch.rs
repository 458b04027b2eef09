//! A scratch folder for a test's files, removed when the test is done with it.

use std::path::{Path, PathBuf};

/// A fresh folder `apart-<tag>-<process id>` in the system's temporary folder (emptied
/// first), removed with everything in it when dropped. Derefs to its path.
#[derive(Debug)]
pub struct Scratch(PathBuf);

impl Scratch {
    /// A fresh, empty folder named after `tag` and this process.
    pub fn new(tag: &str) -> Scratch {
        let dir = std::env::temp_dir().join(format!("apart-{tag}-{}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).expect("a scratch folder");
        Scratch(dir)
    }

    /// The folder's path.
    pub fn path(&self) -> &Path {
        &self.0
    }
}

impl std::ops::Deref for Scratch {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Scratch {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Scratch {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_scratch_folder_is_there_until_dropped() {
        let s = Scratch::new("scratch-self-test");
        std::fs::write(s.join("x.txt"), "x").unwrap();
        let p = s.path().to_path_buf();
        assert!(p.join("x.txt").is_file());
        drop(s);
        assert!(!p.exists());
    }
}
