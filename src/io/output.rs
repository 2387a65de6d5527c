//! Output files that are never half-written, never clobber what they should not, and never leave
//! temporary files behind.
//!
//! - `-` is stdout.
//! - A regular file (or a name that does not exist yet) is written to a temporary file beside it
//!   and renamed into place by [`Output::commit`]; dropped without a commit (an error, a full
//!   disk), the temporary file is removed.
//! - A symlink is followed: its target is replaced (a link to a regular file) or written in place.
//! - Anything else (a device such as /dev/null, a named pipe) is written in place, never
//!   replaced by a regular file.
//!
//! [`install_signal_cleanup`] removes the temporary files of outputs still being written when
//! the process gets SIGINT or SIGTERM.

use anyhow::Context;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporary files being written now.
static PENDING: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn pending() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    PENDING.lock().unwrap_or_else(|e| e.into_inner())
}

/// On SIGINT or SIGTERM: remove every temporary output file, then exit with 130. Call once, at
/// the start of a program that writes outputs.
#[cfg(feature = "cli")]
pub fn install_signal_cleanup() {
    let _ = ctrlc::set_handler(|| {
        for p in pending().iter() {
            let _ = std::fs::remove_file(p);
        }
        eprintln!("interrupted: no output file was written");
        std::process::exit(130);
    });
}

enum Sink {
    Stdout(BufWriter<std::io::Stdout>),
    InPlace(BufWriter<File>),
    Temp { file: BufWriter<File>, tmp: PathBuf },
}

/// One output being written; see the module documentation.
pub struct Output {
    sink: Option<Sink>,
    /// What the user named (for messages).
    name: PathBuf,
    /// Where a temporary file is renamed to (the symlink's target for a link).
    target: PathBuf,
}

/// The file a path finally names: symlinks followed, also dangling ones (their target will be
/// created).
fn resolve(path: &Path) -> PathBuf {
    let mut p = path.to_path_buf();
    for _ in 0..40 {
        match std::fs::symlink_metadata(&p) {
            Ok(m) if m.file_type().is_symlink() => match std::fs::read_link(&p) {
                Ok(t) if t.is_absolute() => p = t,
                Ok(t) => p = p.parent().unwrap_or(Path::new(".")).join(t),
                Err(_) => return p,
            },
            _ => return p,
        }
    }
    p
}

impl Output {
    /// Opens `path` for writing (`-` is stdout). Fails at once, before any work is done, if the
    /// place cannot be written.
    pub fn create(path: impl AsRef<Path>) -> anyhow::Result<Output> {
        let name = path.as_ref().to_path_buf();
        if name.as_os_str() == "-" {
            return Ok(Output {
                sink: Some(Sink::Stdout(BufWriter::with_capacity(
                    1 << 16,
                    std::io::stdout(),
                ))),
                target: name.clone(),
                name,
            });
        }
        let target = resolve(&name);
        let shown = name.display().to_string();
        match std::fs::metadata(&target) {
            Ok(m) if m.is_dir() => {
                anyhow::bail!("cannot write {shown}: it is a directory; give a file name")
            }
            Ok(m) if !m.is_file() => {
                // A device or a pipe: write into it, never replace it.
                let f = std::fs::OpenOptions::new()
                    .write(true)
                    .open(&target)
                    .with_context(|| format!("cannot write {shown}"))?;
                return Ok(Output {
                    sink: Some(Sink::InPlace(BufWriter::with_capacity(1 << 16, f))),
                    name,
                    target,
                });
            }
            _ => {}
        }
        let dir = target
            .parent()
            .filter(|p| !p.as_os_str().is_empty())
            .unwrap_or(Path::new("."));
        let file_name = target
            .file_name()
            .with_context(|| format!("cannot write {shown}: the path has no file name"))?;
        let prefix = format!(".{}.", file_name.to_string_lossy());
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp");
        // The mode of a file created in place (0666 less the umask), or the replaced file's:
        // tempfile's own 0600 would make every output private.
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            let mode = std::fs::metadata(&target).map_or(0o666, |m| m.permissions().mode());
            builder.permissions(std::fs::Permissions::from_mode(mode));
        }
        let tmp = builder.tempfile_in(dir).with_context(|| {
            format!(
                "cannot write {shown}: cannot create a file in {}",
                dir.display()
            )
        })?;
        // Keep the file, drop tempfile's own guard: removal is ours (on drop and on signals).
        let (file, tmp_path) = tmp
            .keep()
            .map_err(|e| e.error)
            .with_context(|| format!("cannot write {shown}"))?;
        pending().push(tmp_path.clone());
        Ok(Output {
            sink: Some(Sink::Temp {
                file: BufWriter::with_capacity(1 << 16, file),
                tmp: tmp_path,
            }),
            name,
            target,
        })
    }

    /// The name the user gave.
    pub fn name(&self) -> &Path {
        &self.name
    }

    /// Finishes the output: flushes it and, for a temporary file, renames it into place.
    pub fn commit(mut self) -> anyhow::Result<()> {
        let shown = self.name.display().to_string();
        match self.sink.take() {
            Some(Sink::Stdout(mut w)) => w.flush().context("cannot write to stdout")?,
            Some(Sink::InPlace(mut w)) => {
                w.flush().with_context(|| format!("cannot write {shown}"))?
            }
            Some(Sink::Temp { file, tmp }) => {
                let res = file
                    .into_inner()
                    .map_err(|e| e.into_error())
                    .and_then(|f| f.sync_all())
                    .with_context(|| format!("cannot write {shown}"))
                    .and_then(|_| {
                        std::fs::rename(&tmp, &self.target).with_context(|| {
                            format!("cannot move the output into place at {shown}")
                        })
                    });
                if res.is_err() {
                    let _ = std::fs::remove_file(&tmp);
                }
                pending().retain(|p| p != &tmp);
                res?;
            }
            None => {}
        }
        Ok(())
    }

    fn writer(&mut self) -> &mut dyn Write {
        match self.sink.as_mut().expect("output used after commit") {
            Sink::Stdout(w) => w,
            Sink::InPlace(w) => w,
            Sink::Temp { file, .. } => file,
        }
    }
}

impl Write for Output {
    fn write(&mut self, buf: &[u8]) -> std::io::Result<usize> {
        self.writer().write(buf)
    }
    fn write_all(&mut self, buf: &[u8]) -> std::io::Result<()> {
        self.writer().write_all(buf)
    }
    fn flush(&mut self) -> std::io::Result<()> {
        self.writer().flush()
    }
}

impl Drop for Output {
    fn drop(&mut self) {
        if let Some(Sink::Temp { tmp, .. }) = self.sink.take() {
            let _ = std::fs::remove_file(&tmp);
            pending().retain(|p| p != &tmp);
        }
    }
}

/// Writes `bytes` to `path` (`-` is stdout) as one output.
pub fn write_output(path: impl AsRef<Path>, bytes: &[u8]) -> anyhow::Result<()> {
    let mut o = Output::create(path)?;
    let shown = o.name().display().to_string();
    o.write_all(bytes)
        .with_context(|| format!("cannot write {shown}"))?;
    o.commit()
}

/// What identifies the file a path will write: stdout for `-`; otherwise the absolute path with
/// every symlink followed (also a dangling one at the end, whose target [`Output::create`]
/// makes) and `.` and `..` taken out, without requiring the file or its folder to exist.
pub fn output_identity(path: &Path) -> PathBuf {
    if path.as_os_str() == "-" {
        return PathBuf::from("-");
    }
    let p = resolve(path);
    let p = if p.is_absolute() {
        p
    } else {
        std::env::current_dir().unwrap_or_default().join(p)
    };
    // Component by component: what exists is canonicalized (its symlinks followed, so `..`
    // after a link goes where the OS goes); what does not is appended as written.
    let mut cur = PathBuf::new();
    for c in p.components() {
        match c {
            std::path::Component::CurDir => {}
            std::path::Component::ParentDir => {
                cur.pop();
            }
            std::path::Component::Normal(n) => {
                cur.push(n);
                if let Ok(real) = std::fs::canonicalize(&cur) {
                    cur = real;
                }
            }
            other => cur.push(other.as_os_str()),
        }
    }
    // A last symlink whose target does not exist yet.
    resolve(&cur)
}

/// Refuses two outputs of one command that would write the same file (the second would
/// silently replace the first): `outputs` are (what names the output, its path), every file a
/// command will write, `-` for stdout (which may appear once). Call it before any work.
/// `/dev/null` may be named any number of times.
pub fn check_distinct<N, P>(outputs: impl IntoIterator<Item = (N, P)>) -> anyhow::Result<()>
where
    N: std::fmt::Display,
    P: AsRef<Path>,
{
    let mut seen: Vec<(String, PathBuf, PathBuf)> = Vec::new();
    for (name, path) in outputs {
        let path = path.as_ref();
        let id = output_identity(path);
        if id == Path::new("/dev/null") {
            continue;
        }
        if let Some((first, first_path, _)) = seen.iter().find(|(_, _, i)| *i == id) {
            let what = if id == Path::new("-") {
                "stdout".to_string()
            } else {
                id.display().to_string()
            };
            anyhow::bail!(
                "{first} {} and {name} {} are the same file ({what}): the second would overwrite the first; give each output its own file",
                first_path.display(),
                path.display()
            );
        }
        seen.push((name.to_string(), path.to_path_buf(), id));
    }
    Ok(())
}

/// Whether descriptor 1 was closed when the process started, read before the Rust runtime
/// puts /dev/null there (it does so in `main`'s set-up; `.init_array` functions run earlier).
#[cfg(target_os = "linux")]
static STDOUT_CLOSED_AT_START: std::sync::atomic::AtomicBool =
    std::sync::atomic::AtomicBool::new(false);

#[cfg(target_os = "linux")]
#[used]
#[link_section = ".init_array"]
static LOOK_AT_STDOUT: extern "C" fn() = {
    extern "C" fn look() {
        extern "C" {
            fn fcntl(fd: i32, cmd: i32, ...) -> i32;
        }
        const F_GETFD: i32 = 1;
        // SAFETY: F_GETFD reads a descriptor's flags and changes nothing.
        if unsafe { fcntl(1, F_GETFD) } == -1 {
            STDOUT_CLOSED_AT_START.store(true, std::sync::atomic::Ordering::Relaxed);
        }
    }
    look
};

/// True if the process was started with stdout closed (`tabor ... >&-`): every result written
/// there would be lost with exit status 0. The descriptor is looked at before the Rust runtime
/// puts /dev/null on it, so a /dev/null the caller gave (`> /dev/null`, or read-write as
/// Python's `subprocess.DEVNULL`) is not mistaken for it. Linux only (elsewhere false).
pub fn stdout_was_closed() -> bool {
    #[cfg(target_os = "linux")]
    {
        STDOUT_CLOSED_AT_START.load(std::sync::atomic::Ordering::Relaxed)
    }
    #[cfg(not(target_os = "linux"))]
    false
}

/// True if the error comes from writing into a closed pipe (`tabor ... | head`): the reader has
/// what it wanted, and the command ends quietly.
pub fn is_broken_pipe(e: &anyhow::Error) -> bool {
    e.chain().any(|c| {
        c.downcast_ref::<std::io::Error>()
            .is_some_and(|e| e.kind() == std::io::ErrorKind::BrokenPipe)
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn regular_files_are_replaced_whole_and_failures_leave_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("a.txt");
        std::fs::write(&p, "old").unwrap();
        let mut o = Output::create(&p).unwrap();
        o.write_all(b"new").unwrap();
        // Not yet committed: the old content is still there.
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "old");
        o.commit().unwrap();
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new");
        // Dropped without commit: the target is untouched, the temporary file gone.
        let mut o = Output::create(&p).unwrap();
        o.write_all(b"partial").unwrap();
        drop(o);
        assert_eq!(std::fs::read_to_string(&p).unwrap(), "new");
        let names: Vec<_> = std::fs::read_dir(dir.path()).unwrap().collect();
        assert_eq!(names.len(), 1, "temporary files left: {names:?}");
        // Only this test's files: the other tests of this module write in parallel.
        assert!(!pending().iter().any(|q| q.starts_with(dir.path())));
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            // New files get the usual mode (not tempfile's private 0600), replaced ones keep theirs.
            let fresh = dir.path().join("fresh.txt");
            write_output(&fresh, b"x").unwrap();
            let mode = std::fs::metadata(&fresh).unwrap().permissions().mode() & 0o777;
            assert_ne!(mode, 0o600, "{mode:o}");
            std::fs::set_permissions(&p, std::fs::Permissions::from_mode(0o640)).unwrap();
            write_output(&p, b"again").unwrap();
            let mode = std::fs::metadata(&p).unwrap().permissions().mode() & 0o777;
            assert_eq!(mode, 0o640);
        }
    }

    #[cfg(unix)]
    #[test]
    fn symlinks_are_followed_and_devices_written_in_place() {
        let dir = tempfile::tempdir().unwrap();
        let real = dir.path().join("real.txt");
        std::fs::write(&real, "old").unwrap();
        let link = dir.path().join("link.txt");
        std::os::unix::fs::symlink(&real, &link).unwrap();
        write_output(&link, b"via link").unwrap();
        assert!(std::fs::symlink_metadata(&link)
            .unwrap()
            .file_type()
            .is_symlink());
        assert_eq!(std::fs::read_to_string(&real).unwrap(), "via link");
        write_output("/dev/null", b"nothing").unwrap();
        let m = std::fs::metadata("/dev/null").unwrap();
        assert!(!m.is_file(), "/dev/null was replaced by a regular file");
        let e = write_output(dir.path(), b"x").unwrap_err().to_string();
        assert!(e.contains("is a directory"), "{e}");
    }
}
