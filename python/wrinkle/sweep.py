"""Parameter sweeps: a scene over a grid of key values (or a list of scenes), one run per
point, on Dask (``client``) or on local processes, into a tidy table.

Each point runs in its own directory ``OUT/points/COMMAND-HASH/`` named by the content hash of
its effective scene, and writes its result there (``point.json``) last; a later sweep into the
same ``OUT`` reads the results back instead of running the points again (points that share an
effective scene run once). A point that fails — an invalid value, a solver failure, a process
killed — is a row with its outcome and reason, never a lost sweep. The table (columns in
``docs/outputs.md``) is written as ``OUT/sweep.csv``, and as ``OUT/sweep.parquet`` where pandas
and pyarrow are installed. Planning, running a point and the table are the library's
(``src/sweep/``), shared with ``wrinkle sweep``.
"""

from __future__ import annotations

import concurrent.futures
import itertools
import json
import multiprocessing
import os
import pathlib
import sys
import time
from dataclasses import dataclass, field
from typing import Any, Callable, Iterable, Mapping, Optional, Sequence, Union

import numpy as np

from . import _native
from .results import _pandas
from .scene import Scene, SceneLike, as_scene, value_text

Grid = Mapping[str, Sequence[Any]]


@dataclass
class SweepTable:
    """A sweep's table: one row per point, its inputs then its result."""

    #: Column names: ``index``, the grid's keys, then the result columns.
    columns: list[str]
    #: One list of cells per point, in point order.
    rows: list[list[Any]]
    #: The sweep directory.
    directory: pathlib.Path
    #: Points this call ran (the others were reused from an earlier sweep or invalid).
    ran: int = 0
    #: Wall-clock seconds of this call.
    seconds: float = 0.0
    #: ``sweep.parquet`` when it was written.
    parquet: Optional[pathlib.Path] = None
    _by_name: dict[str, int] = field(default_factory=dict, repr=False)

    def __post_init__(self) -> None:
        self._by_name = {name: i for i, name in enumerate(self.columns)}

    def __len__(self) -> int:
        return len(self.rows)

    @property
    def csv(self) -> pathlib.Path:
        """``sweep.csv``."""
        return self.directory / "sweep.csv"

    def column(self, name: str) -> np.ndarray:
        """One column as a NumPy array (numbers as floats with NaN for empty cells)."""
        values = [row[self._by_name[name]] for row in self.rows]
        if all(v is None or isinstance(v, (int, float)) for v in values):
            return np.array([np.nan if v is None else v for v in values], dtype=float)
        return np.array(values, dtype=object)

    def records(self) -> list[dict[str, Any]]:
        """The rows as dicts."""
        return [dict(zip(self.columns, row)) for row in self.rows]

    def to_pandas(self) -> Any:
        """The table as a ``pandas.DataFrame`` (grid values as given, parsed as numbers where
        they are)."""
        frame = _pandas().DataFrame(self.rows, columns=self.columns)
        for column in self.columns[1 : self.columns.index("outcome")]:
            frame[column] = _numeric_if_possible(frame[column])
        return frame


def _numeric_if_possible(series: Any) -> Any:
    """A column of value texts as numbers when every one is one."""
    try:
        return series.astype(float)
    except (TypeError, ValueError):
        return series


def grid_points(base: Scene, grid: Grid) -> list[dict[str, Any]]:
    """The points of ``grid`` over ``base``: every combination, the first key varying slowest
    (as ``wrinkle sweep --grid`` orders them), each ``{index, inputs, recipe}``."""
    axes = [(key, [value_text(key, v) for v in values]) for key, values in grid.items()]
    return crossed_points(base.recipe(), axes)


def crossed_points(recipe: dict[str, Any], axes: Sequence[Sequence[Any]]) -> list[dict[str, Any]]:
    """The points of ``axes`` (``[(key, [value texts])]``) over ``recipe``: every combination,
    the first axis varying slowest, each setting its values after the recipe's overrides."""
    points = []
    for index, combination in enumerate(itertools.product(*(values for _, values in axes))):
        inputs = [[key, text] for (key, _), text in zip(axes, combination)]
        overrides = recipe["overrides"] + [f"{key}={text}" for key, text in inputs]
        points.append({"index": index, "inputs": inputs, "recipe": {**recipe, "overrides": overrides}})
    return points


def listed_points(scenes: Iterable[SceneLike]) -> list[dict[str, Any]]:
    """One point per scene, with an input ``scene`` naming it (:attr:`Scene.label`)."""
    points = []
    for index, scene in enumerate(scenes):
        made = as_scene(scene)
        points.append({"index": index, "inputs": [["scene", made.label]], "recipe": made.recipe()})
    return points


def run_point(recipe: str, command: str, out: str, threads: Optional[int] = None) -> str:
    """One point, in whatever process runs it (a Dask worker, a local process): its result as
    JSON. ``threads`` sets this process's worker threads on its first point."""
    if threads:
        _native.set_threads(threads)
    return _native.sweep_run_point(recipe, command, out)


def sweep(
    scene: SceneLike,
    grid: Union[Grid, Sequence[SceneLike]],
    *,
    client: Any = None,
    out: Union[str, "os.PathLike[str]"] = "out/sweep",
    command: str = "run",
    workers: Optional[int] = None,
    threads_per_point: Optional[int] = None,
    progress: bool = False,
) -> SweepTable:
    """Runs ``scene`` over ``grid`` and returns the table (also written as ``out/sweep.csv``).

    ``grid`` is a dict of dotted scene keys to lists of values (``{"load.tension_y": [5, 10],
    "geometry.lx": [300, 400]}``: every combination, the first key varying slowest), or a list
    of scenes (dicts, TOML text, paths or :class:`Scene`; ``scene`` is then ignored).
    ``command`` is ``"run"`` (threshold and path) or ``"buckle"`` (the threshold only).

    With ``client`` (a ``dask.distributed.Client``) each point is one Dask task, keyed by its
    content hash (a task lost with its worker is run again by Dask; its directory is recovered);
    without, ``workers`` local processes (default: one per core) run them. ``out`` must be
    reachable by every worker under the same path (a shared file system on a cluster).
    ``threads_per_point`` sets each worker process's threads (default: cores / workers locally,
    left to the process on Dask).
    """
    start = time.perf_counter()
    if isinstance(grid, Mapping):
        points = grid_points(as_scene(scene), grid)
    else:
        points = listed_points(grid)
    return run_points(
        points,
        command=command,
        out=out,
        client=client,
        workers=workers,
        threads_per_point=threads_per_point,
        progress=progress,
        start=start,
    )


def run_points(
    points: list[dict[str, Any]],
    *,
    command: str,
    out: Union[str, "os.PathLike[str]"],
    client: Any,
    workers: Optional[int],
    threads_per_point: Optional[int],
    progress: bool,
    start: float,
) -> SweepTable:
    """Plans ``points``, runs what is pending (Dask or local processes), writes the table."""
    directory = pathlib.Path(out).resolve()
    directory.mkdir(parents=True, exist_ok=True)
    plan = json.loads(_native.sweep_plan(json.dumps(points), command, str(directory)))
    pending = plan["pending"]
    report = _progress_printer(len(pending)) if progress else (lambda name, result: None)
    if not pending:
        results: dict[str, Any] = {}
    elif client is not None:
        results = _run_on_dask(client, pending, command, directory, threads_per_point, report)
    else:
        results = _run_locally(pending, command, directory, workers, threads_per_point, report)
    table = json.loads(_native.sweep_table(json.dumps(plan), json.dumps(results), str(directory)))
    swept = SweepTable(
        columns=table["columns"],
        rows=table["rows"],
        directory=directory,
        ran=len(pending),
        seconds=time.perf_counter() - start,
    )
    swept.parquet = _write_parquet(swept)
    return swept


def _progress_printer(total: int) -> Callable[[str, dict[str, Any]], None]:
    """Prints one line per finished point on standard error."""
    done = itertools.count(1)

    def report(name: str, result: dict[str, Any]) -> None:
        print(
            f"sweep: {next(done)}/{total} {name} ({result['outcome']}, {result['seconds']:.1f} s)",
            file=sys.stderr,
        )

    return report


def _run_on_dask(
    client: Any,
    pending: list[dict[str, Any]],
    command: str,
    directory: pathlib.Path,
    threads: Optional[int],
    report: Callable[[str, dict[str, Any]], None],
) -> dict[str, Any]:
    """One Dask task per pending run, keyed by its name; results by name. A task that fails
    for good (its workers killed ``distributed.scheduler.allowed-failures`` times) is a
    ``lost`` row."""
    from distributed import as_completed

    futures = {}
    for run in pending:
        future = client.submit(
            run_point,
            json.dumps(run["recipe"]),
            command,
            str(directory),
            threads,
            key=f"wrinkle-{run['name']}",
            pure=False,
        )
        futures[future] = run["name"]
    results: dict[str, Any] = {}
    for future in as_completed(list(futures)):
        name = futures[future]
        try:
            results[name] = json.loads(future.result())
        except Exception as error:  # a task lost for good: its row says why
            results[name] = _lost(name, f"the Dask task failed: {error!r}")
        report(name, results[name])
    return results


def _run_locally(
    pending: list[dict[str, Any]],
    command: str,
    directory: pathlib.Path,
    workers: Optional[int],
    threads: Optional[int],
    report: Callable[[str, dict[str, Any]], None],
) -> dict[str, Any]:
    """The pending runs on local processes (``spawn``: a fresh interpreter each, no forked
    solver threads); a process that dies is a ``lost`` row."""
    cores = os.cpu_count() or 1
    workers = max(1, min(workers or cores, len(pending)))
    threads = threads or max(1, cores // workers)
    context = multiprocessing.get_context("spawn")
    results: dict[str, Any] = {}
    with concurrent.futures.ProcessPoolExecutor(workers, mp_context=context) as pool:
        futures = {
            pool.submit(run_point, json.dumps(run["recipe"]), command, str(directory), threads): run[
                "name"
            ]
            for run in pending
        }
        for future in concurrent.futures.as_completed(futures):
            name = futures[future]
            try:
                results[name] = json.loads(future.result())
            except Exception as error:
                results[name] = _lost(name, f"the process running it failed: {error!r}")
            report(name, results[name])
    return results


def _lost(name: str, why: str) -> dict[str, Any]:
    """The result of a run that came back with none (as the library's ``lost``)."""
    return {
        "hash": name.split("-", 1)[-1],
        "directory": f"points/{name}",
        "outcome": "lost",
        "exit_code": None,
        "reason": why,
        "model": None,
        "dofs": None,
        "critical_load": None,
        "load_unit": None,
        "closed_form_critical_load": None,
        "closed_form_relative_difference": None,
        "closed_form_wavenumber": None,
        "wavenumber": None,
        "wavelength": None,
        "load_at_amplitude": [None, None, None],
        "steps": None,
        "failed_checks": [],
        "seconds": 0.0,
        "peak_memory_bytes": None,
        "reused": False,
    }


def _write_parquet(table: SweepTable) -> Optional[pathlib.Path]:
    """``sweep.parquet`` beside ``sweep.csv`` when pandas and pyarrow are installed."""
    try:
        import pyarrow  # noqa: F401
    except ImportError:
        return None
    path = table.directory / "sweep.parquet"
    frame = table.to_pandas()
    temporary = path.with_name(f".{path.name}.{os.getpid()}.tmp")
    frame.to_parquet(temporary, index=False)
    os.replace(temporary, path)
    return path
