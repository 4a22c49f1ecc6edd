import json
import os
import pathlib
import signal
import threading
import time

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


def endless(scene):
    """Sets `scene` to frames that take hours: 100000 substeps of 100000 Gauss-Seidel iterations, every one run."""
    scene.settings.substeps = 100000
    scene.settings.iterations = 100000
    scene.settings.method = "gauss-seidel"


# How soon after Ctrl-C an endless frame must end (s). A substep of
# `endless` takes about 30 ms alone, but under CI the two batch workers share
# two cores with a headless Chromium and another test (0.24 s seen); the
# frame itself takes hours, so an interrupt honoured only between frames fails.
PROMPT_S = 1.0


def interrupt_latency(call, after_s=0.5):
    """Sends this process SIGINT after `after_s` and runs `call`, which must raise KeyboardInterrupt; returns
    how long after the signal was sent it did (s)."""
    # Python leaves SIGINT ignored where its parent did (a background job of
    # a script): the signal would never arrive, and an endless call step for
    # hours. Python's own handler, as in a terminal.
    signal.signal(signal.SIGINT, signal.default_int_handler)
    sent = []

    def send():
        sent.append(time.monotonic())  # not the timer's start: its thread may wait for a core
        os.kill(os.getpid(), signal.SIGINT)

    timer = threading.Timer(after_s, send)
    timer.start()
    with pytest.raises(KeyboardInterrupt):
        call()
    latency = time.monotonic() - sent[0]
    timer.join()
    return latency
