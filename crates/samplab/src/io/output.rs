//! Outputs that never destroy what samplab did not write.
//!
//! - A file is written to a temporary sibling and renamed over its target, so a failed or
//!   interrupted write leaves the target as it was. A target that exists and is not a
//!   regular file (a device such as `/dev/null`, a FIFO) is written through instead, never
//!   renamed over; a folder is never replaced by a file.
//! - A folder is filled as a temporary sibling and renamed into place. An existing target
//!   folder is replaced only when samplab made it (its [`MANIFEST`] lists every entry it
//!   holds) or when the caller forces it; a file is never replaced by a folder; the working
//!   folder, any folder above it, the home folder and `/` are never an output folder.
//! - Several outputs of one command are staged first and renamed together ([`Staged`]), so
//!   they appear together or not at all.
//! - A target named `-` is refused: by the command-line convention it is standard output,
//!   which a front end writes itself; made as a file or folder it would be a stray `-`.
//!
//! Every temporary path is registered while it exists, so that a front end stopping the
//! process at once (a second signal, a watchdog) can remove them first ([`abandon`]).

use std::path::{Path, PathBuf};
use std::sync::Mutex;

use crate::error::{Error, Result};

/// The file listing what samplab wrote in an output folder, one relative path a line.
pub const MANIFEST: &str = ".samplab-manifest";

/// The temporary files and folders that exist now. Held while outputs are renamed into
/// place, so that [`abandon`] never runs between two renames of one command.
static STAGED: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn staged() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    STAGED.lock().unwrap_or_else(std::sync::PoisonError::into_inner)
}

fn register(path: &Path) {
    staged().push(path.to_path_buf());
}

fn remove(path: &Path) {
    let _ = std::fs::remove_file(path).or_else(|_| std::fs::remove_dir_all(path));
}

/// Remove a temporary path and forget it (`list` is the held [`STAGED`]).
fn discard(list: &mut Vec<PathBuf>, path: &Path) {
    remove(path);
    list.retain(|p| p != path);
}

/// Remove every temporary output that exists now and exit the process with `code`, holding
/// the lock so that no output is renamed into place after this: for a front end that must
/// stop at once.
pub fn abandon(code: i32) -> ! {
    let list = staged();
    for path in list.iter() {
        remove(path);
    }
    std::process::exit(code)
}

fn io_error(path: &Path, e: &std::io::Error) -> Error {
    Error::Io { path: path.display().to_string(), reason: e.to_string() }
}

/// Refuse the target `-` (module docs): `what` is a file or a folder.
fn refuse_dash(path: &Path, what: &str) -> Result<()> {
    if path.as_os_str() == "-" {
        return Err(Error::Io {
            path: "-".into(),
            reason: format!("means standard output, which cannot hold a {what}; name a {what}"),
        });
    }
    Ok(())
}

/// What is at `path` now (following links).
enum Existing {
    Nothing,
    File,
    Folder,
    /// A device, a FIFO or a socket: written through, never replaced.
    Special,
}

fn existing(path: &Path) -> Existing {
    match std::fs::metadata(path) {
        Err(_) => Existing::Nothing,
        Ok(m) if m.is_dir() => Existing::Folder,
        Ok(m) if m.is_file() => Existing::File,
        Ok(_) => Existing::Special,
    }
}

/// `path`'s folder and file name.
fn split(path: &Path) -> Result<(PathBuf, String)> {
    let dir = path.parent().filter(|p| !p.as_os_str().is_empty()).unwrap_or(Path::new("."));
    let name = path
        .file_name()
        .ok_or_else(|| Error::Io { path: path.display().to_string(), reason: "not a file name".into() })?;
    Ok((dir.to_path_buf(), name.to_string_lossy().into_owned()))
}

/// Refuse a file of at least `bytes` for `path` when its file system has less room free
/// (a streamed output that would fill the disk after hours of work).
///
/// # Errors
/// [`Error::Io`] with both sizes.
pub(crate) fn check_disk(path: &Path, bytes: u128) -> Result<()> {
    #[cfg(unix)]
    {
        let (dir, _) = split(path)?;
        let Ok(c) = std::ffi::CString::new(dir.as_os_str().as_encoded_bytes()) else { return Ok(()) };
        // SAFETY: statvfs fills the zeroed struct from a NUL-terminated path.
        let mut st: libc::statvfs = unsafe { std::mem::zeroed() };
        if unsafe { libc::statvfs(c.as_ptr(), &raw mut st) } != 0 {
            return Ok(());
        }
        let free = u128::from(st.f_bavail) * u128::from(st.f_frsize);
        if bytes > free && !matches!(existing(path), Existing::Special) {
            return Err(Error::Io {
                path: path.display().to_string(),
                reason: format!(
                    "needs at least {} on disk, {} free there",
                    crate::memory::human(bytes),
                    crate::memory::human(free)
                ),
            });
        }
    }
    Ok(())
}

/// Outputs of one command, staged as temporary files and renamed into place together by
/// [`Staged::commit`]; dropped uncommitted, they leave nothing behind.
#[derive(Debug, Default)]
pub struct Staged {
    /// (temporary path, target), in the order staged.
    files: Vec<(PathBuf, PathBuf)>,
}

impl Staged {
    /// No outputs yet.
    pub fn new() -> Self {
        Staged::default()
    }

    /// Stage `bytes` for `path` (a device or a FIFO is written through now).
    ///
    /// # Errors
    /// `path` is a folder, its folder is missing or cannot be written.
    pub fn file(&mut self, path: &Path, bytes: &[u8]) -> Result<()> {
        self.file_with(path, &mut |w| w.write_all(bytes).map_err(|e| io_error(path, &e)))
    }

    /// Stage what `write` writes for `path`.
    ///
    /// # Errors
    /// As [`Staged::file`], and `write`'s errors.
    pub fn file_with(
        &mut self,
        path: &Path,
        write: &mut dyn FnMut(&mut dyn std::io::Write) -> Result<()>,
    ) -> Result<()> {
        refuse_dash(path, "file")?;
        match existing(path) {
            Existing::Folder => {
                return Err(Error::Io {
                    path: path.display().to_string(),
                    reason: "is a folder; samplab does not replace a folder by a file".into(),
                });
            }
            Existing::Special => {
                // a device or a FIFO: written through (a FIFO's open waits for its reader)
                let f = std::fs::OpenOptions::new().write(true).open(path).map_err(|e| io_error(path, &e))?;
                let mut w = std::io::BufWriter::new(f);
                write(&mut w)?;
                return w.into_inner().map(drop).map_err(|e| io_error(path, e.error()));
            }
            Existing::Nothing | Existing::File => {}
        }
        let (dir, name) = split(path)?;
        let tmp = dir.join(format!(".{name}.{}.{}.tmp", std::process::id(), self.files.len()));
        self.stage_into(&tmp, path, write)?;
        self.files.push((tmp, path.to_path_buf()));
        Ok(())
    }

    fn stage_into(
        &self,
        tmp: &Path,
        path: &Path,
        write: &mut dyn FnMut(&mut dyn std::io::Write) -> Result<()>,
    ) -> Result<()> {
        register(tmp);
        let result = std::fs::File::create(tmp).map_err(|e| io_error(path, &e)).and_then(|f| {
            let mut w = std::io::BufWriter::new(f);
            write(&mut w)?;
            let f = w.into_inner().map_err(|e| io_error(path, e.error()))?;
            f.sync_all().map_err(|e| io_error(path, &e))
        });
        if result.is_err() {
            discard(&mut staged(), tmp);
        }
        result
    }

    /// Rename every staged file into place.
    ///
    /// # Errors
    /// A rename fails; the outputs not yet in place are removed.
    pub fn commit(mut self) -> Result<()> {
        let mut list = staged();
        let files = std::mem::take(&mut self.files);
        let mut result = Ok(());
        for (tmp, target) in &files {
            if result.is_ok() {
                result = std::fs::rename(tmp, target).map_err(|e| io_error(target, &e));
            }
            if result.is_err() {
                discard(&mut list, tmp);
            } else {
                list.retain(|p| p != tmp);
            }
        }
        result
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let mut list = staged();
        for (tmp, _) in &self.files {
            discard(&mut list, tmp);
        }
    }
}

/// Write `bytes` to `path` atomically (module docs).
///
/// # Errors
/// `path` is a folder, or its folder cannot be written.
pub fn write_atomic(path: &Path, bytes: &[u8]) -> Result<()> {
    let mut out = Staged::new();
    out.file(path, bytes)?;
    out.commit()
}

/// Write what `write` writes to `path` atomically (module docs).
///
/// # Errors
/// As [`write_atomic`], and `write`'s errors.
pub(crate) fn write_atomic_with(
    path: &Path,
    write: &mut dyn FnMut(&mut dyn std::io::Write) -> Result<()>,
) -> Result<()> {
    let mut out = Staged::new();
    out.file_with(path, write)?;
    out.commit()
}

/// Whether an existing output folder may be replaced.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
pub enum Replace {
    /// Only a folder samplab made (everything in it listed in its manifest).
    #[default]
    IfOurs,
    /// Any folder but the protected ones (the CLI's `--force`).
    Force,
}

/// The folders never used as an output folder: `/`, the home folder, the working folder
/// and every folder above it.
fn protected(target: &Path) -> Option<&'static str> {
    let canon = std::fs::canonicalize(target).ok()?;
    if canon.parent().is_none() {
        return Some("the root folder");
    }
    if let Some(home) = std::env::var_os("HOME").and_then(|h| std::fs::canonicalize(h).ok())
        && canon == home
    {
        return Some("the home folder");
    }
    if let Ok(cwd) = std::env::current_dir().and_then(std::fs::canonicalize)
        && cwd.starts_with(&canon)
    {
        return Some(if cwd == canon { "the working folder" } else { "a folder holding the working folder" });
    }
    None
}

/// The first entry of the folder `dir` (in [`entries`]' order) that its manifest does not
/// list, if any.
fn foreign_entry(dir: &Path) -> Result<Option<String>> {
    let listed: std::collections::HashSet<String> =
        std::fs::read_to_string(dir.join(MANIFEST)).map(|t| t.lines().map(str::to_owned).collect()).unwrap_or_default();
    Ok(entries(dir)?.into_iter().find(|e| e != MANIFEST && !listed.contains(e)))
}

/// Every entry under `dir`, relative, in sorted order (for its manifest).
fn entries(dir: &Path) -> Result<Vec<String>> {
    let mut out = Vec::new();
    let mut stack = vec![PathBuf::new()];
    while let Some(rel) = stack.pop() {
        let read = std::fs::read_dir(dir.join(&rel)).map_err(|e| io_error(&dir.join(&rel), &e))?;
        for entry in read.filter_map(|e| e.ok()) {
            let path = rel.join(entry.file_name());
            if entry.file_type().is_ok_and(|t| t.is_dir()) {
                stack.push(path.clone());
            }
            out.push(path.to_string_lossy().into_owned());
        }
    }
    out.sort();
    Ok(out)
}

/// Check that `out` may be written as a folder under `replace` (module docs).
///
/// # Errors
/// [`Error::Io`] saying why not, in one line.
pub fn check_folder(out: &Path, replace: Replace) -> Result<()> {
    refuse_dash(out, "folder")?;
    let refuse = |reason: String| Err(Error::Io { path: out.display().to_string(), reason });
    if let Some(what) = protected(out) {
        return refuse(format!("is {what}; samplab never writes its output there (name a new folder)"));
    }
    match existing(out) {
        Existing::Nothing => Ok(()),
        Existing::File | Existing::Special => {
            refuse("is a file; samplab does not replace a file by a folder (name a new folder)".into())
        }
        Existing::Folder if replace == Replace::Force => Ok(()),
        Existing::Folder => match foreign_entry(out)? {
            None => Ok(()),
            Some(name) => refuse(format!(
                "holds '{name}', which samplab did not write; name a new folder, or pass --force to replace it"
            )),
        },
    }
}

/// Write the folder `out`: `fill` fills a temporary sibling, which then replaces `out`
/// (module docs). On any error, or a stop, `out` is left as it was.
///
/// # Errors
/// [`check_folder`]'s refusals, `fill`'s errors, or the folder cannot be written.
pub fn write_folder<E: From<Error>>(
    out: &Path,
    replace: Replace,
    fill: impl FnOnce(&Path) -> std::result::Result<(), E>,
) -> std::result::Result<(), E> {
    check_folder(out, replace)?;
    let (parent, name) = split(out)?;
    std::fs::create_dir_all(&parent).map_err(|e| io_error(&parent, &e))?;
    let staging = parent.join(format!(".{name}.partial-{}", std::process::id()));
    register(&staging);
    let _ = std::fs::remove_dir_all(&staging);
    if let Err(e) = std::fs::create_dir(&staging) {
        discard(&mut staged(), &staging);
        return Err(io_error(&staging, &e).into());
    }
    let filled = fill(&staging).and_then(|()| {
        let mut manifest = entries(&staging)?.join("\n");
        manifest.push('\n');
        std::fs::write(staging.join(MANIFEST), manifest).map_err(|e| E::from(io_error(&staging, &e)))
    });
    if let Err(e) = filled {
        discard(&mut staged(), &staging);
        return Err(e);
    }
    // the old folder (if any) goes only once the new one is complete
    let mut list = staged();
    let old = parent.join(format!(".{name}.old-{}", std::process::id()));
    let result = (|| {
        check_folder(out, replace)?;
        if out.exists() {
            std::fs::rename(out, &old).map_err(|e| io_error(out, &e))?;
        }
        std::fs::rename(&staging, out).map_err(|e| io_error(out, &e))
    })();
    if result.is_err() {
        discard(&mut list, &staging);
    } else {
        list.retain(|p| p != &staging);
    }
    drop(list);
    let _ = std::fs::remove_dir_all(&old);
    Ok(result?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn temp(name: &str) -> PathBuf {
        let dir = std::env::temp_dir().join(format!("samplab-output-{}-{name}", std::process::id()));
        let _ = std::fs::remove_dir_all(&dir);
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    fn listing(dir: &Path) -> Vec<String> {
        let mut v: Vec<_> =
            std::fs::read_dir(dir).unwrap().map(|e| e.unwrap().file_name().to_string_lossy().into_owned()).collect();
        v.sort();
        v
    }

    fn fill(dir: &Path) -> Result<()> {
        std::fs::create_dir(dir.join("sub")).unwrap();
        std::fs::write(dir.join("sub/a.txt"), "a").unwrap();
        std::fs::write(dir.join("b.txt"), "b").unwrap();
        Ok(())
    }

    #[test]
    fn atomic_write_leaves_no_temporary() {
        let dir = temp("atomic");
        let path = dir.join("p.txt");
        write_atomic(&path, b"0.5 0.5\n").unwrap();
        assert_eq!(std::fs::read(&path).unwrap(), b"0.5 0.5\n");
        assert_eq!(listing(&dir), ["p.txt"]);
        assert!(write_atomic(&dir.join("missing/q.txt"), b"x").is_err());
        assert!(!staged().iter().any(|p| p.starts_with(&dir)), "a temporary path is still registered");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_folder_samplab_made_is_replaced_and_a_foreign_one_refused() {
        let dir = temp("folders");
        let out = dir.join("out");
        write_folder::<Error>(&out, Replace::IfOurs, fill).unwrap();
        assert_eq!(listing(&out), [MANIFEST, "b.txt", "sub"]);
        // ours: replaced
        write_folder::<Error>(&out, Replace::IfOurs, fill).unwrap();
        // a file the user put there: refused, the folder untouched
        std::fs::write(out.join("sub/precious.txt"), "mine").unwrap();
        let err = write_folder::<Error>(&out, Replace::IfOurs, fill).unwrap_err().to_string();
        assert!(err.contains("'sub/precious.txt'") && err.contains("--force"), "{err}");
        assert_eq!(std::fs::read(out.join("sub/precious.txt")).unwrap(), b"mine");
        // forced: replaced
        write_folder::<Error>(&out, Replace::Force, fill).unwrap();
        assert!(!out.join("sub/precious.txt").exists());
        // a file is never replaced by a folder
        let file = dir.join("file");
        std::fs::write(&file, "mine").unwrap();
        assert!(write_folder::<Error>(&file, Replace::Force, fill).is_err());
        assert_eq!(std::fs::read(&file).unwrap(), b"mine");
        assert_eq!(listing(&dir), ["file", "out"]);
        assert!(!staged().iter().any(|p| p.starts_with(&dir)), "a temporary path is still registered");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_root_and_home_folders_are_never_outputs() {
        for p in ["/", "/.", "/tmp/.."] {
            let err = check_folder(Path::new(p), Replace::Force).unwrap_err().to_string();
            assert!(err.contains("the root folder"), "{p}: {err}");
        }
        if let Some(home) = std::env::var_os("HOME").filter(|h| Path::new(h).is_dir() && Path::new(h) != Path::new("/"))
        {
            let err = check_folder(Path::new(&home), Replace::Force).unwrap_err().to_string();
            assert!(err.contains("the home folder"), "{err}");
        }
        let cwd = std::env::current_dir().unwrap();
        assert!(check_folder(&cwd, Replace::Force).unwrap_err().to_string().contains("the working folder"));
        assert!(check_folder(Path::new("."), Replace::Force).is_err());
        assert!(check_folder(Path::new(".."), Replace::Force).unwrap_err().to_string().contains("holding"));
    }

    #[cfg(unix)]
    #[test]
    fn a_fifo_is_written_through_not_replaced() {
        use std::os::unix::fs::FileTypeExt as _;
        let dir = temp("fifo");
        let fifo = dir.join("pipe");
        let c = std::ffi::CString::new(fifo.to_str().unwrap()).unwrap();
        // SAFETY: a valid NUL-terminated path.
        assert_eq!(unsafe { libc::mkfifo(c.as_ptr(), 0o600) }, 0);
        let reader = {
            let fifo = fifo.clone();
            std::thread::spawn(move || std::fs::read(fifo).unwrap())
        };
        write_atomic(&fifo, b"through").unwrap();
        assert_eq!(reader.join().unwrap(), b"through");
        assert!(std::fs::metadata(&fifo).unwrap().file_type().is_fifo());
        assert_eq!(listing(&dir), ["pipe"]);
        // a folder is not replaced by a file
        let sub = dir.join("sub");
        std::fs::create_dir(&sub).unwrap();
        assert!(write_atomic(&sub, b"x").unwrap_err().to_string().contains("is a folder"));
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn staged_outputs_appear_together_or_not_at_all() {
        let dir = temp("staged");
        let mut out = Staged::new();
        out.file(&dir.join("a.exr"), b"a").unwrap();
        assert!(out.file(&dir.join("missing/b.png"), b"b").is_err());
        drop(out);
        assert!(listing(&dir).is_empty());
        let mut out = Staged::new();
        out.file(&dir.join("a.exr"), b"a").unwrap();
        out.file(&dir.join("b.png"), b"b").unwrap();
        out.commit().unwrap();
        assert_eq!(listing(&dir), ["a.exr", "b.png"]);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
