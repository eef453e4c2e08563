//! What the tests of the C interface and of the header share: where the crate and the
//! library are, and compiling a C program against them.

use std::path::{Path, PathBuf};
use std::process::Command;

pub fn crate_dir() -> PathBuf {
    PathBuf::from(env!("CARGO_MANIFEST_DIR"))
}

/// The folder holding the cdylib cargo built beside this test.
pub fn library_dir() -> PathBuf {
    let exe = std::env::current_exe().unwrap();
    let deps = exe.parent().unwrap();
    [deps, deps.parent().unwrap()]
        .into_iter()
        .find(|d| d.join("libsamplab_c.so").is_file())
        .expect("libsamplab_c.so beside the test binary")
        .to_path_buf()
}

/// Compile the C program `source` into `out`, against the header and the library, and put
/// the link its SONAME names (`libsamplab_c.so.0`, which an install makes) beside it, where
/// its rpath looks.
pub fn compile(source: &Path, out: &Path) {
    let dir = out.parent().unwrap();
    let soname = dir.join(format!("libsamplab_c.so.{}", env!("CARGO_PKG_VERSION_MAJOR")));
    if !soname.exists() {
        std::os::unix::fs::symlink(library_dir().join("libsamplab_c.so"), soname).unwrap();
    }
    let cc = std::env::var("CC").unwrap_or_else(|_| "cc".into());
    let status = Command::new(&cc)
        .args(["-std=c99", "-Wall", "-Wextra", "-Werror", "-o"])
        .arg(out)
        .arg(source)
        .arg("-I")
        .arg(crate_dir().join("include"))
        .arg("-L")
        .arg(library_dir())
        .args(["-lsamplab_c", "-lm"])
        .arg(format!("-Wl,-rpath,{}", dir.display()))
        .output()
        .unwrap_or_else(|e| panic!("running the C compiler {cc}: {e}"));
    assert!(
        status.status.success(),
        "{} does not compile: {}",
        source.display(),
        String::from_utf8_lossy(&status.stderr)
    );
}
