"""The Atwood machine from Python meets its closed form, at the scene's
settings and at wheel-to-load mass ratios of 1e-6 and 1e6."""
import numpy as np
import pytest

import reeve
from conftest import G, atwood_acceleration


def fall(scene, seconds):
    """The heavy box's acceleration (m/s^2, down) from rest over `seconds`."""
    heavy = scene.bodies.index("heavy")
    y0 = scene.bodies.positions_m[heavy, 1]
    scene.step(round(seconds * scene.settings.frame_rate_hz))
    t = scene.time_s
    return 2.0 * (y0 - scene.bodies.positions_m[heavy, 1]) / t**2


def test_acceleration_and_tensions_meet_the_closed_form(scenes):
    scene = reeve.load(scenes / "atwood.json")
    a = atwood_acceleration()
    assert fall(scene, 0.5) == pytest.approx(a, rel=0.01)
    tensions = scene.cables["rope"].tensions_N
    assert tensions == pytest.approx([1.0 * (G + a), 2.0 * (G - a)], rel=0.01)
    # The cable keeps its length: what the heavy side paid out, the light side took in.
    rope = scene.cables["rope"]
    assert rope.rest_lengths_m.sum() + rope.stored_m.sum() == pytest.approx(rope.total_length_m, rel=1e-12)


@pytest.mark.parametrize("wheel_kg", [2e-6, 2e6])
def test_wheel_to_load_mass_ratios_of_1e_6_and_1e6(atwood_dict, wheel_kg):
    for body in atwood_dict["bodies"]:
        if body["name"] == "wheel":
            body["mass_kg"] = wheel_kg
    atwood_dict["solver"]["substeps"] = 20
    scene = reeve.load(atwood_dict)
    a = atwood_acceleration(wheel=wheel_kg)
    assert fall(scene, 0.5) == pytest.approx(a, rel=0.01)
    assert scene.cables["rope"].tensions_N == pytest.approx([1.0 * (G + a), 2.0 * (G - a)], rel=0.01)


@pytest.mark.parametrize("push_N", [G, 1000.0])
def test_a_push_set_between_steps_enters_the_closed_form(scenes, push_N):
    # G N down on the light box balances the machine; a kilonewton reverses
    # it at 25 g (20 substeps: at the scene's 10 the light box's 250 m/s^2
    # costs 1.7 %).
    scene = reeve.load(scenes / "atwood.json")
    scene.settings.substeps = 20
    scene.bodies.set_applied_force("light", [0.0, -push_N, 0.0])
    assert scene.bodies.applied_forces_N[scene.bodies.index("light")] == pytest.approx([0.0, -push_N, 0.0])
    a = atwood_acceleration(push=push_N)
    got = fall(scene, 0.1)
    assert got == pytest.approx(a, rel=0.01, abs=0.01)
    if a == 0.0:
        assert scene.cables["rope"].tensions_N == pytest.approx([2.0 * G, 2.0 * G], rel=0.01)


def test_gauss_seidel_meets_it_too(scenes):
    scene = reeve.load(scenes / "atwood.json")
    scene.settings.method = "gauss-seidel"
    scene.settings.substeps = 20
    assert fall(scene, 0.5) == pytest.approx(atwood_acceleration(), rel=0.01)
