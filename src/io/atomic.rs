//! Output files appear whole or not at all: every writer writes a temporary file beside the
//! target and renames it at the end.

use crate::io::IoError;
use std::fs::File;
use std::io::{BufWriter, Write};
use std::path::{Path, PathBuf};

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
    for (t, path) in temps.into_iter().zip(paths) {
        t.persist(path).map_err(|e| werr(path, e.error))?;
    }
    Ok(())
}

/// Shorthand for turning a `std::io::Error` while writing `path` into an [`IoError`].
pub fn write_err(path: &Path) -> impl Fn(std::io::Error) -> IoError + '_ {
    move |source| IoError::Write { path: path.to_path_buf(), source }
}

#[cfg(test)]
mod tests {
    use super::*;

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
