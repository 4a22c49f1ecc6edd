"""Scene.view(): `reeve view` from Python (issue 31)."""
import json
import os
import signal
import struct
import subprocess
import sys
import urllib.request

import pytest

import reeve


def messages(url, count):
    """The first `count` messages of the server's stream: (type, payload)."""
    out = []
    with urllib.request.urlopen(url + "stream", timeout=10) as stream:
        while len(out) < count:
            (n,) = struct.unpack("<I", stream.read(4))
            body = stream.read(n)
            out.append((body[0], body[1:]))
    return out


def test_view_serves_the_scene_with_its_current_settings(scenes):
    scene = reeve.load(scenes / "atwood.json")
    scene.settings.substeps = 7
    scene.settings.method = "gauss-seidel"
    with scene.view(port=0, block=False) as viewer:
        assert viewer.url == f"http://127.0.0.1:{viewer.port}/"
        assert b"/viewer/live.js" in urllib.request.urlopen(viewer.url, timeout=10).read()
        (kind, head), (_, status), (frame_kind, _) = messages(viewer.url, 3)
        assert kind == 2 and json.loads(head)["name"] == "atwood"
        assert json.loads(head)["file"] == str(scenes / "atwood.json")
        settings = json.loads(status)["settings"]
        assert (settings["substeps"], settings["iterations"], settings["solver"]) == (7, 2, "gauss-seidel")
        assert frame_kind == 1
        watching = urllib.request.urlopen(viewer.url + "stream", timeout=10)
        watching.read(4)
    # Leaving the block stopped it: the stream still open ends.
    while watching.read(65536):
        pass
    viewer.stop()  # again: nothing left to stop


def test_view_of_a_dict_names_it(scenes):
    source = json.loads((scenes / "atwood.json").read_text())
    source["name"] = "from a dict"
    with reeve.load(source).view(port=0, block=False) as viewer:
        head = json.loads(messages(viewer.url, 1)[0][1])
        assert (head["name"], head["file"]) == ("from a dict", "<dict>")


def test_view_refuses_a_bad_port_and_a_missing_viewer(scenes, tmp_path, monkeypatch):
    scene = reeve.load(scenes / "atwood.json")
    with pytest.raises(ValueError, match="port"):
        scene.view(port=70000, block=False)
    monkeypatch.setenv("REEVE_VIEWER_DIR", str(tmp_path))
    with pytest.raises(FileNotFoundError, match="tools/setup.sh"):
        scene.view(port=0, block=False)


def test_view_blocks_until_ctrl_c(scenes):
    code = f"import reeve; reeve.load({str(scenes / 'atwood.json')!r}).view(port=0)"
    env = dict(os.environ, PYTHONPATH=os.pathsep.join(sys.path))
    child = subprocess.Popen([sys.executable, "-c", code], stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True,
                             env=env)
    line = child.stdout.readline()
    assert "(Ctrl-C stops)" in line, line
    url = line.split(" at ")[1].split()[0]
    assert urllib.request.urlopen(url, timeout=10).status == 200
    child.send_signal(signal.SIGINT)
    _, err = child.communicate(timeout=10)
    assert "KeyboardInterrupt" in err
