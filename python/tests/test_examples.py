"""The examples run and do what they say."""
import pathlib
import runpy
import subprocess
import sys

import pytest

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def test_plot_tensions_writes_a_png(tmp_path):
    out = tmp_path / "tensions.png"
    done = subprocess.run([sys.executable, str(EXAMPLES / "plot_tensions.py"), "-o", str(out), "--seconds", "1"],
                          capture_output=True, text=True)
    assert done.returncode == 0, done.stderr
    assert out.read_bytes()[:8] == b"\x89PNG\r\n\x1a\n"
    assert "4 joints" in done.stdout  # Table 1: Simple has 4 cable joints


def test_the_winch_controller_holds_the_load_with_m_g_r():
    winch = runpy.run_path(str(EXAMPLES / "winch_controller.py"))
    scene = winch["hold"](-2.0, 4.0, report=None)
    load = scene.bodies.index("load")
    assert scene.bodies.positions_m[load, 1] == pytest.approx(-2.0, abs=0.005)
    assert abs(scene.bodies.linear_velocities_m_per_s[load, 1]) < 0.01
    m_g = winch["LOAD_KG"] * winch["G"]
    assert scene.cables["winch"].tensions_N[0] == pytest.approx(m_g, rel=0.01)
    assert abs(scene.hinges.drive_torques_N_m[0]) == pytest.approx(m_g * winch["DRUM_RADIUS_M"], rel=0.01)
