//! Every file the program reads goes through [`read_capped`]: at most a stated number of bytes,
//! so that a wrong argument (`--threshold /dev/urandom`, a multi-gigabyte file) is a clear error
//! at once instead of memory growing until the system kills the process.
//!
//! The caps: scene files [`crate::scene::MAX_SCENE_BYTES`], `--threshold` files and a previous
//! run's `summary.json` [`MAX_SUMMARY_BYTES`], the plots embedded in a report
//! [`MAX_FIGURE_BYTES`].

use std::io::{self, Read};
use std::path::Path;

/// Largest JSON file read: a `summary.json` (`--threshold`, or a previous run's manifest) or
/// the output of `wrinkle buckle --json`. The summary of a run of [`crate::scene::MAX_STEPS`
/// steps](crate::scene) and its path is a few tens of megabytes.
pub const MAX_SUMMARY_BYTES: u64 = 256 << 20;

/// Largest figure (PNG) embedded in `report.html`.
pub const MAX_FIGURE_BYTES: u64 = 64 << 20;

/// The contents of `path`, at most `limit` bytes. A longer file (or an endless one, such as a
/// device) is an error of kind [`io::ErrorKind::FileTooLarge`] saying so, after reading at
/// most `limit + 1` bytes; the message does not repeat the path (callers name the file).
pub fn read_capped(path: &Path, limit: u64) -> io::Result<Vec<u8>> {
    let file = std::fs::File::open(path)?;
    let mut bytes = Vec::new();
    file.take(limit.saturating_add(1)).read_to_end(&mut bytes)?;
    if bytes.len() as u64 > limit {
        return Err(io::Error::new(
            io::ErrorKind::FileTooLarge,
            format!(
                "larger than {} (the most this file may hold)",
                bytes_text(limit)
            ),
        ));
    }
    Ok(bytes)
}

/// [`read_capped`] as UTF-8 text; text that is not UTF-8 is an error of kind
/// [`io::ErrorKind::InvalidData`].
pub fn read_capped_text(path: &Path, limit: u64) -> io::Result<String> {
    String::from_utf8(read_capped(path, limit)?).map_err(|error| {
        io::Error::new(
            io::ErrorKind::InvalidData,
            format!("not UTF-8 text: {error}"),
        )
    })
}

/// `limit` bytes in words: `1 MiB`, `256 MiB`, or a count of bytes.
fn bytes_text(limit: u64) -> String {
    const MIB: u64 = 1 << 20;
    if limit >= MIB && limit.is_multiple_of(MIB) {
        format!("{} MiB", limit / MIB)
    } else {
        format!("{limit} bytes")
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_endless_file_is_refused_after_its_cap() {
        let error = read_capped(Path::new("/dev/zero"), 1 << 10).unwrap_err();
        assert_eq!(error.kind(), io::ErrorKind::FileTooLarge);
        assert!(
            error.to_string().contains("larger than 1024 bytes"),
            "{error}"
        );
    }

    #[test]
    fn caps_are_stated_in_mebibytes() {
        assert_eq!(bytes_text(MAX_SUMMARY_BYTES), "256 MiB");
        assert_eq!(bytes_text(1000), "1000 bytes");
    }
}
