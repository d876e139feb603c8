//! Files a researcher's tools read: every VTU and PVD that `wrinkle run` writes for each model
//! (and `wrinkle buckle --out`) holds only array types meshio accepts — meshio 5.3 refuses a
//! file with a `String` array ("Illegal data type 'String'") — and every collection lists
//! files that exist, in increasing load.
//!
//! When a Python with meshio is at hand (`WRINKLE_PYTHON`, else `python3`), the same files are
//! read with `meshio.read` by `tests/support/read_with_meshio.py`; otherwise the test says why
//! it skipped that part.

use std::path::{Path, PathBuf};
use std::process::Command;

/// The array types meshio's VTU reader knows (`meshio/vtu/_vtu.py`, `vtu_to_numpy_type`).
const MESHIO_TYPES: [&str; 10] = [
    "Float32", "Float64", "Int8", "Int16", "Int32", "Int64", "UInt8", "UInt16", "UInt32", "UInt64",
];

fn scratch_dir(name: &str) -> PathBuf {
    let dir = std::env::temp_dir().join(format!("wrinkle-readers-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    dir
}

/// A short run of `model` on a coarse mesh (every output but the plots), accepting every
/// validity check: only the files matter here.
fn run_model(model: &str) -> PathBuf {
    let dir = scratch_dir(model);
    let output = Command::new(env!("CARGO_BIN_EXE_wrinkle"))
        .args(["run", "--quiet", "--out", dir.to_str().unwrap()])
        .args(["--set", &format!("model.name={model}")])
        .args(["--set", "mesh.nx=16", "--set", "mesh.ny=8"])
        .args(["--set", "solver.max_amplitude_over_h=1"])
        .args([
            "--set",
            "output.plots=false",
            "--set",
            "validity.accept=all",
        ])
        .args(["--set", "output.vtu_loads=[0.05]"])
        .output()
        .unwrap();
    assert!(
        matches!(output.status.code(), Some(0 | 3)),
        "{model}: {}",
        String::from_utf8_lossy(&output.stderr)
    );
    dir
}

/// Every file below `dir` whose name ends with `extension`.
fn files_below(dir: &Path, extension: &str) -> Vec<PathBuf> {
    let mut found = Vec::new();
    for entry in std::fs::read_dir(dir).unwrap() {
        let path = entry.unwrap().path();
        if path.is_dir() {
            found.extend(files_below(&path, extension));
        } else if path.extension().is_some_and(|e| e == extension) {
            found.push(path);
        }
    }
    found.sort();
    found
}

/// The `type="…"` of every `<DataArray>` of an XML file.
fn data_array_types(xml: &str) -> Vec<String> {
    xml.split("<DataArray")
        .skip(1)
        .map(|rest| {
            let tag = &rest[..rest.find('>').unwrap()];
            let at = tag.find("type=\"").expect("a DataArray without a type") + 6;
            tag[at..at + tag[at..].find('"').unwrap()].to_string()
        })
        .collect()
}

/// Checks the XML shape of every VTU and PVD below `dir`; returns how many files it checked.
fn check_xml_shape(dir: &Path) -> usize {
    let vtu = files_below(dir, "vtu");
    assert!(!vtu.is_empty(), "no VTU below {}", dir.display());
    for file in &vtu {
        let xml = std::fs::read_to_string(file).unwrap();
        let types = data_array_types(&xml);
        assert!(!types.is_empty(), "{}", file.display());
        for kind in types {
            assert!(
                MESHIO_TYPES.contains(&kind.as_str()),
                "{}: array type `{kind}` that meshio refuses",
                file.display()
            );
        }
        for field_data in ["load", "load_unit"] {
            assert!(
                xml.contains(&format!("Name=\"{field_data}\"")),
                "{}: no field data `{field_data}`",
                file.display()
            );
        }
    }
    let pvd = files_below(dir, "pvd");
    for collection in &pvd {
        let xml = std::fs::read_to_string(collection).unwrap();
        assert!(
            xml.contains("type=\"Collection\""),
            "{}",
            collection.display()
        );
        let mut previous = f64::NEG_INFINITY;
        for dataset in xml.split("<DataSet ").skip(1) {
            let attribute = |name: &str| {
                let at = dataset.find(&format!("{name}=\"")).unwrap() + name.len() + 2;
                dataset[at..at + dataset[at..].find('"').unwrap()].to_string()
            };
            let time: f64 = attribute("timestep").parse().unwrap();
            assert!(
                time > previous,
                "{}: times not increasing",
                collection.display()
            );
            previous = time;
            let file = collection.parent().unwrap().join(attribute("file"));
            assert!(
                file.is_file(),
                "{} lists a missing {}",
                collection.display(),
                file.display()
            );
        }
    }
    vtu.len() + pvd.len()
}

/// The Python that reads the files, if it has meshio: `Err` says why not.
fn python_with_meshio() -> Result<String, String> {
    let python = std::env::var("WRINKLE_PYTHON").unwrap_or_else(|_| "python3".into());
    match Command::new(&python).args(["-c", "import meshio"]).output() {
        Ok(output) if output.status.success() => Ok(python),
        Ok(output) => Err(format!(
            "`{python} -c \"import meshio\"` failed: {}",
            String::from_utf8_lossy(&output.stderr).trim()
        )),
        Err(error) => Err(format!("no `{python}`: {error}")),
    }
}

/// Reads every VTU and PVD below `dirs` with meshio, or says why it could not.
fn read_with_meshio(dirs: &[PathBuf]) {
    let python = match python_with_meshio() {
        Ok(python) => python,
        Err(reason) => {
            eprintln!(
                "skipped the meshio check: {reason} (set WRINKLE_PYTHON to a Python with meshio)"
            );
            return;
        }
    };
    let script = Path::new(env!("CARGO_MANIFEST_DIR")).join("tests/support/read_with_meshio.py");
    let output = Command::new(python)
        .arg(script)
        .args(dirs)
        .output()
        .unwrap();
    let stdout = String::from_utf8_lossy(&output.stdout);
    assert!(
        output.status.success(),
        "meshio could not read a file:\n{stdout}\n{}",
        String::from_utf8_lossy(&output.stderr)
    );
    eprintln!("{stdout}");
}

#[test]
fn every_vtu_and_pvd_of_every_model_is_readable_by_meshio() {
    let dirs: Vec<PathBuf> = [
        "reference-envelope",
        "complex-envelope",
        "fvk-plate",
        "pure-membrane",
    ]
    .into_iter()
    .map(run_model)
    .collect();
    for dir in &dirs {
        check_xml_shape(dir);
        // The path as a time series: fields and surface at every step end.
        for collection in ["fields.pvd", "surface.pvd"] {
            assert!(
                dir.join(collection).is_file(),
                "{}: no {collection}",
                dir.display()
            );
        }
    }
    read_with_meshio(&dirs);
    for dir in dirs {
        std::fs::remove_dir_all(dir).unwrap();
    }
}

/// The plate has no carrier wave: its VTU field data give the wavelength of its mode, not a
/// wavenumber of 0.
#[test]
fn the_plate_vtu_gives_its_wavelength_not_a_zero_wavenumber() {
    let dir = run_model("fvk-plate");
    let xml = std::fs::read_to_string(dir.join("fields_final.vtu")).unwrap();
    assert!(
        !xml.contains("Name=\"wavenumber\""),
        "a plate has no wavenumber"
    );
    let at = xml.find("Name=\"wavelength\"").expect("no wavelength");
    let text = &xml[at..];
    let value: f64 = text[text.find('>').unwrap() + 1..text.find('<').unwrap()]
        .trim()
        .parse()
        .unwrap();
    assert!(value > 10.0 && value < 60.0, "wavelength {value} mm");
    std::fs::remove_dir_all(dir).unwrap();
}
