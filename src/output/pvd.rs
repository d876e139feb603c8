//! ParaView data collections (`.pvd`): a time series of `.vtu` files, one per recorded load,
//! that ParaView opens as one animated dataset (its "time" is the load $`\lambda`$).
//!
//! meshio has no `.pvd` reader: a Python script reads the collection with `xml.etree` and each
//! `file` with `meshio.read` (the `<DataSet>` elements are in load order).

use super::files::write_atomically;
use super::invalid;
use std::io;
use std::path::Path;

/// One dataset of a collection: the load it was recorded at and its file, relative to the
/// collection's directory (`/`-separated, as ParaView expects).
#[derive(Clone, Debug, PartialEq)]
pub struct SeriesEntry {
    /// The load $`\lambda`$ (ParaView's time value).
    pub load: f64,
    /// The `.vtu` file, relative to the `.pvd` file's directory.
    pub file: String,
}

/// Writes `entries` as a ParaView collection at `path` (atomically): one
/// `<DataSet timestep="λ" part="0" file="…"/>` per entry, in the order given.
///
/// ParaView sorts a collection by `timestep` and shows one dataset per distinct value; the
/// loads of a path are increasing except past a limit point, so a repeated load is nudged to the
/// next representable number above the previous one (the file keeps its exact load as field
/// data).
///
/// Errors (kind [`io::ErrorKind::InvalidInput`]): no entry, a non-finite load, an empty file
/// name or one that is absolute or climbs out with `..`.
pub fn write_pvd(path: &Path, entries: &[SeriesEntry]) -> io::Result<()> {
    if entries.is_empty() {
        return Err(invalid("time series", "needs at least one dataset"));
    }
    let mut xml = String::from(
        "<?xml version=\"1.0\"?>\n\
         <VTKFile type=\"Collection\" version=\"0.1\" byte_order=\"LittleEndian\">\n\
         <Collection>\n",
    );
    let mut previous: Option<f64> = None;
    for entry in entries {
        if !entry.load.is_finite() {
            return Err(invalid(
                format!("time series entry `{}`", entry.file),
                format!("load must be finite, got {}", entry.load),
            ));
        }
        let relative = Path::new(&entry.file);
        if entry.file.is_empty()
            || relative.is_absolute()
            || relative
                .components()
                .any(|c| matches!(c, std::path::Component::ParentDir))
        {
            return Err(invalid(
                "time series entry",
                format!("`{}` is not a file below the collection", entry.file),
            ));
        }
        let timestep = match previous {
            Some(last) if entry.load <= last => last.next_up(),
            _ => entry.load,
        };
        previous = Some(timestep);
        xml.push_str(&format!(
            "<DataSet timestep=\"{timestep:e}\" part=\"0\" file=\"{}\"/>\n",
            escape_attribute(&entry.file)
        ));
    }
    xml.push_str("</Collection>\n</VTKFile>\n");
    write_atomically(path, |writer| writer.write_all(xml.as_bytes()))
}

fn escape_attribute(text: &str) -> String {
    text.replace('&', "&amp;")
        .replace('"', "&quot;")
        .replace('<', "&lt;")
        .replace('>', "&gt;")
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Entries in order, a repeated load nudged upward, bad names refused.
    #[test]
    fn collection_lists_every_dataset_with_increasing_times() {
        let dir = std::env::temp_dir().join(format!("wrinkle-pvd-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let path = dir.join("fields.pvd");
        let entries = [
            SeriesEntry {
                load: 0.0,
                file: "series/fields_0000.vtu".into(),
            },
            SeriesEntry {
                load: 0.1,
                file: "series/fields_0001.vtu".into(),
            },
            SeriesEntry {
                load: 0.1,
                file: "series/fields_0002.vtu".into(),
            },
        ];
        write_pvd(&path, &entries).unwrap();
        let xml = std::fs::read_to_string(&path).unwrap();
        let times: Vec<f64> = xml
            .split("timestep=\"")
            .skip(1)
            .map(|rest| rest.split('"').next().unwrap().parse().unwrap())
            .collect();
        assert_eq!(times, [0.0, 0.1, 0.1f64.next_up()]);
        assert!(xml.contains("file=\"series/fields_0002.vtu\""));
        for bad in ["", "/a.vtu", "../a.vtu"] {
            let entry = SeriesEntry {
                load: 0.0,
                file: bad.into(),
            };
            assert!(write_pvd(&path, &[entry]).is_err(), "{bad}");
        }
        assert!(write_pvd(&path, &[]).is_err());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}
