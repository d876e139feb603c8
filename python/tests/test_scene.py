"""Scenes from Python: dicts, dotted keys, TOML text, files; bad keys raise ValueError naming
the key (the CLI's messages)."""

from __future__ import annotations

import pytest

import wrinkle


def test_a_dict_a_dotted_dict_and_toml_text_make_the_same_scene():
    nested = wrinkle.Scene({"load": {"tension_y": 5.0}, "geometry": {"lx": 300.0}})
    dotted = wrinkle.Scene({"load.tension_y": 5.0, "geometry.lx": 300.0})
    text = wrinkle.Scene.from_toml("[load]\ntension_y = 5.0\n[geometry]\nlx = 300.0\n")
    overridden = wrinkle.Scene(None, {"load.tension_y": 5.0, "geometry.lx": 300.0})
    hashes = {s.content_hash() for s in (nested, dotted, text, overridden)}
    assert len(hashes) == 1
    assert nested["load.tension_y"] == 5.0
    assert "tension_y = 5.0" in nested.toml


def test_a_scene_file_reads_like_the_cli(tmp_path):
    path = tmp_path / "scene.toml"
    path.write_text("[material]\npoisson = 0.25\n")
    scene = wrinkle.Scene.from_file(path)
    assert scene["material.poisson"] == 0.25
    assert scene.source == str(path)


@pytest.mark.parametrize(
    "values, key",
    [
        ({"material": {"poisson": 0.6}}, "material.poisson"),
        ({"load.tension_z": 1.0}, "load.tension_z"),
        ({"mesh": {"nx": "many"}}, "mesh.nx"),
        ({"mesh": {"nx": 0}}, "mesh.nx"),
    ],
)
def test_a_bad_key_raises_value_error_naming_it(values, key):
    with pytest.raises(ValueError, match=f"`{key}`") as raised:
        wrinkle.Scene(values)
    assert isinstance(raised.value, wrinkle.SceneError)
    assert raised.value.key == key
    assert raised.value.exit_code == 2


def test_a_bad_override_names_the_key_too():
    with pytest.raises(ValueError, match="`material.poisson`"):
        wrinkle.Scene(None, {"material.poisson": 0.7})
    with pytest.raises(ValueError, match="`material.poisson`"):
        wrinkle.buckle({"material.poisson": 0.7})


def test_numpy_values_are_scene_values():
    numpy = pytest.importorskip("numpy")
    scene = wrinkle.Scene(None, {"load.tension_y": numpy.float64(7.5), "mesh.nx": numpy.int64(20)})
    assert scene["load.tension_y"] == 7.5
    assert scene["mesh.nx"] == 20
