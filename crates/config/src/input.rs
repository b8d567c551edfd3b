//! Files a pipeline names (`friction.grid.file`, `fault.grid.file`, `set.target_csv`): where they
//! are looked for and how they are read.
//!
//! A path in a pipeline file is relative to the pipeline file's folder and stays inside it: an
//! absolute path or one that climbs out with `..` is refused, so a pipeline file (one shared by
//! someone else, say) reads only files that travel with it, and its output folder can keep a copy
//! of each ([`crate::Pipeline::output_copy`]). The file must be a regular file (not a folder, a
//! FIFO or a device such as `/dev/zero`, which would never end) of at most [`MAX_INPUT_BYTES`],
//! in UTF-8. A refusal names the field, the path as written and why, and never echoes the file's
//! content.

use std::io::Read;
use std::path::{Component, Path, PathBuf};

use crate::check::Checker;

/// The largest input file read (bytes): a friction grid of a 1000 × 1000 base is about 60 MB.
pub const MAX_INPUT_BYTES: u64 = 256 << 20;

/// A file a pipeline read: the field that names it, the path as written, where it was found and
/// its text as read.
#[derive(Clone, Debug, PartialEq)]
pub struct InputFile {
    /// The field, e.g. `friction.grid.file`.
    pub field: String,
    /// The path as written in the pipeline file (relative to its folder).
    pub given: String,
    /// The path it was read from.
    pub path: PathBuf,
    /// Its text as read.
    pub text: String,
}

/// The path `given` (from `field`) resolved against the pipeline's folder `base`; refuses (into
/// `ck`) an empty, absolute or climbing path.
pub fn resolve(ck: &mut Checker, field: &str, given: &str, base: &Path) -> Option<PathBuf> {
    let p = Path::new(given);
    let allowed = "a path relative to the pipeline file's folder, inside it (no absolute path, no '..'): the output \
                   folder keeps a copy of every file a pipeline reads";
    if given.trim().is_empty() {
        ck.push(field, "\"\"", "a file name, relative to the pipeline file's folder");
        return None;
    }
    if p.is_absolute() || p.components().any(|c| !matches!(c, Component::Normal(_) | Component::CurDir)) {
        ck.push(field, format!("{given:?}"), allowed);
        return None;
    }
    Some(base.join(p))
}

/// Reads the file `given` names (from `field`, relative to `base`) as text: a regular file of at
/// most [`MAX_INPUT_BYTES`] in UTF-8; `what` says what it should hold (for the refusals).
pub fn read(ck: &mut Checker, field: &str, given: &str, base: &Path, what: &str) -> Option<InputFile> {
    let path = resolve(ck, field, given, base)?;
    match read_regular(&path, MAX_INPUT_BYTES) {
        Ok(text) => Some(InputFile { field: field.into(), given: given.into(), path, text }),
        Err(why) => {
            ck.push(field, format!("{given:?}"), format!("{what}: {} {why}", path.display()));
            None
        }
    }
}

/// The text of `path`: a regular file (not a folder, FIFO or device) of at most `max` bytes, in
/// UTF-8; otherwise why not ("is a folder", …), without the file's content.
pub fn read_regular(path: &Path, max: u64) -> Result<String, String> {
    check_regular(path, max)?;
    let file = std::fs::File::open(path).and_then(|f| {
        // The file seen open must still be a regular file (not swapped for a FIFO since).
        if f.metadata()?.is_file() { Ok(f) } else { Err(std::io::Error::other("not a regular file")) }
    });
    let mut bytes = Vec::new();
    file.and_then(|f| f.take(max + 1).read_to_end(&mut bytes))
        .map_err(|e| format!("cannot be read ({})", io_reason(&e)))?;
    if bytes.len() as u64 > max {
        return Err(format!("grew past the {max} bytes read"));
    }
    String::from_utf8(bytes).map_err(|_| "is not UTF-8 text".into())
}

/// `Ok` when `path` is a regular file (not a folder, FIFO or device) of at most `max` bytes,
/// else why not: what a reader checks before it opens a file that might never end.
pub fn check_regular(path: &Path, max: u64) -> Result<(), String> {
    let meta = std::fs::metadata(path).map_err(|e| format!("cannot be read ({})", io_reason(&e)))?;
    if meta.is_dir() {
        return Err("is a folder".into());
    }
    if !meta.is_file() {
        return Err("is not a regular file (a FIFO, socket or device)".into());
    }
    if meta.len() > max {
        return Err(format!("holds {} bytes, more than the {max} read", meta.len()));
    }
    Ok(())
}

/// The cause of an I/O error in words, without the OS's error number.
fn io_reason(e: &std::io::Error) -> String {
    match e.kind() {
        std::io::ErrorKind::NotFound => "no such file".into(),
        std::io::ErrorKind::PermissionDenied => "permission denied".into(),
        _ => e.to_string(),
    }
}

/// Where the output folder keeps its copy of the file of `field` named `given`:
/// `inputs/<field>/<file name>`.
pub fn copy_path(field: &str, given: &str) -> String {
    let name = Path::new(given).file_name().and_then(|n| n.to_str()).unwrap_or("input");
    format!("inputs/{field}/{name}")
}

/// A CSV grid of `N` numbers per base node read from `given` relative to `base` (see [`read`]):
/// its first line after blank lines and `#` comments must be `header` (spaces aside), each row
/// `N` finite numbers (`columns` name them in a refusal, `per_row` says what a row holds).
/// Refusals go into `ck` under `field` and never echo the file's content; `None` when refused.
pub fn read_grid<const N: usize>(
    ck: &mut Checker,
    field: &str,
    given: &str,
    base: &Path,
    header: &str,
    columns: &[&str; N],
    per_row: &str,
) -> Option<(InputFile, Vec<[f64; N]>)> {
    let what = format!("a CSV file with the header {header:?} and one row per base node");
    let input = read(ck, field, given, base, &what)?;
    let mut lines =
        input.text.lines().enumerate().filter(|(_, l)| !l.trim().is_empty() && !l.trim_start().starts_with('#'));
    let first: String = lines.next().map_or("", |(_, l)| l).chars().filter(|c| !c.is_whitespace()).collect();
    if first != header {
        ck.push(field, format!("{given:?}"), format!("{what}: its first line (after # comments) is not that header"));
        return None;
    }
    let mut rows = Vec::new();
    for (i, (k, line)) in lines.enumerate() {
        let cells: Vec<&str> = line.split(',').map(str::trim).collect();
        let bad = if cells.len() != N {
            Some(format!("{} cells", cells.len()))
        } else {
            cells
                .iter()
                .position(|c| !c.parse::<f64>().is_ok_and(f64::is_finite))
                .map(|j| format!("{} is not a finite number", columns[j]))
        };
        if let Some(bad) = bad {
            ck.push(field, format!("{given:?} row {} (line {})", i + 1, k + 1), format!("{per_row} ({bad})"));
            return None;
        }
        let v: Vec<f64> = cells.iter().map(|c| c.parse::<f64>().unwrap_or(f64::NAN)).collect();
        rows.push(std::array::from_fn(|j| v[j]));
    }
    Some((input, rows))
}

#[cfg(test)]
mod tests {
    use super::*;

    fn refusal(given: &str, base: &Path) -> String {
        let mut ck = Checker::default();
        assert!(read(&mut ck, "f.file", given, base, "a CSV file").is_none(), "{given} was read");
        ck.finish().unwrap_err().to_string()
    }

    #[test]
    fn only_regular_files_inside_the_pipeline_folder_are_read_and_never_echoed() {
        let dir = std::env::temp_dir().join(format!("stickslip-input-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        std::fs::write(dir.join("sub/ok.csv"), "a,b\n1,2\n").unwrap();
        let mut ck = Checker::default();
        let f = read(&mut ck, "f.file", "sub/ok.csv", &dir, "a CSV file").unwrap();
        assert!(ck.is_clean());
        assert_eq!(f.text, "a,b\n1,2\n");
        assert_eq!(f.path, dir.join("sub/ok.csv"));
        assert!(refusal("/etc/hostname", &dir).contains("no absolute path"));
        assert!(refusal("../x.csv", &dir).contains("no '..'"));
        assert!(refusal("sub/../../x.csv", &dir).contains("no '..'"));
        assert!(refusal("", &dir).contains("a file name"));
        assert!(refusal("missing.csv", &dir).contains("no such file"));
        assert!(refusal("sub", &dir).contains("is a folder"));
        // A device that never ends, reached through a link in the pipeline's folder.
        #[cfg(unix)]
        {
            std::os::unix::fs::symlink("/dev/zero", dir.join("zero.csv")).unwrap();
            assert!(refusal("zero.csv", &dir).contains("not a regular file"));
        }
        std::fs::write(dir.join("bin.csv"), [0xff, 0xfe, b's', b'e', b'c', b'r', b'e', b't']).unwrap();
        let e = refusal("bin.csv", &dir);
        assert!(e.contains("not UTF-8") && !e.contains("secret"), "{e}");
        std::fs::remove_dir_all(&dir).unwrap();
        assert_eq!(copy_path("friction.grid.file", "sub/ok.csv"), "inputs/friction.grid.file/ok.csv");
    }
}
