"""Type stubs of the native module ``wrinkle._native`` (PyO3). Scenes travel as recipes (JSON:
``{"text", "source", "overrides"}``), results as JSON text; the typed objects are made by the
pure-Python modules (:mod:`wrinkle.results`, :mod:`wrinkle.sweep`)."""

from typing import Optional

__version__: str

class WrinkleError(RuntimeError):
    """A run that could not be done; ``exit_code`` is the CLI's."""

    exit_code: int
    key: Optional[str]
    source: Optional[str]

class SceneError(ValueError):
    """A bad scene: ``key`` names the key, ``source`` where it was set; ``exit_code`` is 2."""

    exit_code: int
    key: Optional[str]
    source: Optional[str]

class SolverError(WrinkleError):
    """A solver failure (singular tangent, no convergence); ``exit_code`` is 1."""

def scene_text_of_dict(json: str) -> str:
    """TOML text of a scene given as a dict (as JSON); dotted keys are nested."""

def value_text(json: str, key: str) -> str:
    """TOML text of one value (as JSON), the ``VALUE`` of ``KEY=VALUE``."""

def effective_scene(recipe: str) -> tuple[str, str]:
    """The recipe's effective scene: its TOML, and its JSON echo. Raises ``SceneError``."""

def content_hash(recipe: str) -> str:
    """The content hash of the recipe's effective scene."""

def models() -> str:
    """The model registry as JSON: ``[[name, description, fields, parameters], ...]``."""

def default_compare_models() -> str:
    """The models ``wrinkle compare`` runs by default, as a JSON list."""

def set_threads(threads: int) -> bool:
    """Sets this process's worker threads; ``False`` when already set."""

def buckle(recipe: str, out: Optional[str] = None) -> str:
    """``wrinkle buckle [--out OUT] --json``: the threshold's keys as JSON."""

def run(recipe: str, out: str) -> tuple[str, bool]:
    """``wrinkle run --out OUT``: ``{summary, files, summary_text, directory}`` as JSON, and
    whether Ctrl-C interrupted the path."""

def compare(recipe: str, models: list[str], model_overrides: list[str], out: str) -> str:
    """``wrinkle compare``: ``{rows, closed_form_critical_load, reference, directory}``."""

def analytic(recipe: str, table_1: bool = False) -> str:
    """``wrinkle analytic --json``."""

def read_vtu(path: str) -> str:
    """A VTU file's arrays as JSON: points, connectivity, offsets, cell types, point and cell
    data (``{name: {components, values}}``)."""

def sweep_plan(points: str, command: str, out: str) -> str:
    """The plan of a sweep (JSON) from its points ``[{index, inputs, recipe}]``."""

def sweep_run_point(recipe: str, command: str, out: str) -> str:
    """Runs one point of a sweep in ``out`` (or reads back its earlier result): JSON."""

def sweep_table(plan: str, results: str, out: str) -> str:
    """Writes ``out/sweep.csv`` from the plan and the results by name; ``{columns, rows}``."""
