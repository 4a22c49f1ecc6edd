"""The energy ledger from Python (issue 28): Scene.energy() against the
Atwood machine's closed form, and step() warning of energy created."""
import json
import warnings

import pytest

import reeve
from conftest import G, atwood_acceleration


def test_the_atwood_machine_trades_potential_for_kinetic_energy(scenes):
    scene = reeve.load(scenes / "atwood.json")
    start = scene.energy()
    assert start["kinetic_J"] == 0.0 and start["residual_J"] == 0.0
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # a warning of energy created would fail here
        scene.step(60)
    e = scene.energy()
    v = atwood_acceleration() * scene.time_s
    assert e["kinetic_J"] == pytest.approx(0.5 * (1.0 + 2.0 + 2.0 / 2) * v * v, rel=1e-3)
    # The heavy box fell as far as the light one rose: (2 - 1) kg x g x that,
    # a t^2 (1 + 1/n) / 2 after n substeps of symplectic Euler.
    n = 60 * scene.settings.substeps
    fell = 0.5 * atwood_acceleration() * scene.time_s**2 * (1.0 + 1.0 / n)
    assert e["potential_J"] - start["potential_J"] == pytest.approx(-1.0 * G * fell, rel=1e-3)
    assert e["total_J"] == pytest.approx(e["kinetic_J"] + e["potential_J"] + e["elastic_J"])
    assert e["work_J"] == 0.0 and e["dissipated_J"] == 0.0
    # Uniformly accelerated, symplectic Euler loses K / n in n substeps.
    assert e["residual_J"] == pytest.approx(-e["kinetic_J"] / n, rel=1e-3)


def test_step_warns_where_a_frame_created_energy(scenes):
    # Gauss-Seidel at one substep and one sweep on the stiff trapezoidal
    # springs (DESIGN, "Energy ledger": a listed defect).
    scene = reeve.load(scenes / "springs.json")
    scene.settings.method = "gauss-seidel"
    scene.settings.substeps = 1
    scene.settings.iterations = 1
    with pytest.warns(RuntimeWarning, match="energy created at t = "):
        scene.step(60)
    assert scene.energy()["residual_J"] > 0.0



def test_a_kinematic_wheel_hauls_and_pays_out_and_the_ledger_counts_its_work(atwood_dict):
    # atwood.json's wheel (r = 0.3 m) made kinematic, turning at 0.4 rad/s
    # counter-clockwise: the rope, which cannot slip, hauls the heavy box
    # (2 kg, right) up at r w = 0.12 m/s and pays the light one (1 kg, left)
    # out as fast, whatever their weights. The wheel's work on each side is
    # m g times its rise plus m v^2 (the heavy box's jerk to v; the light
    # box falls free until the rope catches it at 2 v): 1.2204 J in 1 s.
    d = atwood_dict
    wheel = d["bodies"][0]
    del wheel["mass_kg"]
    wheel["motion"] = [{"t_s": 0, "angular_velocity_rad_per_s": [0, 0, 0.4]}]
    scene = reeve.load(d)
    assert scene.bodies.kinematic.tolist() == [True, False, False]
    with warnings.catch_warnings():
        warnings.simplefilter("error")  # no energy created
        scene.step(60)
    v = 0.3 * 0.4
    assert scene.bodies.positions_m[2, 1] == pytest.approx(-3.5 + v, abs=1e-9)
    assert scene.bodies.positions_m[1, 1] == pytest.approx(-3.5 - v, abs=1e-9)
    e = scene.energy()
    assert e["kinematic_work_J"] == pytest.approx(2.0 * G * v + 2.0 * v * v - 1.0 * G * v + 1.0 * v * v, rel=1e-6)
    assert e["residual_J"] <= 1e-9
    with pytest.raises(ValueError, match="kinematic"):
        scene.bodies.set_angular_velocity(0, [0, 0, 1])


def test_a_damped_cable_credits_what_its_swing_lost(scenes):
    # The light weight of elastic.json (1 kg on 0.01 m/N) swings on its
    # cable damped with 4 N s/m instead of by air drag: released at the rest
    # length it settles m g / k lower, having lost m g x / 2 = (m g)^2 k^-1
    # / 2. The ledger credits that but for implicit Euler's own share, about
    # h k / m / (b / m + h k / m) = 4 % at 10 substeps of 60 Hz.
    scene_dict = json.loads((scenes / "elastic.json").read_text())
    del scene_dict["bodies"][2]["linear_damping_per_s"]
    scene_dict["cables"][0]["damping_N_s_per_m"] = 4.0
    scene = reeve.load(scene_dict)
    scene.step(480)
    lost = 0.5 * (1.0 * G) ** 2 * 0.01
    e = scene.energy()
    assert e["cable_damping_J"] <= lost
    assert e["cable_damping_J"] == pytest.approx(lost * (1.0 - 0.04), rel=0.01)
    assert e["residual_J"] <= 0.0
