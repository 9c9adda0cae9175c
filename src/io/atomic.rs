//! Output files appear whole or not at all: every writer writes a temporary file beside the
//! target and renames it at the end.

use crate::io::IoError;
use std::cell::RefCell;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};
use tempfile::NamedTempFile;

/// Files written whole to temporaries (flushed and synced) and not yet renamed onto their
/// paths: [`Pending::commit`] renames them; dropping a `Pending` removes them, leaving the
/// paths as they were.
#[must_use = "dropping it removes the files written"]
#[derive(Debug, Default)]
pub struct Pending {
    files: Vec<(NamedTempFile, PathBuf)>,
}

impl Pending {
    /// Renames the temporary files onto their paths.
    ///
    /// # Errors
    /// [`IoError::Write`] where a rename fails (the files not yet renamed are removed).
    pub fn commit(self) -> Result<(), IoError> {
        for (t, path) in self.files {
            t.persist(&path).map_err(|e| IoError::Write { path: path.clone(), source: e.error })?;
        }
        Ok(())
    }
}

thread_local! {
    /// Where [`write_atomic_many`] leaves its temporaries inside [`deferred`] on this thread.
    static DEFERRED: RefCell<Option<Vec<(NamedTempFile, PathBuf)>>> = const { RefCell::new(None) };
}

/// Runs `write` (any writer of [`crate::io`]) with the renames held back: its files are
/// written whole to temporaries and the returned [`Pending`] renames them, so a caller can
/// write while it decides whether the output may stand. The writers' renames happen on the
/// thread that calls them, which is this one: `write` must not hand whole writes to other
/// threads, and this thread must not write other files meanwhile (a rayon job it steals
/// while `write` waits would be deferred too; the pipeline runs beside it only jobs that
/// write nothing).
///
/// # Errors
/// The error of `write`; the temporaries written before it are removed.
pub fn deferred<E>(write: impl FnOnce() -> Result<(), E>) -> Result<Pending, E> {
    let outer = DEFERRED.with(|d| d.replace(Some(Vec::new())));
    let result = write();
    let files = DEFERRED.with(|d| d.replace(outer)).unwrap_or_default();
    result.map(|()| Pending { files })
}

/// Writes `path` through a temporary file in the same directory, renamed on success.
/// On any error the temporary file is removed and `path` is left as it was.
///
/// # Errors
/// [`IoError::Write`] for failures of the file system; errors of `body` pass through.
pub fn write_atomic<F>(path: &Path, body: F) -> Result<(), IoError>
where
    F: FnOnce(&mut BufWriter<File>) -> Result<(), IoError>,
{
    write_atomic_many(&[path.to_path_buf()], |writers| body(&mut writers[0]))
}

/// Writes several files (e.g. TetGen's `.node`, `.ele`, `.face`) through temporary files that
/// are all renamed only after every one has been written.
///
/// # Errors
/// As [`write_atomic`].
pub fn write_atomic_many<F>(paths: &[PathBuf], body: F) -> Result<(), IoError>
where
    F: FnOnce(&mut [BufWriter<File>]) -> Result<(), IoError>,
{
    let werr = |path: &Path, source: std::io::Error| IoError::Write { path: path.to_path_buf(), source };
    let mut temps = Vec::with_capacity(paths.len());
    for path in paths {
        let dir = match path.parent() {
            Some(d) if !d.as_os_str().is_empty() => d.to_path_buf(),
            _ => PathBuf::from("."),
        };
        let name = path.file_name().map(|n| n.to_string_lossy().into_owned()).unwrap_or_default();
        let prefix = format!(".{name}.");
        let mut builder = tempfile::Builder::new();
        builder.prefix(&prefix).suffix(".tmp");
        // a temporary file is private (0600); the output is an ordinary file, readable as
        // the user's umask says (0666 & !umask), as a plain `File::create` would make it
        #[cfg(unix)]
        {
            use std::os::unix::fs::PermissionsExt;
            builder.permissions(std::fs::Permissions::from_mode(0o666));
        }
        let tmp = builder.tempfile_in(&dir).map_err(|e| werr(path, e))?;
        temps.push(tmp);
    }
    let mut writers = Vec::with_capacity(temps.len());
    for (t, path) in temps.iter().zip(paths) {
        writers.push(BufWriter::with_capacity(1 << 20, t.reopen().map_err(|e| werr(path, e))?));
    }
    body(&mut writers)?;
    for (w, path) in writers.iter_mut().zip(paths) {
        w.flush().map_err(|e| werr(path, e))?;
        w.get_ref().sync_data().ok();
    }
    drop(writers);
    let pending = Pending { files: temps.into_iter().zip(paths.iter().cloned()).collect() };
    // inside `deferred`: the renames wait for its caller
    let pending = DEFERRED.with(|d| match d.borrow_mut().as_mut() {
        Some(held) => {
            held.extend(pending.files);
            None
        }
        None => Some(pending),
    });
    pending.map_or(Ok(()), Pending::commit)
}

/// Shorthand for turning a `std::io::Error` while writing `path` into an [`IoError`].
pub fn write_err(path: &Path) -> impl Fn(std::io::Error) -> IoError + '_ {
    move |source| IoError::Write { path: path.to_path_buf(), source }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn deferred_writes_appear_on_commit_and_vanish_on_drop() -> Result<(), Box<dyn std::error::Error>> {
        let dir = tempfile::tempdir()?;
        let (a, b) = (dir.path().join("a.txt"), dir.path().join("b.txt"));
        std::fs::write(&b, "old")?;
        let names = || -> std::io::Result<Vec<String>> {
            let mut v = Vec::new();
            for e in std::fs::read_dir(dir.path())? {
                v.push(e?.file_name().to_string_lossy().into_owned());
            }
            v.sort();
            Ok(v)
        };
        let read = |p: &Path| std::fs::read_to_string(p);
        // written whole to temporaries; nothing renamed yet
        let pending = deferred(|| -> Result<(), IoError> {
            write_atomic(&a, |w| w.write_all(b"one").map_err(write_err(&a)))?;
            write_atomic(&b, |w| w.write_all(b"two").map_err(write_err(&b)))
        })?;
        assert!(!a.exists());
        assert_eq!(read(&b)?, "old");
        assert_eq!(names()?.len(), 3, "{:?}", names()?);
        pending.commit()?;
        assert_eq!((read(&a)?, read(&b)?), ("one".into(), "two".into()));
        assert_eq!(names()?, ["a.txt", "b.txt"]);
        // dropped: the paths stay as they were, no temporary is left
        drop(deferred(|| write_atomic(&a, |w| w.write_all(b"three").map_err(write_err(&a))))?);
        assert_eq!(read(&a)?, "one");
        assert_eq!(names()?, ["a.txt", "b.txt"]);
        // an error inside: the earlier temporaries are removed too
        let r = deferred(|| -> Result<(), IoError> {
            write_atomic(&a, |w| w.write_all(b"four").map_err(write_err(&a)))?;
            write_atomic(&b, |_| Err(IoError::Write { path: b.clone(), source: std::io::Error::other("no") }))
        });
        assert!(r.is_err());
        assert_eq!(names()?, ["a.txt", "b.txt"]);
        assert_eq!(read(&a)?, "one");
        // outside `deferred` a write renames at once again
        write_atomic(&a, |w| w.write_all(b"five").map_err(write_err(&a)))?;
        assert_eq!(read(&a)?, "five");
        Ok(())
    }

    #[cfg(unix)]
    #[test]
    fn output_is_readable_like_a_created_file() {
        use std::os::unix::fs::PermissionsExt;
        let dir = tempfile::tempdir().unwrap();
        let (ours, plain) = (dir.path().join("a.stl"), dir.path().join("b.stl"));
        write_atomic(&ours, |w| w.write_all(b"x").map_err(write_err(&ours))).unwrap();
        std::fs::write(&plain, b"x").unwrap();
        let mode = |p: &Path| std::fs::metadata(p).unwrap().permissions().mode() & 0o777;
        assert_eq!(mode(&ours), mode(&plain));
    }

    #[test]
    fn failed_body_leaves_nothing() {
        let dir = tempfile::tempdir().unwrap();
        let p = dir.path().join("out.stl");
        let r = write_atomic(&p, |w| {
            w.write_all(b"partial").map_err(write_err(&p))?;
            Err(IoError::in_file(&p, "boom"))
        });
        assert!(r.is_err());
        assert!(!p.exists());
        assert_eq!(std::fs::read_dir(dir.path()).unwrap().count(), 0, "temporary file left behind");
        write_atomic(&p, |w| w.write_all(b"whole").map_err(write_err(&p))).unwrap();
        assert_eq!(std::fs::read(&p).unwrap(), b"whole");
    }
}
