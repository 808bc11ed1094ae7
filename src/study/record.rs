//! A run's record file, as `map` and `basins` keep theirs: a header line,
//! one line per result appended as results come, read back on resume (a
//! partial last line, left by a killed run, is dropped), and rewritten
//! atomically in canonical order at the end. The formats of the header and
//! the records are the callers'; this module holds what the two share.

use std::fs::{self, File, OpenOptions};
use std::io::{self, Write};
use std::path::{Path, PathBuf};

/// The complete lines of a record file's contents.
#[derive(Debug, PartialEq)]
pub(crate) struct CompleteLines<'a> {
    /// Every complete line, with its newline, in order (the header first).
    pub lines: Vec<&'a str>,
    /// The length in bytes of the complete lines (where appending resumes).
    pub valid_len: u64,
    /// Whether a partial last line was dropped.
    pub dropped_partial: bool,
}

/// The complete lines of `bytes`; a partial last line may end inside a
/// character, so only complete lines must be UTF-8. `Err(line)`: the
/// 1-based line that is not UTF-8.
pub(crate) fn complete_lines(bytes: &[u8]) -> Result<CompleteLines<'_>, usize> {
    let (complete, dropped_partial) = match bytes.iter().rposition(|&b| b == b'\n') {
        Some(end) => (&bytes[..=end], end + 1 < bytes.len()),
        None => (&bytes[..0], !bytes.is_empty()),
    };
    let text = std::str::from_utf8(complete).map_err(|e| {
        1 + complete[..e.valid_up_to()]
            .iter()
            .filter(|&&b| b == b'\n')
            .count()
    })?;
    Ok(CompleteLines {
        lines: text.split_inclusive('\n').collect(),
        valid_len: complete.len() as u64,
        dropped_partial,
    })
}

/// Write `text` to `out` atomically: a temporary file beside it (named
/// after it, or after `fallback` when `out` has no file name), synced, then
/// renamed over it. On error, the path that failed.
pub(crate) fn write_atomic(
    out: &Path,
    fallback: &str,
    text: &str,
) -> Result<(), (PathBuf, io::Error)> {
    let name = out
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .unwrap_or_else(|| fallback.to_string());
    let tmp = out.with_file_name(format!(".{name}.tmp"));
    let at = |p: &Path| {
        let p = p.to_path_buf();
        move |e| (p, e)
    };
    let mut f = File::create(&tmp).map_err(at(&tmp))?;
    f.write_all(text.as_bytes()).map_err(at(&tmp))?;
    f.sync_all().map_err(at(&tmp))?;
    drop(f);
    fs::rename(&tmp, out).map_err(at(out))
}

/// Reopen the record file `out` of a resumed run for appending, cut back to
/// its `valid_len` bytes of complete lines (a line cut short by a kill is
/// dropped before anything is appended after it).
pub(crate) fn reopen(out: &Path, valid_len: u64) -> io::Result<File> {
    OpenOptions::new()
        .write(true)
        .open(out)?
        .set_len(valid_len)?;
    OpenOptions::new().append(true).open(out)
}

/// A record file at `out` holding only `header`: a new file (`fresh`: never
/// an existing one), or the file of a run killed before even its header
/// was complete, started afresh.
pub(crate) fn start(out: &Path, header: &str, fresh: bool) -> io::Result<File> {
    let mut f = if fresh {
        OpenOptions::new().append(true).create_new(true).open(out)?
    } else {
        File::create(out)?
    };
    f.write_all(header.as_bytes())?;
    Ok(f)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_partial_last_line_is_dropped_and_counted() {
        let c = complete_lines(b"# h\n1,a\n2,b").unwrap();
        assert_eq!(c.lines, vec!["# h\n", "1,a\n"]);
        assert_eq!(c.valid_len, 8);
        assert!(c.dropped_partial);
        let c = complete_lines(b"# h\n1,a\n").unwrap();
        assert!(!c.dropped_partial);
        assert_eq!(c.valid_len, 8);
        let c = complete_lines(b"# h").unwrap();
        assert!(c.lines.is_empty() && c.dropped_partial && c.valid_len == 0);
    }

    #[test]
    fn only_complete_lines_must_be_text() {
        // A partial last line cut inside a character is dropped, not an error.
        assert!(complete_lines(b"# h\n1,\xc3").is_ok());
        assert_eq!(complete_lines(b"# h\n1,\xff\n2\n"), Err(2));
    }

    #[test]
    fn writes_atomically_and_replaces() {
        let dir = std::env::temp_dir().join(format!("record_{}", std::process::id()));
        fs::create_dir_all(&dir).unwrap();
        let out = dir.join("r.csv");
        write_atomic(&out, "r", "one\n").unwrap();
        write_atomic(&out, "r", "two\n").unwrap();
        assert_eq!(fs::read_to_string(&out).unwrap(), "two\n");
        assert!(!dir.join(".r.csv.tmp").exists());
        let missing = dir.join("no/such/dir/r.csv");
        let (path, _) = write_atomic(&missing, "r", "x").unwrap_err();
        assert_eq!(path, dir.join("no/such/dir/.r.csv.tmp"));
        fs::remove_dir_all(&dir).ok();
    }
}
