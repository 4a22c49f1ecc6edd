"""The Simple scene (paper Fig. 12, left) and its cable tensions over time, plotted to a PNG.

    PYTHONPATH=build/python python3 examples/plot_tensions.py [-o simple_tensions.png] [--seconds 5]
"""
import argparse

import matplotlib

matplotlib.use("Agg")  # files only: no display needed
import matplotlib.pyplot as plt
import numpy as np

import reeve


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("-o", "--output", default="simple_tensions.png", help="PNG to write")
    parser.add_argument("--seconds", type=float, default=5.0, help="simulated time (s)")
    args = parser.parse_args()

    scene = reeve.load(reeve.scenes_dir() / "simple.json")
    cable = scene.cables["cable"]
    times, tensions = [], []
    for _ in range(round(args.seconds * scene.settings.frame_rate_hz)):
        scene.step()
        times.append(scene.time_s)
        tensions.append(cable.tensions_N)
    tensions = np.array(tensions)  # (frames, joints)

    fig, ax = plt.subplots(figsize=(8, 4.5), dpi=100)
    for j in range(tensions.shape[1]):
        a, b = cable.link_bodies[j], cable.link_bodies[j + 1]
        ax.plot(times, tensions[:, j], label=f"joint {j}: {a} - {b}")
    ax.set_xlabel("time (s)")
    ax.set_ylabel("tension (N)")
    ax.set_title(f"{scene.name}: cable joint tensions ({scene.settings.substeps} substeps x "
                 f"{scene.settings.iterations} iterations)")
    ax.legend()
    ax.grid(alpha=0.3)
    fig.tight_layout()
    fig.savefig(args.output)
    print(f"{args.output}: {tensions.shape[1]} joints over {times[-1]:.2f} s; "
          f"mean tensions {np.round(tensions.mean(axis=0), 3).tolist()} N")


if __name__ == "__main__":
    main()
