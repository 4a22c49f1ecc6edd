import json
import pathlib

import pytest

import reeve


@pytest.fixture
def scenes():
    return reeve.scenes_dir()


@pytest.fixture
def atwood_dict(scenes):
    return json.loads((scenes / "atwood.json").read_text())


# atwood.json: boxes of 1 kg ("light") and 2 kg ("heavy") on a rope over a
# hinged 2 kg solid wheel: a = (m2 - m1) g / (m1 + m2 + M / 2).
G = 9.81


def atwood_acceleration(m1=1.0, m2=2.0, wheel=2.0, push=0.0):
    """Acceleration of the heavy box (m/s^2, down) with `push` N down on the light one."""
    return ((m2 - m1) * G - push) / (m1 + m2 + wheel / 2)
