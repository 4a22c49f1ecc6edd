"""reeve.Batch: scenes stepped side by side equal the same scenes stepped alone, bit for bit, on any number of
threads; their arrays carry a leading batch axis; bad input is refused whole."""
import pathlib
import runpy
import signal

import numpy as np
import pytest

import reeve
from conftest import PROMPT_S, atwood_acceleration, endless, interrupt_latency

EXAMPLES = pathlib.Path(__file__).resolve().parents[2] / "examples"


def pushes(n):
    """n different downward pushes (N) on the light box: from -4 N (up) to 8 N."""
    return np.linspace(-4.0, 8.0, n)


def test_copies_with_different_pushes_meet_the_atwood_closed_form_and_equal_serial_runs(scenes):
    n = 64
    batch = reeve.Batch(scenes / "atwood.json", copies=n, threads=2)
    assert len(batch) == n and batch.threads == 2 and len(batch.scenes) == n
    light, heavy = batch.scenes[0].bodies.index("light"), batch.scenes[0].bodies.index("heavy")
    forces = np.zeros(batch.positions_m.shape)
    forces[:, light, 1] = -pushes(n)
    batch.set_applied_forces(forces)
    batch.step(6)
    v0 = batch.linear_velocities_m_per_s[:, heavy, 1]
    batch.step(12)
    assert batch.time_s == pytest.approx(np.full(n, 18 / 60), rel=1e-12)
    a = -(batch.linear_velocities_m_per_s[:, heavy, 1] - v0) / (12 / 60)  # down
    expected = np.array([atwood_acceleration(push=p) for p in pushes(n)])
    assert a == pytest.approx(expected, rel=1e-6, abs=1e-9)
    for k in (0, 17, n - 1):  # alone, the same bits
        alone = reeve.load(scenes / "atwood.json")
        alone.bodies.set_applied_force(light, forces[k, light])
        alone.step(18)
        assert np.array_equal(batch.positions_m[k], alone.bodies.positions_m)
        assert np.array_equal(batch.linear_velocities_m_per_s[k], alone.bodies.linear_velocities_m_per_s)
        assert np.array_equal(batch.orientations[k], alone.bodies.orientations)


@pytest.mark.parametrize("threads", [1, 2, 3])
def test_hand_copies_end_on_the_same_bits_whatever_the_threads(scenes, threads):
    n = 6
    batch = reeve.Batch(scenes / "hand.json", copies=n, threads=threads)
    assert batch.threads == threads
    weight = batch.scenes[0].bodies.index("index_weight")
    forces = np.zeros(batch.positions_m.shape)
    forces[:, weight, 1] = -np.arange(n, dtype=float)  # 0 .. 5 N more on the index flexor
    batch.set_applied_forces(forces)
    batch.step(20)
    alone = reeve.load(scenes / "hand.json")
    alone.bodies.set_applied_force(weight, forces[n - 1, weight])
    alone.step(20)
    assert np.array_equal(batch.positions_m[n - 1], alone.bodies.positions_m)
    assert np.array_equal(batch.angular_velocities_rad_per_s[n - 1], alone.bodies.angular_velocities_rad_per_s)
    assert np.array_equal(batch.hinge_angles_rad[n - 1], alone.hinges.angles_rad)
    # More pull curls the index finger's first joint further (to its 1.3 rad
    # limit, where the copies held there differ by rounding).
    mcp = [k for k, (body, _) in enumerate(alone.hinges.bodies) if body == "index_1"][0]
    assert np.all(np.diff(batch.hinge_angles_rad[:, mcp]) >= -1e-12)
    assert batch.hinge_angles_rad[0, mcp] < batch.hinge_angles_rad[n - 1, mcp]


def test_different_machines_step_together_and_arrays_refuse_mixed_sizes(scenes):
    a, b = reeve.load(scenes / "atwood.json"), reeve.load(scenes / "crane.json")
    batch = reeve.Batch([a, b])
    assert batch.scenes[0] is a and batch.scenes[1] is b
    batch.step(3)
    assert a.time_s == pytest.approx(3 / 60) and b.time_s == pytest.approx(3 / b.settings.frame_rate_hz)
    with pytest.raises(ValueError, match="body counts differ"):
        batch.positions_m
    assert batch.time_s.shape == (2,)


def test_hinge_drive_targets_are_set_per_copy_and_nan_leaves_one(scenes):
    batch = reeve.Batch(scenes / "crane.json", copies=3, threads=2)
    driven = [k for k, t in enumerate(batch.scenes[0].hinges.drive_targets) if not np.isnan(t)]
    assert driven, "crane.json drives a hinge"
    k = driven[0]
    before = batch.scenes[1].hinges.drive_targets[k]
    targets = np.full((3, len(batch.scenes[0].hinges)), np.nan)
    targets[0, k], targets[2, k] = 0.1, -0.2
    batch.set_hinge_drive_targets(targets)
    assert [s.hinges.drive_targets[k] for s in batch.scenes] == [0.1, before, -0.2]
    undriven = [j for j in range(targets.shape[1]) if j not in driven]
    if undriven:
        targets[1, undriven[0]] = 1.0
        with pytest.raises(ValueError, match="has no drive"):
            batch.set_hinge_drive_targets(targets)
        assert batch.scenes[0].hinges.drive_targets[k] == 0.1  # nothing set


def test_ctrl_c_ends_every_scenes_substep_and_leaves_the_batch_usable(scenes):
    batch = reeve.Batch(scenes / "atwood.json", copies=4, threads=2)
    for scene in batch.scenes:
        endless(scene)
    latency = interrupt_latency(lambda: batch.step(1))
    assert latency < PROMPT_S, latency
    stopped = batch.time_s
    assert np.all(stopped < 1.0 / 60.0)  # each inside its first frame, at a substep's end (0 if not begun)
    assert np.allclose(stopped * 6e6, np.round(stopped * 6e6), atol=1e-6)
    for scene in batch.scenes:
        scene.settings.substeps = 10
        scene.settings.iterations = 2
    batch.step(6)
    assert np.allclose(batch.time_s, stopped + 0.1)
    assert np.all(np.isfinite(batch.positions_m))
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_bad_input_is_refused_before_anything_changes(scenes):
    scene = reeve.load(scenes / "atwood.json")
    with pytest.raises(ValueError, match="again"):
        reeve.Batch([scene, scene])
    with pytest.raises(ValueError, match="copies"):
        reeve.Batch([scene], copies=2)
    with pytest.raises(ValueError, match="copies"):
        reeve.Batch(scene, copies=2)
    with pytest.raises(ValueError, match="copies"):
        reeve.Batch(scenes / "atwood.json", copies=0)
    with pytest.raises(ValueError, match="threads"):
        reeve.Batch(scenes / "atwood.json", threads=0)
    with pytest.raises(ValueError, match="at least one"):
        reeve.Batch([])
    with pytest.raises(TypeError, match="reeve.Scene"):
        reeve.Batch([scene, 3])
    with pytest.raises(reeve.SceneError):
        reeve.Batch({"bodies": 3}, copies=2)
    batch = reeve.Batch(scenes / "atwood.json", copies=2)
    with pytest.raises(ValueError, match="frames"):
        batch.step(-1)
    n_bodies = len(batch.scenes[0].bodies)
    with pytest.raises(ValueError, match=r"shape \(2, %d, 3\)" % n_bodies):
        batch.set_applied_forces(np.zeros((3, n_bodies, 3)))
    forces = np.zeros((2, n_bodies, 3))
    forces[1, batch.scenes[0].bodies.index("light"), 1] = -1.0
    forces[0, batch.scenes[0].bodies.index("light"), 0] = np.inf
    with pytest.raises(ValueError, match="finite"):
        batch.set_applied_forces(forces)
    forces[0, batch.scenes[0].bodies.index("light"), 0] = 0.0
    wheel = batch.scenes[0].bodies.index("wheel")
    static = [k for k, s in enumerate(batch.scenes[0].bodies.static) if s]
    if static:
        forces[0, static[0], 1] = 1.0
        with pytest.raises(ValueError, match="static"):
            batch.set_applied_forces(forces)
    assert not batch.scenes[1].bodies.applied_forces_N.any()  # nothing was set
    assert batch.scenes[0].bodies.masses_kg[wheel] > 0.0


def test_the_learning_example_holds_the_atwood_load_with_m_g_and_curls_the_finger():
    example = runpy.run_path(str(EXAMPLES / "batch_control.py"))
    gains = example["cross_entropy"](lambda g: -example["atwood_hold"](g)[1], [5.0, 50.0, 5.0], [5.0, 40.0, 5.0],
                                     copies=16, generations=4)
    batch, _ = example["atwood_hold"](np.array([gains]), seconds=10.0)
    scene = batch.scenes[0]
    light, heavy = scene.bodies.index("light"), scene.bodies.index("heavy")
    # Held still, the push on the light box is what the boxes' weights differ by.
    assert abs(scene.bodies.linear_velocities_m_per_s[heavy, 1]) < 1e-3
    assert -scene.bodies.applied_forces_N[light, 1] == pytest.approx(example["G"] * (2.0 - 1.0), rel=1e-3)
    pull = example["cross_entropy"](lambda p: -np.abs(example["hand_curl"](p)[1]), [1.0], [2.0], copies=16,
                                    generations=4)
    _, error = example["hand_curl"](np.array([pull]))
    assert abs(error[0]) < 0.02
