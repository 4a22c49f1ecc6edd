"""reeve.load: from a file, JSON text or a dict, the same scene; bad input
raises SceneError with the command line's message and its parts."""
import json
import os
import subprocess

import numpy as np
import pytest

import reeve


def trajectory(scene, frames=30):
    scene.step(frames)
    return scene.bodies.positions_m, scene.cables["rope"].tensions_N


def test_a_dict_json_text_and_the_file_are_the_same_scene_bit_for_bit(scenes, atwood_dict):
    path = scenes / "atwood.json"
    from_file = trajectory(reeve.load(path))
    for other in (reeve.load(str(path)), reeve.load(atwood_dict), reeve.load(path.read_text())):
        positions, tensions = trajectory(other)
        assert np.array_equal(positions, from_file[0])
        assert np.array_equal(tensions, from_file[1])
    assert reeve.load(atwood_dict).source == "<dict>"
    assert reeve.load(path).source == str(path)


def test_numpy_values_in_a_dict_are_their_numbers(atwood_dict, scenes):
    for body in atwood_dict["bodies"]:
        body["position_m"] = np.array(body["position_m"], dtype=np.float64)
        body["mass_kg"] = np.float64(body["mass_kg"])
    assert np.array_equal(trajectory(reeve.load(atwood_dict))[0], trajectory(reeve.load(scenes / "atwood.json"))[0])


def test_bad_input_raises_scene_error_with_the_json_path(atwood_dict):
    atwood_dict["bodies"][0]["shape"]["radius_m"] = -0.3
    with pytest.raises(reeve.SceneError) as caught:
        reeve.load(atwood_dict)
    e = caught.value
    assert isinstance(e, ValueError)
    assert str(e) == "<dict>: /bodies/0/shape/radius_m: expected a number > 0, got -0.3"
    assert (e.file, e.json_path, e.expected, e.found) == ("<dict>", "/bodies/0/shape/radius_m", "a number > 0", "-0.3")


def test_the_message_is_the_command_line_s(tmp_path, atwood_dict):
    atwood_dict["cables"][0]["links"][1]["body"] = "sprocket"
    bad = tmp_path / "bad.json"
    bad.write_text(json.dumps(atwood_dict))
    with pytest.raises(reeve.SceneError) as caught:
        reeve.load(bad)
    assert caught.value.json_path == "/cables/0/links/1/body"
    cli = subprocess.run([os.environ["REEVE_BINARY"], "validate", str(bad)], capture_output=True, text=True)
    assert cli.returncode == 2
    assert cli.stderr.strip() == "reeve: " + str(caught.value)


def test_syntax_errors_missing_files_and_other_kinds():
    with pytest.raises(reeve.SceneError) as caught:
        reeve.load('{"name": "x",\n "solver": {}, }')
    assert (caught.value.file, caught.value.line) == ("<text>", 2)
    with pytest.raises(reeve.SceneError, match="no/such/scene.json: cannot read"):
        reeve.load("no/such/scene.json")
    with pytest.raises(reeve.SceneError, match="<dict>: expected a JSON document .*not JSON compliant"):
        reeve.load({"name": "x", "solver": {}, "bodies": [], "duration_s": float("nan")})
    with pytest.raises(reeve.SceneError, match="<dict>: expected a JSON document .*type set"):
        reeve.load({"name": "x", "solver": {}, "bodies": {1, 2}})
    with pytest.raises(TypeError, match="expected a path, JSON text or a dict, got int"):
        reeve.load(42)


def test_the_schema_key_is_accepted_and_the_schema_is_there(scenes):
    scene = reeve.load(scenes / "simple.json")  # names "$schema": "scene.schema.json"
    assert scene.name == "simple"
    schema = json.loads(reeve.scene_schema_json())
    assert schema["$id"].endswith("/scene.schema.json")
    assert json.loads(reeve.default_scene_json())["name"] == "simple"
    assert (reeve.scenes_dir() / "scene.schema.json").is_file()
