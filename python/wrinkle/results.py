"""Typed results: what :func:`wrinkle.buckle`, :func:`wrinkle.run` and :func:`wrinkle.compare`
return. Each is built from the library's own result (``summary.json``'s keys, documented in
``docs/outputs.md``), computed once in Rust; these classes only give it Python types — the
path as NumPy arrays, the fields with their mesh — and ``to_pandas()`` where pandas is
installed. ``data`` keeps every key as the library serialised it.
"""

from __future__ import annotations

import json
import pathlib
from dataclasses import dataclass, field
from typing import Any, Optional

import numpy as np

from . import _native

#: Columns of the path, as in ``path.csv``.
PATH_COLUMNS = (
    "step",
    "interior",
    "lambda",
    "n_x",
    "max_amplitude",
    "max_amplitude_over_h",
    "centre_amplitude_over_h",
    "residual",
    "elliptic",
    "closed_form_amplitude_over_h",
)


def _pandas() -> Any:
    """The pandas module, or an ``ImportError`` saying how to get it."""
    try:
        import pandas
    except ImportError as error:  # pragma: no cover - depends on the environment
        raise ImportError("to_pandas() needs pandas: pip install pandas") from error
    return pandas


@dataclass(frozen=True)
class Threshold:
    """The wrinkling threshold of a scene (``wrinkle buckle --json``)."""

    #: Registry name of the model.
    model: str
    #: Critical load λ_c (unit :attr:`load_unit`).
    critical_load: float
    #: Unit of λ: ``N/mm`` (biaxial load) or ``mm`` (end displacement).
    load_unit: str
    #: Wavenumber Q (1/mm) of an envelope model, else ``None``.
    wavenumber: Optional[float]
    #: Wavelength (mm).
    wavelength: Optional[float]
    #: Where Q came from (``auto``, ``fixed``, ``mode``, …).
    wavenumber_mode: str
    #: Free unknowns.
    dofs: int
    #: λ_c of eq. (42) minimised, where it applies.
    closed_form_critical_load: Optional[float]
    #: (λ_c − λ_c⁽⁴²⁾)/λ_c⁽⁴²⁾.
    closed_form_relative_difference: Optional[float]
    #: Notes for the user.
    notes: list[str]
    #: Failed validity checks: ``[{"check", "message"}]``.
    warnings: list[dict[str, str]]
    #: Every key, as serialised.
    data: dict[str, Any] = field(repr=False)

    @classmethod
    def from_data(cls, data: dict[str, Any]) -> "Threshold":
        """The threshold of its JSON object."""
        return cls(
            model=data["model"],
            critical_load=data["critical_load"],
            load_unit=data["load_unit"],
            wavenumber=data.get("wavenumber"),
            wavelength=data.get("wavelength"),
            wavenumber_mode=data.get("wavenumber_mode", ""),
            dofs=data["dofs"],
            closed_form_critical_load=data.get("closed_form_critical_load"),
            closed_form_relative_difference=data.get("closed_form_relative_difference"),
            notes=list(data.get("notes", [])),
            warnings=list(data.get("warnings", [])),
            data=data,
        )


class Path:
    """The equilibrium path: one NumPy array per column of ``path.csv`` (``lambda`` is
    :attr:`load`); a missing value (``n_x`` off the biaxial load) is NaN."""

    def __init__(self, points: list[dict[str, Any]]) -> None:
        self._points = points
        self.columns: dict[str, np.ndarray] = {}
        for column in PATH_COLUMNS:
            values = [point.get(column) for point in points]
            if column in ("interior", "elliptic"):
                self.columns[column] = np.array(values, dtype=bool)
            elif column == "step":
                self.columns[column] = np.array(values, dtype=np.int64)
            else:
                self.columns[column] = np.array(
                    [np.nan if v is None else v for v in values], dtype=float
                )

    def __len__(self) -> int:
        return len(self._points)

    def __getitem__(self, column: str) -> np.ndarray:
        return self.columns[column]

    @property
    def load(self) -> np.ndarray:
        """The load parameter λ at each point."""
        return self.columns["lambda"]

    @property
    def amplitude_over_h(self) -> np.ndarray:
        """The maximum physical wrinkle amplitude over the thickness at each point."""
        return self.columns["max_amplitude_over_h"]

    def to_pandas(self) -> Any:
        """The path as a ``pandas.DataFrame`` (columns of ``path.csv``)."""
        return _pandas().DataFrame(self.columns)


@dataclass(frozen=True)
class Fields:
    """The fields of a VTU file with their mesh: node coordinates ``points`` (n × 3), cells
    ``cells`` (m × nodes per cell; Q8: 8, VTK type 23), point and cell data by name (n or
    n × components)."""

    #: The file read.
    file: pathlib.Path
    #: Node coordinates (mm), n × 3.
    points: np.ndarray
    #: Node indices of each cell, m × 8 for Q8 meshes.
    cells: np.ndarray
    #: VTK cell types (23: quadratic quadrilateral).
    cell_types: np.ndarray
    #: Nodal arrays by name.
    point_data: dict[str, np.ndarray]
    #: Cell arrays by name.
    cell_data: dict[str, np.ndarray]

    @classmethod
    def read(cls, file: "str | pathlib.Path") -> "Fields":
        """Reads a VTU file written by a run."""
        file = pathlib.Path(file)
        data = json.loads(_native.read_vtu(str(file)))
        offsets = np.asarray(data["offsets"], dtype=np.int64)
        connectivity = np.asarray(data["connectivity"], dtype=np.int64)
        sizes = np.diff(np.concatenate([[0], offsets]))
        if len(sizes) and np.all(sizes == sizes[0]):
            cells = connectivity.reshape(len(sizes), int(sizes[0]))
        else:
            cells = np.asarray(np.split(connectivity, offsets[:-1]), dtype=object)

        def arrays(group: dict[str, Any]) -> dict[str, np.ndarray]:
            out = {}
            for name, array in group.items():
                values = np.asarray(array["values"], dtype=float)
                components = int(array["components"])
                out[name] = values.reshape(-1, components) if components > 1 else values
            return out

        return cls(
            file=file,
            points=np.asarray(data["points"], dtype=float).reshape(-1, 3),
            cells=cells,
            cell_types=np.asarray(data["cell_types"], dtype=np.uint8),
            point_data=arrays(data["point_data"]),
            cell_data=arrays(data["cell_data"]),
        )

    def to_pandas(self) -> Any:
        """The nodal data with the coordinates as a ``pandas.DataFrame`` (vector arrays split
        into ``NAME_0``, ``NAME_1``, …)."""
        columns: dict[str, np.ndarray] = {"x": self.points[:, 0], "y": self.points[:, 1]}
        for name, values in self.point_data.items():
            if values.ndim == 1:
                columns[name] = values
            else:
                for component in range(values.shape[1]):
                    columns[f"{name}_{component}"] = values[:, component]
        return _pandas().DataFrame(columns)


class RunInterrupted(KeyboardInterrupt):
    """Ctrl-C during :func:`wrinkle.run`: the path stopped after its current point and every
    output was written; :attr:`result` is the run's result (outcome ``interrupted``)."""

    def __init__(self, result: "RunResult") -> None:
        super().__init__(f"run interrupted; outputs written to {result.directory}")
        self.result = result


@dataclass(frozen=True)
class RunResult:
    """What :func:`wrinkle.run` produced (``summary.json``, typed)."""

    #: ``reached``, ``failed``, ``incomplete``, ``invalid`` or ``interrupted``.
    outcome: str
    #: The exit code ``wrinkle run`` would end with (0, 1, 3, 4, 130).
    exit_code: int
    #: Why it did not reach its target, if it did not.
    reason: Optional[str]
    #: The threshold found on the run's problem.
    threshold: Threshold
    #: The equilibrium path.
    path: Path = field(repr=False)
    #: The run directory.
    directory: pathlib.Path
    #: Every file written.
    files: list[pathlib.Path] = field(repr=False)
    #: The summary table as the CLI prints it.
    summary_text: str = field(repr=False)
    #: ``summary.json`` as serialised.
    summary: dict[str, Any] = field(repr=False)

    @classmethod
    def from_data(cls, data: dict[str, Any]) -> "RunResult":
        """The result of the native ``run``'s JSON object."""
        summary = data["summary"]
        return cls(
            outcome=summary["outcome"],
            exit_code=summary["exit_code"],
            reason=summary.get("outcome_reason"),
            threshold=Threshold.from_data(summary["threshold"]),
            path=Path(summary["path"]),
            directory=pathlib.Path(data["directory"]),
            files=[pathlib.Path(f) for f in data["files"]],
            summary_text=data["summary_text"],
            summary=summary,
        )

    @property
    def report(self) -> pathlib.Path:
        """The self-contained HTML report."""
        return self.directory / "report.html"

    @property
    def vtu_files(self) -> list[tuple[float, pathlib.Path]]:
        """The VTU files of states along the path, with their loads."""
        return [(v["load"], self.directory / v["file"]) for v in self.summary.get("vtu", [])]

    def fields(self, file: str = "fields_final.vtu") -> Fields:
        """The fields of one VTU file of the run (default: the last point)."""
        return Fields.read(self.directory / file)

    def to_pandas(self) -> Any:
        """The path as a ``pandas.DataFrame``."""
        return self.path.to_pandas()


@dataclass(frozen=True)
class Comparison:
    """What :func:`wrinkle.compare` produced: one row per model (``compare.json``)."""

    #: One dict per model: ``model``, ``outcome``, ``critical_load``, ``wavelength``,
    #: ``load_at_amplitude`` (at a/h = 0.5, 1, 2), …
    rows: list[dict[str, Any]]
    #: λ_c of eq. (42) where the scene has it.
    closed_form_critical_load: Optional[float]
    #: The model the ratios are relative to.
    reference: Optional[str]
    #: The comparison's directory (one run directory per model).
    directory: pathlib.Path

    def to_pandas(self) -> Any:
        """The rows as a ``pandas.DataFrame``, loads at a/h = 0.5, 1, 2 as three columns."""
        records = []
        for row in self.rows:
            record = {k: v for k, v in row.items() if k != "load_at_amplitude"}
            for level, load in zip((0.5, 1, 2), row.get("load_at_amplitude", [])):
                record[f"load_at_amplitude_{level}"] = load
            records.append(record)
        return _pandas().DataFrame.from_records(records)
