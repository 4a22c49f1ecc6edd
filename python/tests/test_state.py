"""State as numpy arrays: shapes, dtypes and units as documented; setting
state between steps has the effect mechanics says."""
import numpy as np
import pytest

import reeve


def test_body_arrays_have_the_documented_shapes_dtypes_and_units(scenes, atwood_dict):
    scene = reeve.load(scenes / "atwood.json")
    b = scene.bodies
    n = len(atwood_dict["bodies"])
    assert len(b) == n
    assert b.names == [body["name"] for body in atwood_dict["bodies"]]
    for name, shape in [("positions_m", (n, 3)), ("orientations", (n, 4)), ("linear_velocities_m_per_s", (n, 3)),
                        ("angular_velocities_rad_per_s", (n, 3)), ("masses_kg", (n,)),
                        ("applied_forces_N", (n, 3)), ("applied_torques_N_m", (n, 3))]:
        array = getattr(b, name)
        assert array.shape == shape, name
        assert array.dtype == np.float64, name
    for k, body in enumerate(atwood_dict["bodies"]):
        assert b.positions_m[k] == pytest.approx(body["position_m"])  # metres, as written
        assert b.masses_kg[k] == pytest.approx(body["mass_kg"])
    assert np.array_equal(b.orientations, np.tile([1.0, 0.0, 0.0, 0.0], (n, 1)))  # w first
    # Copies: writing one changes nothing in the scene.
    positions = b.positions_m
    positions[:] = 7.0
    assert not np.any(b.positions_m == 7.0)


def test_cable_arrays_have_the_documented_shapes(scenes):
    scene = reeve.load(scenes / "atwood.json")
    assert len(scene.cables) == 1 and "rope" in scene.cables and scene.cables.names == ["rope"]
    rope = scene.cables["rope"]
    assert rope.link_types == ["attachment", "rolling", "attachment"]
    assert rope.link_bodies == ["light", "wheel", "heavy"]
    for name, shape in [("tensions_N", (2,)), ("rest_lengths_m", (2,)), ("lengths_m", (2,)), ("stored_m", (3,))]:
        assert getattr(rope, name).shape == shape, name
        assert getattr(rope, name).dtype == np.float64, name
    assert rope.joint_enabled.tolist() == [True, True]
    # Loaded taut: each span's length is its rest length, and the spans are
    # the 2.9 m from each box's top to the wheel's side.
    assert rope.lengths_m == pytest.approx(rope.rest_lengths_m, abs=1e-12)
    assert [c.name for c in scene.cables] == ["rope"]
    assert scene.cables[0].name == scene.cables[-1].name == "rope"
    with pytest.raises(KeyError, match="no cable named 'chain'"):
        scene.cables["chain"]
    with pytest.raises(IndexError):
        scene.cables[1]


def test_a_velocity_set_between_steps_is_a_ballistic_start():
    scene = reeve.load({"name": "throw", "solver": {"substeps": 10},
                        "bodies": [{"name": "ball", "shape": {"type": "sphere", "radius_m": 0.1},
                                    "mass_kg": 1.0, "position_m": [0, 0, 0]}]})
    scene.step(30)
    v = scene.bodies.linear_velocities_m_per_s[0]
    assert v == pytest.approx([0.0, -9.81 * 0.5, 0.0], rel=1e-9)
    scene.bodies.set_linear_velocity("ball", [2.0, 10.0, 0.0])
    y0 = scene.bodies.positions_m[0, 1]
    scene.step(60)  # 1 s
    # (Velocities are differences of positions: rounding, not physics, past 1e-12.)
    assert scene.bodies.linear_velocities_m_per_s[0] == pytest.approx([2.0, 10.0 - 9.81, 0.0], rel=1e-9)
    # Symplectic Euler: y = v t - g t^2 / 2 - g t h / 2 with h the substep.
    h = 1.0 / 600.0
    assert scene.bodies.positions_m[0] == pytest.approx([2.0, y0 + 10.0 - 9.81 / 2 - 9.81 * h / 2, 0.0], rel=1e-9)


def test_spin_torque_and_position_set_between_steps():
    disc = {"name": "disc", "shape": {"type": "cylinder", "radius_m": 0.5, "half_length_m": 0.1},
            "mass_kg": 4.0, "position_m": [0, 0, 0]}
    scene = reeve.load({"name": "top", "solver": {"gravity_m_per_s2": [0, 0, 0]}, "bodies": [disc]})
    inertia = 0.5 * 4.0 * 0.5**2  # about the cylinder's axis (local z)
    scene.bodies.set_applied_torque(0, [0.0, 0.0, 1.0])
    scene.step(60)
    assert scene.bodies.angular_velocities_rad_per_s[0] == pytest.approx([0.0, 0.0, 1.0 / inertia], rel=1e-12)
    scene.bodies.set_applied_torque(0, [0.0, 0.0, 0.0])
    scene.bodies.set_angular_velocity("disc", [0.0, 0.0, 0.0])
    scene.bodies.set_position("disc", [1.0, 2.0, 3.0])
    scene.bodies.set_orientation("disc", [np.cos(0.25), 0.0, 0.0, np.sin(0.25)])  # 0.5 rad about z
    scene.step(1)
    assert scene.bodies.positions_m[0] == pytest.approx([1.0, 2.0, 3.0], abs=1e-15)
    assert scene.bodies.orientations[0] == pytest.approx([np.cos(0.25), 0.0, 0.0, np.sin(0.25)], abs=1e-15)


def test_bad_state_is_refused_by_name(scenes):
    scene = reeve.load(scenes / "pinhole.json")
    static = int(np.flatnonzero(scene.bodies.static)[0])
    with pytest.raises(ValueError, match="is static"):
        scene.bodies.set_linear_velocity(static, [1.0, 0.0, 0.0])
    with pytest.raises(KeyError, match="no body named 'nobody'"):
        scene.bodies.set_position("nobody", [0.0, 0.0, 0.0])
    with pytest.raises(IndexError, match="out of range"):
        scene.bodies.set_position(len(scene.bodies), [0.0, 0.0, 0.0])
    with pytest.raises(ValueError, match="finite"):
        scene.bodies.set_position(0, [0.0, float("nan"), 0.0])
    with pytest.raises(ValueError, match="unit quaternion"):
        scene.bodies.set_orientation(0, [1.0, 1.0, 0.0, 0.0])


def test_settings_are_writable_within_the_schema_ranges(scenes):
    scene = reeve.load(scenes / "atwood.json")
    s = scene.settings
    assert (s.substeps, s.iterations, s.frame_rate_hz, s.method) == (10, 2, 60.0, "direct")
    s.substeps, s.iterations, s.frame_rate_hz, s.method = 40, 1, 120.0, "gauss-seidel"
    assert (scene.settings.substeps, scene.settings.iterations, scene.settings.frame_rate_hz,
            scene.settings.method) == (40, 1, 120.0, "gauss-seidel")
    scene.step(12)
    assert scene.time_s == pytest.approx(0.1, rel=1e-12)
    assert s.projection == "end"
    s.projection = "start"
    assert scene.settings.projection == "start"
    assert s.threads == 1
    s.threads = 2
    assert scene.settings.threads == 2
    for name, bad in [("substeps", 0), ("substeps", 100001), ("iterations", 0), ("iterations", 100001),
                      ("frame_rate_hz", 0.0), ("frame_rate_hz", 2e6), ("method", "jacobi"),
                      ("projection", "middle"), ("threads", 0), ("threads", 1025)]:
        with pytest.raises(ValueError, match=name):
            setattr(scene.settings, name, bad)


def test_drive_targets_set_between_steps_drive_hinges_and_slides(scenes):
    scene = reeve.load(scenes / "joints.json")
    hinges, joints = scene.hinges, scene.joints
    assert len(hinges) == 2 and joints.types == ["prismatic", "spherical", "fixed"]
    assert hinges.bodies[0] == ("wheel", "world")
    assert hinges.drive_targets.tolist() == [6.0, 0.8]
    # The wheel (solid cylinder 5 kg, r 0.4 m: I = 0.4 kg m^2) on a motor of
    # at most 2 N m, sent backwards: it spins up at 5 rad/s^2 to -3 rad/s.
    hinges.set_drive_target(0, -3.0)
    hinges.set_drive_target(1, -0.5)  # the arm's servo, rad
    joints.set_drive_target(0, -0.4)  # the carriage, m/s down its rail
    wheel = scene.bodies.index("wheel")
    scene.step(18)  # 0.3 s
    assert scene.bodies.angular_velocities_rad_per_s[wheel, 2] == pytest.approx(-1.5, rel=0.01)
    assert hinges.drive_torques_N_m[0] == pytest.approx(-2.0, rel=0.01)
    scene.step(42)  # 1 s
    assert scene.bodies.angular_velocities_rad_per_s[wheel, 2] == pytest.approx(-3.0, rel=1e-3)
    assert hinges.angles_rad[1] == pytest.approx(-0.5, abs=1e-3)
    axis = np.array([0.9396926207859084, 0.3420201433256687, 0.0])
    carriage = scene.bodies.index("carriage")
    assert scene.bodies.linear_velocities_m_per_s[carriage] @ axis == pytest.approx(-0.4, rel=1e-3)
    for array in (hinges.forces_N, hinges.torques_N_m, joints.forces_N, joints.torques_N_m):
        assert array.shape[1] == 3 and np.all(np.isfinite(array))
    with pytest.raises(ValueError, match="only prismatic joints have drives"):
        joints.set_drive_target(1, 0.0)
    with pytest.raises(IndexError):
        hinges.set_drive_target(2, 0.0)


def test_a_drive_schedule_ramps_a_wheel_and_its_angle_counts_whole_turns(scenes):
    # joints.json's wheel (I = 0.4 kg m^2, motor of at most 2 N m: 5 rad/s^2)
    # ramped from rest to 2 rad/s over 1 s, then held: it turns 1 rad in the
    # ramp and 2 rad a second after, 7 rad by 4 s: past a whole turn, where
    # an angle in (-pi, pi] would read 0.72.
    scene = reeve.load(scenes / "joints.json")
    hinges = scene.hinges
    hinges.set_drive_schedule(0, [(0.0, 0.0), (1.0, 2.0)])
    wheel = scene.bodies.index("wheel")
    scene.step(60)
    h = 1.0 / (60 * scene.settings.substeps)
    assert scene.bodies.angular_velocities_rad_per_s[wheel, 2] == pytest.approx(2.0 * (1.0 - h / 2), rel=1e-6)
    assert hinges.drive_targets[0] == pytest.approx(2.0 * (1.0 - h / 2))
    assert hinges.drive_torques_N_m[0] == pytest.approx(0.4 * 2.0, rel=1e-3)  # I alpha
    scene.step(180)
    assert hinges.angles_rad[0] == pytest.approx(7.0, abs=1e-6)
    hinges.set_drive_target(0, 0.0)  # the schedule ends: the motor brakes at 5 rad/s^2
    scene.step(30)
    assert scene.bodies.angular_velocities_rad_per_s[wheel, 2] == pytest.approx(0.0, abs=1e-9)
    with pytest.raises(ValueError, match="after the previous keyframe's 1.0 s"):
        hinges.set_drive_schedule(0, [(0.0, 0.0), (1.0, 2.0), (1.0, 3.0)])
    with pytest.raises(ValueError, match="at least one"):
        hinges.set_drive_schedule(0, [])
    with pytest.raises(ValueError, match="finite"):
        hinges.set_drive_schedule(0, [(0.0, float("nan"))])


def test_slip_speeds_and_slipping_follow_the_cable_over_a_frictionless_drum(scenes):
    # capstan.json's ideal pulley: 1 kg and 1.2 kg over a drum with mu 0, so
    # the cable slides over it at the boxes' speed, forward (towards the
    # heavy box, link 2); the bollard's rope sticks.
    scene = reeve.load(scenes / "capstan.json")
    scene.step(30)
    ideal = scene.cables["ideal_rope"]
    slip = ideal.slip_speeds_m_per_s
    assert slip.shape == (3,) and slip.dtype == np.float64
    heavy = scene.bodies.names.index("ideal_heavy")
    speed = -scene.bodies.linear_velocities_m_per_s[heavy][1]
    assert speed == pytest.approx(9.81 * 0.2 / 2.2 * scene.time_s, rel=1e-3)
    # Measured as each substep starts, over the one before it.
    h = 1.0 / (scene.settings.frame_rate_hz * scene.settings.substeps)
    assert slip[1] == pytest.approx(9.81 * 0.2 / 2.2 * (scene.time_s - h), rel=1e-3)
    assert slip[0] == 0.0 and slip[2] == 0.0
    assert list(ideal.slipping) == [False, True, False]
    bollard = scene.cables["bollard_rope"]
    assert list(bollard.slipping) == [False, False, False]
    assert bollard.slip_speeds_m_per_s[1] == 0.0
