"""Issue 27: the package checks its interpreter at import and says which
python3 to use; Ctrl-C inside a long step() ends it within a solver
iteration and leaves the scene usable."""
import os
import signal
import subprocess
import sys

import numpy as np
import pytest

import reeve
from conftest import PROMPT_S, endless, interrupt_latency
from reeve import _runtime


def test_an_interpreter_without_numpy_is_told_which_python3_to_use_at_import():
    # numpy blocked as a pyenv python3 without it would lack it.
    code = "import sys; sys.modules['numpy'] = None; import reeve"
    done = subprocess.run([sys.executable, "-c", code], capture_output=True, text=True, env=os.environ)
    assert done.returncode == 1
    last = done.stderr.strip().splitlines()[-1]
    assert last.startswith("ImportError: reeve needs numpy, which this Python (" + sys.executable), done.stderr
    assert "run it with " + _runtime.BUILT_FOR in last
    assert "ModuleNotFoundError" not in done.stderr


def test_another_python_version_is_refused_before_the_compiled_module_is_loaded():
    other = (_runtime.BUILT_FOR_VERSION[0], _runtime.BUILT_FOR_VERSION[1] + 1, 0)
    with pytest.raises(ImportError) as caught:
        _runtime.check(version_info=other, executable="/opt/other/bin/python3", has_numpy=True)
    message = str(caught.value)
    assert "reeve was built for Python %d.%d (%s)" % (*_runtime.BUILT_FOR_VERSION, _runtime.BUILT_FOR) in message
    assert "this is Python %d.%d (/opt/other/bin/python3)" % other[:2] in message
    _runtime.check()  # this interpreter passes


def test_ctrl_c_inside_a_long_frame_raises_keyboard_interrupt_and_leaves_the_scene_usable(scenes):
    scene = reeve.load(scenes / "atwood.json")
    endless(scene)
    latency = interrupt_latency(lambda: scene.step(1))
    assert latency < PROMPT_S, latency
    stopped = scene.time_s
    assert 0.0 < stopped < 1.0 / 60.0  # inside the first frame, at a substep's end
    assert np.isclose(stopped * 100000 * 60.0, round(stopped * 100000 * 60.0), atol=1e-6)
    # Usable: it steps on from there, and Python's own handler is back.
    scene.settings.substeps = 10
    scene.settings.iterations = 2
    scene.step(6)
    assert np.isclose(scene.time_s, stopped + 0.1)
    assert np.all(np.isfinite(scene.bodies.positions_m))
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
