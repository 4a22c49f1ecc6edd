"""A learning loop over many copies of a machine, stepped side by side with reeve.Batch.

Each generation tries one candidate controller per copy: the batch steps all
copies one frame at a time (on every core, the GIL released), numpy computes
every copy's action from the batch's arrays, and the best candidates seed the
next generation (the cross-entropy method). Two machines:

* atwood.json: learn a push on the light box (a constant and PD gains) that
  holds the heavy box at a height. Held still, the push must be (m2 - m1) g.
* hand.json: learn the extra pull on the index finger's tendon weight that
  curls its first joint (MCP) to a target angle (it hangs at 0.78 rad; 5 N
  more takes it to its 1.3 rad limit).

    /usr/bin/python3 examples/batch_control.py [--copies 64] [--generations 8]
"""
import argparse
import os
import time

import numpy as np

import reeve

G = 9.81


def cross_entropy(score, mean, spread, copies, generations, elite=8, seed=1):
    """Maximises score(candidates (copies, k)) -> (copies,) by the cross-entropy method; returns the best mean."""
    rng = np.random.default_rng(seed)
    mean, spread = np.asarray(mean, float), np.asarray(spread, float)
    for _ in range(generations):
        candidates = mean + spread * rng.standard_normal((copies, mean.size))
        best = candidates[np.argsort(score(candidates))[-elite:]]
        mean, spread = best.mean(axis=0), best.std(axis=0) + 1e-3 * np.abs(mean)
    return mean


def atwood_hold(gains, target_drop_m=0.3, seconds=1.5, threads=None):
    """Each copy of atwood.json, its light box pushed down by P = p0 - kp e - kd v, gains[i] = (p0 N, kp N/m,
    kd N s/m), e and v the heavy box's height above a target `target_drop_m` below where it starts and its
    speed up. Returns (batch, squared error summed over the frames)."""
    batch = reeve.Batch(reeve.scenes_dir() / "atwood.json", copies=len(gains), threads=threads)
    first = batch.scenes[0].bodies
    light, heavy = first.index("light"), first.index("heavy")
    target = batch.positions_m[:, heavy, 1] - target_drop_m
    forces = np.zeros(batch.positions_m.shape)
    cost = np.zeros(len(gains))
    for _ in range(round(seconds * batch.scenes[0].settings.frame_rate_hz)):
        error = batch.positions_m[:, heavy, 1] - target  # > 0: the heavy box is too high
        speed = batch.linear_velocities_m_per_s[:, heavy, 1]
        forces[:, light, 1] = -(gains[:, 0] - gains[:, 1] * error - gains[:, 2] * speed)  # down on light: heavy up
        batch.set_applied_forces(forces)
        batch.step()
        cost += error**2
    return batch, cost


def hand_curl(pulls, target_rad=1.0, seconds=1.0, threads=None):
    """Each copy of hand.json with pulls[i, 0] N more on the index finger's tendon weight. Returns (batch, the
    index MCP's angle error at the end)."""
    batch = reeve.Batch(reeve.scenes_dir() / "hand.json", copies=len(pulls), threads=threads)
    scene = batch.scenes[0]
    weight = scene.bodies.index("index_weight")
    mcp = [k for k, (body, other) in enumerate(scene.hinges.bodies) if body == "index_1"][0]
    forces = np.zeros(batch.positions_m.shape)
    forces[:, weight, 1] = -np.clip(pulls[:, 0], 0.0, 50.0)  # down: the weight pulls the flexor
    batch.set_applied_forces(forces)
    batch.step(round(seconds * scene.settings.frame_rate_hz))
    return batch, batch.hinge_angles_rad[:, mcp] - target_rad


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--copies", type=int, default=64)
    parser.add_argument("--generations", type=int, default=8)
    parser.add_argument("--threads", type=int, default=None)
    args = parser.parse_args()

    start = time.perf_counter()
    gains = cross_entropy(lambda g: -atwood_hold(g, threads=args.threads)[1], [5.0, 50.0, 5.0], [5.0, 40.0, 5.0],
                          args.copies, args.generations)
    batch, _ = atwood_hold(np.array([gains]), seconds=10.0, threads=1)
    light = batch.scenes[0].bodies.index("light")
    push = -batch.scenes[0].bodies.applied_forces_N[light, 1]
    threads = min(args.threads or os.cpu_count(), args.copies)
    print(f"atwood: p0 {gains[0]:.2f} N, kp {gains[1]:.1f} N/m, kd {gains[2]:.1f} N s/m hold the load with "
          f"{push:.3f} N ((m2 - m1) g = {G:.3f} N); {args.copies} copies x {args.generations} generations in "
          f"{time.perf_counter() - start:.1f} s on {threads} threads")

    start = time.perf_counter()
    pull = cross_entropy(lambda p: -np.abs(hand_curl(p, threads=args.threads)[1]), [1.0], [2.0], args.copies,
                         max(2, args.generations // 2))
    _, error = hand_curl(np.array([pull]))
    print(f"hand: {pull[0]:.2f} N more on the index flexor curls its MCP to 1.0 rad within {abs(error[0]):.4f} rad "
          f"({time.perf_counter() - start:.1f} s)")


if __name__ == "__main__":
    main()
