//! The shared library's SONAME: `libsamplab_c.so.MAJOR`, so that a program linked against
//! one release finds any later one of the same major version (scripts/install-c installs the
//! links).

fn main() {
    let major = std::env::var("CARGO_PKG_VERSION_MAJOR").expect("cargo sets the version");
    if std::env::var("CARGO_CFG_TARGET_OS").as_deref() == Ok("linux") {
        println!("cargo::rustc-cdylib-link-arg=-Wl,-soname,libsamplab_c.so.{major}");
    }
}
