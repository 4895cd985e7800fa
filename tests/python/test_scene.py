"""seasim.Scene: files, dicts, overrides, and the errors bad input raises."""

from __future__ import annotations

import tomllib

import numpy as np
import pytest

import seasim
from conftest import SMALL, scene_path


def test_load_reads_the_file_with_overrides(flat_sea):
    assert flat_sea.name == "flat_sea"
    assert (flat_sea.width, flat_sea.height) == (64, 36)
    assert flat_sea.file == str(scene_path("flat_sea.toml"))
    assert flat_sea.overrides == {"camera.width": "64", "camera.height": "36"}
    assert "sea_single" in flat_sea.plan


def test_from_dict_takes_the_scene_files_keys_and_renders_the_same_image():
    with open(scene_path("flat_sea.toml"), "rb") as f:
        as_dict = tomllib.load(f)
    as_dict["camera"]["width"], as_dict["camera"]["height"] = 64, 36
    from_dict = seasim.Scene.from_dict(as_dict)
    assert from_dict.file is None and from_dict.name == "flat_sea"
    from_file = seasim.Scene.load(scene_path("flat_sea.toml"), overrides=SMALL)
    a = seasim.Renderer(from_dict).render().rgb
    b = seasim.Renderer(from_file).render().rgb
    assert np.array_equal(a, b)


def test_from_dict_accepts_numpy_values_and_tuples():
    with open(scene_path("flat_sea.toml"), "rb") as f:
        as_dict = tomllib.load(f)
    as_dict["camera"]["position"] = np.array([0.0, 10.0, 0.0])
    as_dict["camera"]["width"] = np.int64(32)
    as_dict["spectral"]["range_nm"] = (400.0, 700.0)
    scene = seasim.Scene.from_dict(as_dict)
    assert scene.width == 32
    assert "position = [ 0.0, 10.0, 0.0 ]" in scene.toml


def test_with_overrides_makes_a_new_scene(flat_sea):
    wider = flat_sea.with_overrides({"camera.width": 80})
    assert wider.width == 80 and flat_sea.width == 64


def test_unknown_key_in_a_file_names_file_line_and_key(tmp_path):
    bad = tmp_path / "bad.toml"
    text = scene_path("flat_sea.toml").read_text(encoding="utf-8")
    bad.write_text(text.replace("fov_deg = 60.0", "fov_deg = 60.0\nfocal = 3"), encoding="utf-8")
    with pytest.raises(seasim.SceneError) as e:
        seasim.Scene.load(bad)
    line = next(i + 1 for i, text in enumerate(bad.read_text(encoding="utf-8").splitlines()) if text.startswith("focal"))
    assert e.value.file == str(bad) and e.value.line == line and e.value.key == "camera.focal"
    assert str(e.value).startswith(f"{bad}:{line}: key 'camera.focal'")


def test_wrong_type_in_an_override_names_the_key():
    with pytest.raises(seasim.SceneError) as e:
        seasim.Scene.load(scene_path("flat_sea.toml"), overrides={"camera.width": "wide"})
    assert e.value.key == "camera.width" and e.value.line is None
    assert str(e.value).startswith("<overrides>: key 'camera.width': ")
    assert "integer" in str(e.value)


def test_wrong_type_in_a_dict_names_the_dict_path():
    with pytest.raises(seasim.SceneError) as e:
        seasim.Scene.from_dict({"camera": {"width": "wide"}, "water": {"jerlov": "IB"}})
    assert e.value.key == "camera.width" and e.value.file is None
    assert str(e.value).startswith("<dict>: key 'camera.width': ")


def test_unknown_key_in_a_dict_names_the_dict_path():
    with pytest.raises(seasim.SceneError) as e:
        seasim.Scene.from_dict({"camera": {"widht": 64}, "water": {"jerlov": "IB"}})
    assert e.value.key == "camera.widht"
    assert "<dict>: key 'camera.widht'" in str(e.value)


def test_a_value_no_scene_file_can_hold_is_a_type_error_with_its_path():
    with pytest.raises(TypeError, match=r"<dict>: key 'camera.position\[1\]': .* not NoneType"):
        seasim.Scene.from_dict({"camera": {"position": [0.0, None, 0.0]}})
    with pytest.raises(TypeError, match="dict of sections"):
        seasim.Scene.from_dict("flat_sea.toml")


def test_missing_file_is_file_not_found_with_the_path(tmp_path):
    missing = tmp_path / "nowhere.toml"
    with pytest.raises(FileNotFoundError, match=f"scene file not found: {missing}"):
        seasim.Scene.load(missing)
