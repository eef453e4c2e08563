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
//! - Every temporary is created exclusively (never through a link or over something that
//!   exists) under a name no other user can predict, beside the resolved target: an output
//!   folder others can write (a shared scratch or cache folder) cannot redirect a write.
//! - A target is resolved before anything is renamed (its folder's links and `..`, and the
//!   target itself when it is a link), so every spelling of a path names one place; a
//!   command refuses an output that is one of its inputs, holds one, or is named twice
//!   ([`refuse_overlap`]).
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

/// A token no other process can predict: SipHash under the process's random keys of a
/// counter and the clock, for temporary names.
fn token() -> String {
    use std::hash::{BuildHasher as _, Hasher as _};
    static COUNT: std::sync::atomic::AtomicU64 = std::sync::atomic::AtomicU64::new(0);
    let mut h = std::collections::hash_map::RandomState::new().build_hasher();
    h.write_u64(COUNT.fetch_add(1, std::sync::atomic::Ordering::Relaxed));
    h.write_u32(std::process::id());
    h.write_u128(std::time::SystemTime::now().duration_since(std::time::UNIX_EPOCH).map_or(0, |d| d.as_nanos()));
    format!("{:016x}", h.finish())
}

/// How a temporary is opened: created, never over an existing entry or through a link.
fn exclusive() -> std::fs::OpenOptions {
    let mut options = std::fs::OpenOptions::new();
    options.write(true).create_new(true);
    #[cfg(unix)]
    {
        use std::os::unix::fs::OpenOptionsExt as _;
        options.custom_flags(libc::O_NOFOLLOW);
    }
    options
}

/// A new file `.{name}.{token}.tmp` in `dir`, created exclusively (never through a link,
/// never over an existing entry), registered while it exists.
///
/// # Errors
/// The file cannot be created (`about` names the path in the error).
fn temporary_file(dir: &Path, name: &str, about: &Path) -> Result<(PathBuf, std::fs::File)> {
    let options = exclusive();
    let mut tries = 0;
    loop {
        let tmp = dir.join(format!(".{name}.{}.tmp", token()));
        match options.open(&tmp) {
            Ok(f) => {
                register(&tmp);
                return Ok((tmp, f));
            }
            // a name taken by chance (or planted): another name
            Err(e) if e.kind() == std::io::ErrorKind::AlreadyExists && tries < 8 => tries += 1,
            Err(e) => return Err(io_error(about, &e)),
        }
    }
}

/// Where a write to `path` lands: its folder resolved (links and `..`), so that every
/// spelling of one place gives one path. A link at `path` itself is refused (replacing it
/// would destroy a link samplab did not make, and following it would let whoever planted
/// it choose the file written), but for a link to a device or a FIFO, written through.
///
/// # Errors
/// The folder does not exist, `path` names no file (`..`, `/`), or it is a link.
pub fn resolve(path: &Path) -> Result<PathBuf> {
    if std::fs::symlink_metadata(path).is_ok_and(|m| m.file_type().is_symlink())
        && !matches!(existing(path), Existing::Special)
    {
        return Err(Error::Io {
            path: path.display().to_string(),
            reason: "is a link; samplab neither replaces nor writes through it (name the file or folder itself)".into(),
        });
    }
    let (dir, name) = split(path)?;
    let dir = std::fs::canonicalize(&dir).map_err(|e| io_error(path, &e))?;
    Ok(dir.join(name))
}

/// Refuse `path` as an output file before any work: `-`, a folder, a link to a file, a
/// missing or unwritable folder (a device or a FIFO is written through).
///
/// # Errors
/// [`Error::Io`] saying why, in one line.
pub fn check_file(path: &Path) -> Result<()> {
    refuse_dash(path, "file")?;
    match existing(path) {
        Existing::Special => return Ok(()),
        Existing::Folder => {
            return Err(Error::Io {
                path: path.display().to_string(),
                reason: "is a folder; samplab does not replace a folder by a file".into(),
            });
        }
        Existing::Nothing | Existing::File => {}
    }
    let target = resolve(path)?;
    writable(target.parent().unwrap_or(Path::new("/")), path)
}

/// Refuse a folder `dir` (or, when it does not exist yet, the nearest folder above it) in
/// which no entry can be made, naming `about`.
fn writable(dir: &Path, about: &Path) -> Result<()> {
    #[cfg(unix)]
    {
        let mut at = dir;
        while !at.exists() {
            match at.parent() {
                Some(p) if !p.as_os_str().is_empty() => at = p,
                _ => return Ok(()),
            }
        }
        let Ok(c) = std::ffi::CString::new(at.as_os_str().as_encoded_bytes()) else { return Ok(()) };
        // SAFETY: access(2) on a NUL-terminated path.
        if !at.is_dir() || unsafe { libc::access(c.as_ptr(), libc::W_OK | libc::X_OK) } != 0 {
            return Err(Error::Io {
                path: about.display().to_string(),
                reason: format!("cannot be written: {} is not a folder samplab may write in", at.display()),
            });
        }
    }
    Ok(())
}

/// Replace the entry `path` (whatever non-folder is there: a file, a link, a FIFO, never
/// followed or opened) by `bytes`, through an exclusively created temporary beside it: for
/// files in a folder others may write, such as a shared cache.
///
/// # Errors
/// The temporary cannot be written or renamed.
pub(crate) fn replace_entry(path: &Path, bytes: &[u8]) -> Result<()> {
    use std::io::Write as _;
    let (dir, name) = split(path)?;
    let (tmp, mut f) = temporary_file(&dir, &name, path)?;
    let result = f
        .write_all(bytes)
        .and_then(|()| f.sync_all())
        .and_then(|()| std::fs::rename(&tmp, path))
        .map_err(|e| io_error(path, &e));
    if result.is_err() {
        discard(&mut staged(), &tmp);
    } else {
        staged().retain(|p| p != &tmp);
    }
    result
}

/// What a command reads or writes, for [`refuse_overlap`].
#[derive(Debug, Clone, Copy)]
#[non_exhaustive]
pub enum Role<'a> {
    /// A file or folder the command reads (its name, e.g. `--reference`, for the message).
    Input(&'a str, &'a Path),
    /// A file the command writes.
    File(&'a str, &'a Path),
    /// A folder the command writes (replaced whole).
    Folder(&'a str, &'a Path),
}

/// Refuse a command whose outputs overlap: an output that is one of its inputs, a folder
/// output holding an input or another output, or one place named by two outputs, whatever
/// the spelling (`a/../a`, `./a`, a link, an absolute path).
///
/// # Errors
/// [`Error::Invalid`] naming both.
pub fn refuse_overlap(roles: &[Role<'_>]) -> Result<()> {
    // where each path lands; a path that cannot be resolved is left to its own command
    let place = |p: &Path| -> Option<PathBuf> {
        std::fs::canonicalize(p).ok().or_else(|| {
            let (dir, name) = split(p).ok()?;
            Some(std::fs::canonicalize(dir).ok()?.join(name))
        })
    };
    let places: Vec<(Role<'_>, Option<PathBuf>)> = roles
        .iter()
        .map(|r| match *r {
            Role::Input(_, p) | Role::File(_, p) | Role::Folder(_, p) => (*r, place(p)),
        })
        .collect();
    let name = |r: &Role<'_>| match *r {
        Role::Input(n, p) | Role::File(n, p) | Role::Folder(n, p) => format!("{n} {}", p.display()),
    };
    for (i, (a, pa)) in places.iter().enumerate() {
        let Some(pa) = pa else { continue };
        for (b, pb) in places.iter().skip(i + 1) {
            let Some(pb) = pb else { continue };
            let (inside_a, inside_b) = (pb.starts_with(pa), pa.starts_with(pb));
            let clash = match (a, b) {
                (Role::Input(..), Role::Input(..)) => false,
                (Role::Folder(..), _) => inside_a,
                (_, Role::Folder(..)) => inside_b,
                _ => pa == pb,
            };
            if clash {
                let how = if pa == pb { "name the same place" } else { "overlap (one holds the other)" };
                return Err(Error::Invalid(format!(
                    "{} and {} {how}; samplab never writes over its own inputs or one output over another",
                    name(a),
                    name(b)
                )));
            }
        }
    }
    Ok(())
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
        let target = resolve(path)?;
        let (dir, name) = split(&target)?;
        let (tmp, f) = temporary_file(&dir, &name, path)?;
        let mut w = std::io::BufWriter::new(f);
        let result = write(&mut w).and_then(|()| {
            let f = w.into_inner().map_err(|e| io_error(path, e.error()))?;
            f.sync_all().map_err(|e| io_error(path, &e))
        });
        if let Err(e) = result {
            discard(&mut staged(), &tmp);
            return Err(e);
        }
        self.files.push((tmp, target));
        Ok(())
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
#[non_exhaustive]
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
    // a manifest is a small regular file; anything else there (a FIFO, a device, a link, a
    // huge file) is itself an entry samplab did not write
    let manifest = dir.join(MANIFEST);
    let small_file = std::fs::symlink_metadata(&manifest).is_ok_and(|m| m.is_file() && m.len() <= 1 << 24);
    let listed: std::collections::HashSet<String> = if small_file {
        std::fs::read_to_string(&manifest).map(|t| t.lines().map(str::to_owned).collect()).unwrap_or_default()
    } else {
        std::collections::HashSet::new()
    };
    Ok(entries(dir)?.into_iter().find(|e| (e != MANIFEST || !small_file) && !listed.contains(e)))
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
/// [`Error::Io`] saying why not, in one line, or [`Error::ForeignEntry`].
pub fn check_folder(out: &Path, replace: Replace) -> Result<()> {
    refuse_dash(out, "folder")?;
    let refuse = |reason: String| Err(Error::Io { path: out.display().to_string(), reason });
    if let Some(what) = protected(out) {
        return refuse(format!("is {what}; samplab never writes its output there (name a new folder)"));
    }
    let (parent, _) = split(out)?;
    writable(&parent, out)?;
    match existing(out) {
        Existing::Nothing => Ok(()),
        Existing::File | Existing::Special => {
            refuse("is a file; samplab does not replace a file by a folder (name a new folder)".into())
        }
        Existing::Folder if replace == Replace::Force => Ok(()),
        Existing::Folder => match foreign_entry(out)? {
            None => Ok(()),
            Some(entry) => Err(Error::ForeignEntry { folder: out.display().to_string(), entry }),
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
    let (parent, _) = split(out)?;
    std::fs::create_dir_all(&parent).map_err(|e| io_error(&parent, &e))?;
    // every spelling of the target (`a/../a`, a link to it) is one place from here on
    let target = resolve(out)?;
    let (parent, name) = split(&target)?;
    let staging = parent.join(format!(".{name}.partial-{}", token()));
    // created exclusively: a planted entry or link at the name is an error, never followed
    std::fs::create_dir(&staging).map_err(|e| io_error(&staging, &e))?;
    register(&staging);
    let filled = fill(&staging).and_then(|()| {
        let mut manifest = entries(&staging)?.join("\n");
        manifest.push('\n');
        std::fs::write(staging.join(MANIFEST), manifest).map_err(|e| E::from(io_error(&staging, &e)))
    });
    if let Err(e) = filled {
        discard(&mut staged(), &staging);
        return Err(e);
    }
    // the old folder (if any) goes only once the new one is in its place
    let mut list = staged();
    let result = (|| {
        check_folder(&target, replace)?;
        let old = match std::fs::symlink_metadata(&target) {
            Ok(_) => {
                let old = parent.join(format!(".{name}.old-{}", token()));
                std::fs::rename(&target, &old).map_err(|e| io_error(out, &e))?;
                Some(old)
            }
            Err(_) => None,
        };
        match std::fs::rename(&staging, &target) {
            Ok(()) => Ok(old),
            Err(e) => {
                let mut reason = e.to_string();
                if let Some(old) = &old
                    && std::fs::rename(old, &target).is_err()
                {
                    reason = format!("{reason}; the old folder is kept as {}", old.display());
                }
                Err(Error::Io { path: out.display().to_string(), reason })
            }
        }
    })();
    if result.is_err() {
        discard(&mut list, &staging);
    } else {
        list.retain(|p| p != &staging);
    }
    drop(list);
    if let Some(old) = result? {
        let _ = std::fs::remove_dir_all(&old);
    }
    Ok(())
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
        let err = write_folder::<Error>(&out, Replace::IfOurs, fill).unwrap_err();
        assert!(matches!(&err, Error::ForeignEntry { entry, .. } if entry == "sub/precious.txt"), "{err}");
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

    #[cfg(unix)]
    #[test]
    fn temporaries_are_unpredictable_and_never_opened_through_a_link() {
        let dir = temp("exclusive");
        let victim = dir.join("victim");
        std::fs::write(&victim, "precious").unwrap();
        // a link or a file at the name: refused, the target untouched
        std::os::unix::fs::symlink(&victim, dir.join("link")).unwrap();
        assert!(exclusive().open(dir.join("link")).is_err());
        assert!(exclusive().open(&victim).is_err());
        assert_eq!(std::fs::read(&victim).unwrap(), b"precious");
        // names: distinct, without the process id
        let names: std::collections::HashSet<String> = (0..64)
            .map(|_| {
                let (tmp, _) = temporary_file(&dir, "p.txt", &dir).unwrap();
                discard(&mut staged(), &tmp);
                tmp.file_name().unwrap().to_string_lossy().into_owned()
            })
            .collect();
        assert_eq!(names.len(), 64);
        let pid = format!(".{}.", std::process::id());
        assert!(names.iter().all(|n| n.starts_with(".p.txt.") && !n.contains(&pid)), "{names:?}");
        assert_eq!(listing(&dir), ["link", "victim"]);
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
