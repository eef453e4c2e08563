//! What the CLI's test files share.

use std::path::{Path, PathBuf};

/// A fresh directory under the system's temporary one, named by the test file's `kind`, the
/// process and `name`, removed with everything in it when dropped (so a test run leaves
/// nothing behind; a failing test's files go too, its assertion message names what failed).
pub struct Temp(PathBuf);

impl Temp {
    pub fn new(kind: &str, name: &str) -> Temp {
        let dir = std::env::temp_dir().join(format!("samplab-{kind}-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        Temp(dir)
    }
}

impl std::ops::Deref for Temp {
    type Target = Path;
    fn deref(&self) -> &Path {
        &self.0
    }
}

impl AsRef<Path> for Temp {
    fn as_ref(&self) -> &Path {
        &self.0
    }
}

impl Drop for Temp {
    fn drop(&mut self) {
        let _ = std::fs::remove_dir_all(&self.0);
    }
}
