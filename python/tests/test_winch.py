"""Winches from Python: the pull read back, a controller's command taking over
from the scene's schedule, and bad commands refused (scenes/crane.json)."""
import pytest

import reeve

G = 9.81


def test_winch_pull_and_a_command_from_python(scenes):
    scene = reeve.load(scenes / "crane.json")
    hoist = scene.cables["hoist"]
    scene.step(90)  # 1.5 s of hauling at 0.6 m/s: the pull is the load's weight
    assert hoist.winch_pull_N == pytest.approx(500 * G, rel=0.05)
    drum = hoist.stored_m[-1]
    # Pay out at 0.3 m/s from now on, instead of the scene's schedule (the
    # load, rising at 0.6 m/s, flies on slack and is caught with a jerk that
    # stalls the winch: it pays out at least what it was told).
    hoist.command_winch(speed_m_per_s=-0.3)
    scene.step(60)
    assert hoist.stored_m[-1] <= drum - 0.3 + 1e-9
    # Length mode: to 0.8 m on the drum at 0.6 m/s, and holds there.
    hoist.command_winch(stored_m=0.8)
    scene.step(120)
    assert hoist.stored_m[-1] == pytest.approx(0.8, abs=1e-9)


def test_bad_winch_commands_are_refused(scenes):
    scene = reeve.load(scenes / "crane.json")
    hoist = scene.cables["hoist"]
    with pytest.raises(ValueError, match="exactly one"):
        hoist.command_winch()
    with pytest.raises(ValueError, match="exactly one"):
        hoist.command_winch(speed_m_per_s=0.1, stored_m=1.0)
    with pytest.raises(ValueError, match="max_speed"):
        hoist.command_winch(speed_m_per_s=5.0)
    with pytest.raises(ValueError, match="target_stored"):
        hoist.command_winch(stored_m=-1.0)
    atwood = reeve.load(scenes / "atwood.json")
    rope = atwood.cables[0]
    assert rope.winch_pull_N is None
    with pytest.raises(ValueError, match="has no winch"):
        rope.command_winch(speed_m_per_s=0.1)
