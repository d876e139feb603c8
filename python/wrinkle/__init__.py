"""wrinkle: multi-scale membrane wrinkling from Python.

The library of the ``wrinkle`` command line (envelope models of Damil, Potier-Ferry & Hu 2014,
Q8 finite elements, linear buckling, ANM and Riks path following), called in-process:

* :class:`Scene` — a scene as a dict, TOML text or file, with the keys of ``docs/scenes.md``
  and the same validation (a bad key raises :class:`SceneError`, a ``ValueError`` naming it);
* :func:`buckle`, :func:`run`, :func:`compare`, :func:`analytic` — the CLI's commands, returning
  typed results (:class:`Threshold`, :class:`RunResult` with the path as NumPy arrays and the
  fields with their mesh, :class:`Comparison`);
* :func:`sweep` — a scene over a grid of key values (or a list of scenes), one run per Dask task
  (or per local process), into a tidy table (:class:`SweepTable`).

The GIL is released while solving; Ctrl-C stops a run after its current path point, writes its
outputs, then raises :class:`RunInterrupted` (a ``KeyboardInterrupt``) carrying the result.
See ``docs/python.md``.
"""

from ._native import SceneError, SolverError, WrinkleError, __version__
from .scene import Scene, as_scene
from .results import (
    Comparison,
    Fields,
    Path,
    RunInterrupted,
    RunResult,
    Threshold,
)
from .commands import analytic, buckle, compare, models, run
from .sweep import SweepTable, sweep

__all__ = [
    "Comparison",
    "Fields",
    "Path",
    "RunInterrupted",
    "RunResult",
    "Scene",
    "SceneError",
    "SolverError",
    "SweepTable",
    "Threshold",
    "WrinkleError",
    "__version__",
    "analytic",
    "as_scene",
    "buckle",
    "compare",
    "models",
    "run",
    "sweep",
]
