"""Scene.render and reeve.run: the command line's images and files."""
import filecmp
import json
import os
import pathlib
import subprocess

import numpy as np
import pytest

import reeve


def test_render_returns_an_image_of_the_scene(scenes):
    scene = reeve.load(scenes / "atwood.json")
    image = scene.render(320, 240)
    assert image.shape == (240, 320, 3) and image.dtype == np.uint8
    # Not blank: a background, shaded bodies and a dark cable.
    colours = np.unique(image.reshape(-1, 3), axis=0)
    assert len(colours) > 50
    assert image.min() < 60 and image.max() > 180
    # It follows the state: the boxes move, the picture changes.
    scene.step(30)
    assert np.count_nonzero(np.any(scene.render(320, 240) != image, axis=2)) > 100
    with pytest.raises(ValueError, match="positive width and height"):
        scene.render(0, 240)


def test_run_writes_what_reeve_run_writes(scenes, tmp_path):
    scene = reeve.load(scenes / "atwood.json")
    result = reeve.run(scene, frames=20, csv=tmp_path / "py.csv", events=tmp_path / "py_events.csv")
    assert result["frames"] == 20 and result["physics_ms_per_frame"] > 0.0
    assert scene.time_s == pytest.approx(20 / 60, rel=1e-12)
    cli = subprocess.run([os.environ["REEVE_BINARY"], "run", str(scenes / "atwood.json"), "--frames", "20",
                          "--csv", str(tmp_path / "cli.csv")], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert filecmp.cmp(tmp_path / "py.csv", tmp_path / "cli.csv", shallow=False)
    with pytest.raises(FileExistsError, match="exists"):
        reeve.run(reeve.load(scenes / "atwood.json"), frames=1, csv=tmp_path / "py.csv")
    with pytest.raises(ValueError, match="same file"):
        reeve.run(reeve.load(scenes / "atwood.json"), frames=1, csv=tmp_path / "a.csv", events=tmp_path / "a.csv")


def test_run_writes_png_frames(scenes, tmp_path):
    scene = reeve.load(scenes / "atwood.json")
    reeve.run(scene, frames=2, png_dir=tmp_path / "frames", width=160, height=120)
    assert sorted(p.name for p in (tmp_path / "frames").iterdir()) == ["frame_00000.png", "frame_00001.png"]


def test_run_writes_the_replay_reeve_run_writes(scenes, tmp_path):
    # The same run from Python and the command line: the same page, byte
    # for byte (tests/viewer plays it in a browser).
    reeve.run(reeve.load(scenes / "atwood.json"), frames=10, html=tmp_path / "py.html")
    cli = subprocess.run([os.environ["REEVE_BINARY"], "run", str(scenes / "atwood.json"), "--frames", "10",
                          "--html", str(tmp_path / "cli.html")], capture_output=True, text=True)
    assert cli.returncode == 0, cli.stderr
    assert filecmp.cmp(tmp_path / "py.html", tmp_path / "cli.html", shallow=False)
    page = (tmp_path / "py.html").read_text()
    assert "<title>Reeve replay: atwood</title>" in page and '"t":[0,' in page
    with pytest.raises(FileExistsError, match="exists"):
        reeve.run(reeve.load(scenes / "atwood.json"), frames=1, html=tmp_path / "py.html")
    with pytest.raises(ValueError, match="same file"):
        reeve.run(reeve.load(scenes / "atwood.json"), frames=1, csv=tmp_path / "b.html", html=tmp_path / "b.html")


def test_a_replay_keeps_a_scenes_own_markup_as_text(scenes, tmp_path):
    # Words in a scene that would end the page's data script or comment
    # it out, or that look like the template's marks, stay data.
    doc = json.loads((scenes / "atwood.json").read_text())
    doc["name"] = "a<b>&/*REEVE_DATA*/"
    doc["description"] = "</script><!-- <script> /*REEVE_VIEWER*/"
    reeve.run(reeve.load(doc), frames=2, html=tmp_path / "m.html")
    page = (tmp_path / "m.html").read_text()
    assert "<title>Reeve replay: a&lt;b&gt;&amp;/*REEVE_DATA*/</title>" in page
    data = page.split('<script id="reeve-data" type="application/json">', 1)[1].split("</script>", 1)[0]
    replay = json.loads(data)
    assert replay["name"] == doc["name"] and replay["description"] == doc["description"]
    assert len(replay["frames"]["t"]) == 3 and page.count("</script>") == 3


def test_a_replay_without_the_viewer_says_how_to_install_it(scenes, tmp_path, monkeypatch):
    monkeypatch.setenv("REEVE_VIEWER_DIR", str(tmp_path / "nowhere"))
    with pytest.raises(FileNotFoundError, match="tools/setup.sh"):
        reeve.run(reeve.load(scenes / "atwood.json"), frames=1, html=tmp_path / "r.html")
    assert not (tmp_path / "r.html").exists()


def test_a_run_that_breaks_raises_simulation_error(tmp_path):
    # gear_1_to_4.json with a hub's rope given no cable to pay out and its
    # weight doubled: the spool runs out, and the run stops as `reeve run`
    # does, leaving no CSV.
    gear = pathlib.Path(__file__).parents[2] / "tests" / "scenes" / "gear_spool_runs_out.json"  # shared with the CLI test
    with pytest.raises(reeve.SimulationError, match="ran out of cable"):
        reeve.run(reeve.load(gear), frames=60, csv=tmp_path / "broken.csv")
    assert not (tmp_path / "broken.csv").exists()
    with pytest.raises(reeve.SimulationError, match="ran out of cable"):
        reeve.load(gear).step(60)


def test_a_span_wound_empty_is_warned_of_and_strict_raises(tmp_path):
    # Issue 28, item 9: a motor hauls a slider along a rail onto a 0.1 m
    # pulley at 0.5 m/s; its 1 m span runs out when the tie point reaches
    # the rim (2 s), which nothing in the model stops: warned of, with the
    # cable, the links and the time; with strict=True a SimulationError.
    scene = pathlib.Path(__file__).parents[2] / "tests" / "scenes" / "span_wound_empty.json"  # shared with the CLI test
    with pytest.warns(RuntimeWarning, match=r"cable 'rope' ran out between 'pulley' \(link 0\) and 'slider' at t = 2\.1"):
        result = reeve.run(reeve.load(scene))
    assert result["spans_run_out"] >= 1
    with pytest.raises(reeve.SimulationError, match="ran out between"):
        reeve.run(reeve.load(scene), csv=tmp_path / "wind.csv", strict=True)
    assert not (tmp_path / "wind.csv").exists()
