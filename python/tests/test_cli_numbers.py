"""`import wrinkle; wrinkle.run(...)` gives the CLI's numbers, bit for bit (same library, and
floating point is the same at every optimisation level: Rust never reassociates)."""

from __future__ import annotations

import json
import subprocess

import numpy as np

import wrinkle

OVERRIDES = ["mesh.nx=16", "mesh.ny=8", "solver.max_amplitude_over_h=1.0", "output.plots=false"]


def test_run_gives_the_cli_numbers(cli, tmp_path, fast_scene):
    command = [str(cli), "--threads", "1", "run", "-q", "--out", str(tmp_path / "cli")]
    for assignment in OVERRIDES:
        command += ["--set", assignment]
    subprocess.run(command, check=True, stdout=subprocess.DEVNULL)
    expected = json.loads((tmp_path / "cli" / "summary.json").read_text())

    result = wrinkle.run(fast_scene, out=tmp_path / "python")

    assert result.outcome == expected["outcome"] == "reached"
    assert result.threshold.critical_load == expected["linear_buckling_load"]
    assert result.threshold.wavenumber == expected["wavenumber"]
    lam = np.array([p["lambda"] for p in expected["path"]])
    amplitude = np.array([p["max_amplitude_over_h"] for p in expected["path"]])
    np.testing.assert_array_equal(result.path.load, lam)
    np.testing.assert_array_equal(result.path.amplitude_over_h, amplitude)
    assert (tmp_path / "python" / "path.csv").read_text() == (tmp_path / "cli" / "path.csv").read_text()


def test_buckle_gives_the_cli_numbers(cli, fast_scene):
    command = [str(cli), "buckle", "--json", "-q"]
    for assignment in OVERRIDES:
        command += ["--set", assignment]
    expected = json.loads(subprocess.run(command, check=True, capture_output=True).stdout)
    threshold = wrinkle.buckle(fast_scene)
    assert threshold.critical_load == expected["critical_load"]
    assert threshold.wavelength == expected["wavelength"]
    assert threshold.closed_form_critical_load == expected["closed_form_critical_load"]


def test_a_run_result_is_typed_with_arrays_fields_and_files(tmp_path, fast_scene):
    result = wrinkle.run(fast_scene, out=tmp_path / "run")
    assert result.exit_code == 0
    assert result.path.load.dtype == np.float64
    assert len(result.path) == len(result.path["step"]) > 2
    assert result.report.is_file()
    fields = result.fields()
    assert fields.points.shape[1] == 3
    assert fields.cells.shape == (16 * 8, 8)
    assert set(fields.cell_types) == {23}
    assert all(len(v) == len(fields.points) for v in fields.point_data.values())
    assert [file.name for _, file in result.vtu_files]
    pandas = __import__("pytest").importorskip("pandas")
    frame = result.to_pandas()
    assert isinstance(frame, pandas.DataFrame) and list(frame["lambda"]) == list(result.path.load)


def test_compare_and_analytic_return_the_cli_objects(tmp_path, fast_scene):
    comparison = wrinkle.compare(fast_scene, models=["reference-envelope"], out=tmp_path / "c")
    assert [row["model"] for row in comparison.rows] == ["reference-envelope"]
    assert comparison.closed_form_critical_load is not None
    closed = wrinkle.analytic(fast_scene)
    assert closed["critical_load_exact"] == comparison.closed_form_critical_load
