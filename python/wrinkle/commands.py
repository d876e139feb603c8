"""The CLI's commands as functions: :func:`buckle`, :func:`run`, :func:`compare`,
:func:`analytic`, :func:`models`. Each runs in this process, with the GIL released while it
solves; scene arguments are anything :func:`wrinkle.as_scene` takes."""

from __future__ import annotations

import json
import os
import pathlib
from typing import Any, Mapping, Optional, Sequence, Union

from . import _native
from .results import Comparison, RunInterrupted, RunResult, Threshold
from .scene import SceneLike, as_scene

PathArgument = Union[str, "os.PathLike[str]"]


def models() -> list[dict[str, Any]]:
    """The registered models: ``name``, ``description``, ``fields`` (with roles),
    ``parameters`` (as ``wrinkle models`` lists them)."""
    return [
        {"name": n, "description": d, "fields": f, "parameters": p}
        for n, d, f, p in json.loads(_native.models())
    ]


def buckle(
    scene: SceneLike = None,
    overrides: Optional[Mapping[str, Any]] = None,
    *,
    out: Optional[PathArgument] = None,
) -> Threshold:
    """Linear buckling of a scene (``wrinkle buckle``): the critical load, minimised over the
    wavenumber for an envelope model with ``model.wavenumber = "auto"``. With ``out``, also
    writes the mode, the wavenumber search and ``buckle.json`` there (``buckle --out``).
    A failed validity check is in :attr:`Threshold.warnings` (the CLI would exit with 4)."""
    made = as_scene(scene, overrides)
    data = json.loads(_native.buckle(made.recipe_json(), None if out is None else os.fspath(out)))
    return Threshold.from_data(data)


def run(
    scene: SceneLike = None,
    overrides: Optional[Mapping[str, Any]] = None,
    *,
    out: Optional[PathArgument] = None,
) -> RunResult:
    """Path following of a scene (``wrinkle run``) into ``out`` (default: the scene's
    ``output.directory``): threshold, imperfection, path to ``solver.max_amplitude_over_h``,
    and every output (``summary.json``, ``path.csv``, VTU files, plots, ``report.html``).

    A run that does not reach its target still returns (see :attr:`RunResult.outcome` and
    :attr:`RunResult.exit_code`); a scene error raises :class:`wrinkle.SceneError`, a failed
    threshold :class:`wrinkle.SolverError`. Ctrl-C stops the path after its current point,
    writes the outputs, then raises :class:`RunInterrupted` carrying the result."""
    made = as_scene(scene, overrides)
    directory = pathlib.Path(out if out is not None else made["output.directory"])
    text, interrupted = _native.run(made.recipe_json(), os.fspath(directory))
    result = RunResult.from_data(json.loads(text))
    if interrupted:
        raise RunInterrupted(result)
    return result


def compare(
    scene: SceneLike = None,
    overrides: Optional[Mapping[str, Any]] = None,
    *,
    models: Optional[Sequence[str]] = None,
    model_overrides: Sequence[str] = (),
    out: Optional[PathArgument] = None,
) -> Comparison:
    """The scene through several models (``wrinkle compare``), each into ``out/MODEL/``
    (default: ``output.directory``/compare): thresholds, wavelengths and loads at a/h = 0.5, 1,
    2 side by side. ``models`` defaults to the CLI's (the hand-written plane models);
    ``model_overrides`` are ``MODEL:KEY=VALUE`` strings (``--model-set``)."""
    made = as_scene(scene, overrides)
    if models is None:
        models = _default_compare_models()
    directory = pathlib.Path(
        out if out is not None else pathlib.Path(made["output.directory"]) / "compare"
    )
    data = json.loads(
        _native.compare(made.recipe_json(), list(models), list(model_overrides), os.fspath(directory))
    )
    return Comparison(
        rows=data["rows"],
        closed_form_critical_load=data.get("closed_form_critical_load"),
        reference=data.get("reference"),
        directory=directory,
    )


def _default_compare_models() -> list[str]:
    """The models ``wrinkle compare`` runs by default."""
    return json.loads(_native.default_compare_models())


def analytic(
    scene: SceneLike = None,
    overrides: Optional[Mapping[str, Any]] = None,
    *,
    table_1: bool = False,
) -> dict[str, Any]:
    """The closed forms of the clamped rectangle (``wrinkle analytic --json``): eq. (42)
    minimised, (44), (96), the amplitude law, a converged Galerkin solution; with ``table_1``
    also the paper's Table 1. Keys in ``docs/analytic.md``."""
    made = as_scene(scene, overrides)
    return json.loads(_native.analytic(made.recipe_json(), table_1))
