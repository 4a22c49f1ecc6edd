"""reeve.sweep on a Dask LocalCluster of 2 workers equals a serial run, and
each result meets the Atwood closed form."""
import copy
import json
import sys

import cloudpickle
import pytest

import reeve
from conftest import atwood_acceleration

# Workers cannot import this test module: send its functions by value.
cloudpickle.register_pickle_by_value(sys.modules[__name__])

ATWOOD = json.loads((reeve.scenes_dir() / "atwood.json").read_text())


def atwood_with_wheel(parameters):
    """atwood.json with the wheel's mass (kg) of this parameter set."""
    wheel_kg, _ = parameters
    doc = copy.deepcopy(ATWOOD)
    next(b for b in doc["bodies"] if b["name"] == "wheel")["mass_kg"] = wheel_kg
    return doc


def heavy_box_acceleration(scene, parameters):
    """The heavy box's acceleration (m/s^2, down) over 0.25 s at the parameter set's substeps."""
    _, substeps = parameters
    scene.settings.substeps = substeps
    heavy = scene.bodies.index("heavy")
    y0 = scene.bodies.positions_m[heavy, 1]
    scene.step(15)
    return 2.0 * (y0 - scene.bodies.positions_m[heavy, 1]) / scene.time_s**2


def test_a_sweep_on_two_workers_equals_the_serial_run():
    grid = [(wheel_kg, substeps) for wheel_kg in (0.5, 2.0, 8.0) for substeps in (10, 40)]
    parallel = reeve.sweep(atwood_with_wheel, grid, heavy_box_acceleration, workers=2)
    serial = [heavy_box_acceleration(reeve.load(atwood_with_wheel(p)), p) for p in grid]
    assert parallel == serial  # bit for bit: Reeve is deterministic
    for (wheel_kg, _), got in zip(grid, parallel):
        assert got == pytest.approx(atwood_acceleration(wheel=wheel_kg), rel=0.01)


def test_an_error_in_a_run_is_raised_here():
    with pytest.raises(reeve.SceneError, match="no/such.json"):
        reeve.sweep("no/such.json", [1], heavy_box_acceleration, workers=1)
