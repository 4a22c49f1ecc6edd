"""A controller between steps: a motor holds a load at a height through a winch.

A 5 kg load hangs from cable wound on a drum of radius 0.1 m, hinged to the
world and turned by a velocity drive (a motor of at most 50 N m). Each frame
a proportional controller reads the load's height and sets the motor's
target speed, so the load rises from -3 m to the target and stays there;
the motor then holds it with the torque m g r.

    PYTHONPATH=build/python python3 examples/winch_controller.py [--target -2.0] [--seconds 4]
"""
import argparse

import reeve

LOAD_KG, DRUM_RADIUS_M, G = 5.0, 0.1, 9.81

WINCH = {
    "name": "winch",
    "description": "A 5 kg load on a cable from a motor-driven drum (examples/winch_controller.py).",
    "solver": {"frame_rate_hz": 60, "substeps": 20, "iterations": 4},
    "bodies": [
        {"name": "drum", "shape": {"type": "cylinder", "radius_m": DRUM_RADIUS_M, "half_length_m": 0.05},
         "mass_kg": 2.0, "position_m": [0, 0, 0]},
        {"name": "load", "shape": {"type": "box", "half_extents_m": [0.1, 0.1, 0.1]},
         "mass_kg": LOAD_KG, "position_m": [DRUM_RADIUS_M, -3.0, 0]},
    ],
    "hinges": [{"body": "drum", "anchor_m": [0, 0, 0], "axis": [0, 0, 1],
                "drive": {"mode": "velocity", "target_rad_per_s": 0.0, "max_torque_N_m": 50.0}}],
    "cables": [{"name": "winch", "links": [
        {"body": "drum", "type": "hybrid", "orientation": "cw", "stored_m": 10.0},
        {"body": "load", "type": "attachment", "point_m": [0, 0.1, 0]}]}],
    "camera": {"eye_m": [0, -1.5, 6], "target_m": [0, -1.5, 0]},
}


def hold(target_m, seconds, gain_per_s=4.0, max_speed_m_per_s=1.0, report=print):
    """Runs the controlled winch; returns the scene at the end."""
    scene = reeve.load(WINCH)
    load = scene.bodies.index("load")
    for frame in range(round(seconds * scene.settings.frame_rate_hz)):
        error_m = target_m - scene.bodies.positions_m[load, 1]
        # The cable leaves the drum's right side going down: turning the
        # drum counter-clockwise (+z) hauls it in at omega r.
        speed = max(-max_speed_m_per_s, min(max_speed_m_per_s, gain_per_s * error_m))
        scene.hinges.set_drive_target(0, speed / DRUM_RADIUS_M)
        scene.step()
        if report and (frame + 1) % 30 == 0:
            report(f"t = {scene.time_s:4.1f} s  height {scene.bodies.positions_m[load, 1]:+.4f} m  "
                   f"motor {scene.hinges.drive_torques_N_m[0]:+7.3f} N m  "
                   f"tension {scene.cables['winch'].tensions_N[0]:7.3f} N")
    return scene


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--target", type=float, default=-2.0, help="height to hold the load at (m)")
    parser.add_argument("--seconds", type=float, default=4.0, help="simulated time (s)")
    args = parser.parse_args()
    scene = hold(args.target, args.seconds)
    height = scene.bodies.positions_m[scene.bodies.index("load"), 1]
    print(f"held at {height:+.4f} m (target {args.target:+.4f} m); motor "
          f"{scene.hinges.drive_torques_N_m[0]:+.3f} N m against m g r = {LOAD_KG * G * DRUM_RADIUS_M:.3f} N m")


if __name__ == "__main__":
    main()
