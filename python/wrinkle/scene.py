"""Scenes: a base (the built-in default, TOML text, a file or a dict) and overrides.

A :class:`Scene` is kept as the recipe that makes it — the base's TOML text and ``KEY=VALUE``
overrides, applied in order as ``wrinkle run SCENE --set KEY=VALUE`` applies them — and is
validated when made: a bad key or value raises :class:`wrinkle.SceneError` (a ``ValueError``)
whose message names the key, and whose ``key`` attribute holds it.
"""

from __future__ import annotations

import json
import os
from typing import Any, Mapping, Optional, Union

from . import _native

SceneLike = Union["Scene", Mapping[str, Any], str, "os.PathLike[str]", None]


def _json_default(value: Any) -> Any:
    """NumPy scalars and arrays as plain Python values for ``json.dumps``."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{type(value).__name__} is not a scene value")


def to_json(value: Any) -> str:
    """``value`` as JSON text (NumPy scalars and arrays accepted)."""
    return json.dumps(value, default=_json_default, allow_nan=False)


def value_text(key: str, value: Any) -> str:
    """The TOML text of one value, as the ``VALUE`` of ``KEY=VALUE``."""
    return _native.value_text(to_json(value), key)


class Scene:
    """A validated scene: a base and overrides.

    ``Scene()`` is the built-in default scene (the paper's example 1); ``Scene(dict)`` a scene
    of the dict's keys (nested tables or dotted keys: ``{"load": {"tension_y": 5}}`` or
    ``{"load.tension_y": 5}``); ``Scene(text)`` TOML text; ``Scene(pathlib.Path(...))`` a file
    (``Scene.from_file`` also takes a ``str``). ``overrides`` are applied after the base, in
    order, as ``--set`` does.
    """

    def __init__(
        self,
        base: Union[Mapping[str, Any], str, "os.PathLike[str]", None] = None,
        overrides: Optional[Mapping[str, Any]] = None,
        *,
        source: Optional[str] = None,
    ) -> None:
        self._given = ""
        if base is None:
            self._text: Optional[str] = None
            self._source = "<built-in default scene>"
        elif isinstance(base, Mapping):
            self._text = _native.scene_text_of_dict(to_json(dict(base)))
            self._source = source or "<dict>"
            self._given = " ".join(f"{k}={v!r}" for k, v in _flattened(base))
        elif isinstance(base, os.PathLike):
            path = os.fspath(base)
            with open(path, encoding="utf-8") as file:
                self._text = file.read()
            self._source = source or path
        elif isinstance(base, str):
            self._text = base
            self._source = source or "<toml>"
        else:
            raise TypeError(f"a scene is a dict, TOML text or a path, not {type(base).__name__}")
        self._overrides: list[str] = []
        for key, value in (overrides or {}).items():
            self._overrides.append(f"{key}={value_text(key, value)}")
        self._effective_toml, echo = _native.effective_scene(self.recipe_json())
        self._echo: dict[str, Any] = json.loads(echo)

    @classmethod
    def from_file(cls, path: Union[str, "os.PathLike[str]"]) -> "Scene":
        """The scene of a TOML file."""
        return cls(_PathLike(os.fspath(path)))

    @classmethod
    def from_toml(cls, text: str, source: str = "<toml>") -> "Scene":
        """The scene of TOML text; ``source`` names it in errors."""
        return cls(text, source=source)

    def with_values(self, values: Mapping[str, Any]) -> "Scene":
        """A new scene: this one with ``values`` (dotted keys) set, after its own overrides."""
        scene = Scene.__new__(Scene)
        scene._text, scene._source, scene._given = self._text, self._source, self._given
        scene._overrides = list(self._overrides) + [
            f"{key}={value_text(key, value)}" for key, value in values.items()
        ]
        scene._effective_toml, echo = _native.effective_scene(scene.recipe_json())
        scene._echo = json.loads(echo)
        return scene

    def recipe(self) -> dict[str, Any]:
        """How the scene is made: ``{"text", "source", "overrides"}``."""
        return {"text": self._text, "source": self._source, "overrides": list(self._overrides)}

    def recipe_json(self) -> str:
        """:meth:`recipe` as JSON (what the native module and the sweep's tasks take)."""
        return json.dumps(self.recipe())

    @property
    def source(self) -> str:
        """Where the base came from (a file's path, ``<dict>``, ``<toml>``)."""
        return self._source

    @property
    def label(self) -> str:
        """A short name: the source (or a dict's keys and values) and the overrides."""
        return " ".join(filter(None, [self._given or self._source, *self._overrides]))

    @property
    def toml(self) -> str:
        """The effective scene (every key) as TOML, as ``wrinkle scene`` prints it."""
        return self._effective_toml

    @property
    def values(self) -> dict[str, Any]:
        """The effective scene as nested dicts (``values["load"]["tension_y"]``)."""
        return self._echo

    def __getitem__(self, key: str) -> Any:
        """A value of the effective scene by dotted key: ``scene["load.tension_y"]``."""
        section, _, name = key.partition(".")
        return self._echo[section][name] if name else self._echo[section]

    def content_hash(self) -> str:
        """The content hash of the effective scene (a sweep point's directory name)."""
        return _native.content_hash(self.recipe_json())

    def __repr__(self) -> str:
        overrides = ", ".join(self._overrides)
        return f"Scene({self._source!r}{', ' + overrides if overrides else ''})"


def _flattened(values: Mapping[str, Any], prefix: str = "") -> list[tuple[str, Any]]:
    """The entries of nested mappings as ``(dotted key, value)``."""
    entries: list[tuple[str, Any]] = []
    for key, value in values.items():
        dotted = f"{prefix}{key}"
        if isinstance(value, Mapping):
            entries.extend(_flattened(value, dotted + "."))
        else:
            entries.append((dotted, value))
    return entries


class _PathLike(os.PathLike):
    """A ``str`` path marked as a path (not TOML text)."""

    def __init__(self, path: str) -> None:
        self._path = path

    def __fspath__(self) -> str:
        return self._path


def as_scene(scene: SceneLike, overrides: Optional[Mapping[str, Any]] = None) -> Scene:
    """``scene`` as a :class:`Scene` (a ``Scene``, dict, TOML text, path, or ``None`` for the
    default), with ``overrides`` applied."""
    if isinstance(scene, Scene):
        return scene.with_values(overrides) if overrides else scene
    return Scene(scene, overrides)
