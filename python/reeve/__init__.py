"""Reeve: cable-driven machines simulated with cable joints.

Reeve is an XPBD rigid-body engine in which each span of cable between two
bodies is one unilateral distance constraint whose ends roll along the
bodies (Mueller et al., "Cable Joints", SCA 2018). This package loads the
same JSON scenes as the `reeve` command line, steps them, and reads and sets
their state as numpy arrays (SI units, named in each attribute)::

    import reeve
    scene = reeve.load("scenes/atwood.json")
    scene.step(60)                                 # one second at 60 Hz
    scene.cables["rope"].tensions_N                # array([11.7..., 14.7...])
    scene.bodies.positions_m[scene.bodies.index("heavy")]

Many copies of a machine (a controller search, a learning loop) step side
by side on threads with reeve.Batch, their state as arrays with a leading
batch axis; reeve.sweep spreads whole runs over Dask workers.

Errors: reeve.SceneError (a ValueError) for a scene that cannot be loaded,
reeve.SimulationError (a RuntimeError) for a run that had to stop.
"""

import json as _json
import os as _os
import pathlib as _pathlib
import warnings as _warnings

from . import _runtime

_runtime.check()  # before the compiled module: a wrong interpreter is told which python3 to use

from ._reeve import (  # noqa: F401  (the public names)
    Batch,
    Bodies,
    Cable,
    Cables,
    Hinges,
    Joints,
    Scene,
    SceneError,
    Settings,
    SimulationError,
    Viewer,
    __version__,
    default_scene_json,
    scene_schema_json,
)
from ._reeve import _SOURCE_SCENES_DIR, _import_mjcf, _load_file, _load_text
from .sweep import sweep  # noqa: F401

__all__ = [
    "Batch", "Bodies", "Cable", "Cables", "Hinges", "Joints", "Scene", "SceneError", "Settings", "SimulationError",
    "Viewer", "default_scene_json", "import_mjcf", "load", "run", "scene_schema_json", "scenes_dir", "sweep",
    "__version__",
]


def load(source):
    """Loads a scene and returns a reeve.Scene ready to step.

    `source` is a path (str or os.PathLike) to a scene file, the JSON text of
    a scene (a str whose first non-blank character is "{"), or a dict as
    json.load() gives (numpy arrays allowed). The scene format is scenes/README.md; the schema is
    reeve.scene_schema_json(). A path ending in .xml is a MuJoCo model, imported as
    import_mjcf(path) does (its pulleys fixed, as MuJoCo's).

    Raises reeve.SceneError (a ValueError) with the message the command line
    prints: the file ("<text>" or "<dict>" when there is none), the JSON
    path, what was expected and what was found, also as its attributes
    file, json_path, expected and found. TypeError for another kind of
    source.
    """
    if isinstance(source, dict):
        try:
            text = _json.dumps(source, allow_nan=False, default=_plain)
        except (TypeError, ValueError) as e:  # NaN or infinity, an object JSON does not have
            raise SceneError(f"<dict>: expected a JSON document (finite numbers, lists, str keys): {e}") from None
        return _load_text(text, "<dict>")
    if isinstance(source, str) and source.lstrip().startswith("{"):
        return _load_text(source, "<text>")
    if isinstance(source, (str, _os.PathLike)):
        path = _os.fspath(source)
        if path.lower().endswith(".xml"):
            return _load_text(_json.dumps(_imported(path, "fixed", {}, stacklevel=3)), path)
        return _load_file(path)
    raise TypeError(f"reeve.load: expected a path, JSON text or a dict, got {type(source).__name__}")


def import_mjcf(path, wheels="fixed", controls=None):
    """Reads a MuJoCo model (MJCF XML) and returns the Reeve scene it makes, as a dict.

    Bodies, joints and spatial tendons are imported; each wrap cylinder a
    tendon runs over becomes a pulley: with wheels="fixed" (the default) a
    frictionless one welded to its body, as MuJoCo's wrap is; with
    wheels="turning" a wheel hinged on its axis with the geom's mass, the
    tendon rolling on it. controls: {actuator name: its control (MuJoCo's
    ctrl)}, held constant while the scene runs (others 0, at rest): motors
    and servos on joints become drives, a motor pulling a tendon a winch,
    a muscle a winch pulling with its control times its peak force, and
    pulley branches a junction of cables. scenes/README.md ("MuJoCo
    models") lists the mapping. What the scene does not carry of the model is given in one
    UserWarning, a line for each element with its file and line. Raises
    reeve.SceneError ("FILE:LINE: <element>: expected ..., got ...") for a
    malformed model or one Reeve cannot build. reeve.load(d) builds the dict.
    """
    return _imported(_os.fspath(path), wheels, dict(controls or {}), stacklevel=3)


def _imported(path, wheels, controls, stacklevel):
    text, unmapped = _import_mjcf(path, wheels, controls)
    if unmapped:
        _warnings.warn(f"reeve: {len(unmapped)} parts of {path} are not imported:\n  " + "\n  ".join(unmapped),
                       stacklevel=stacklevel)
    return _json.loads(text)


def _plain(value):
    # numpy arrays and scalars in a dict scene: their lists and numbers.
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"Object of type {type(value).__name__} is not JSON serializable")


def run(scene, frames=None, csv=None, png_dir=None, video=None, events=None, width=1280, height=720, force=False,
        strict=False, html=None):
    """Steps `scene` and writes what `reeve run` writes, from its current state.

    frames: frames to step (default: the scene's frame_count). csv: a CSV of
    body positions and cable joint state, a row before the first frame and
    one per frame (columns as `reeve run --csv`). png_dir: a folder of
    frame_00000.png, ... png files. video: an .mp4 file (H.264 through the
    ffmpeg program; even width and height). events: the cable events (hybrid
    links running out, merges, splits, breaks, spans wound empty) as JSON
    lines. html: a replay to open in a browser, one self-contained file
    (`reeve run --html`). width, height: image size in pixels. force: replace outputs that
    exist. strict: energy created (the energy ledger, Scene.energy()) or a
    span wound empty is an error, as `reeve run --strict`.

    Each output appears whole at the end, or not at all. Returns a dict:
    frames (done), physics_ms_per_frame, energy_created_frames (frames whose
    ledger showed energy created; each of the first 100 is also warned of,
    RuntimeWarning), spans_run_out (spans a wheel wound empty, its tie
    point at the rim: warned of likewise). Raises FileExistsError for an
    output that exists without force, ValueError for outputs that clash or a
    bad size, reeve.SimulationError when the state becomes non-finite or the
    cable bookkeeping breaks, or with strict energy is created or a span runs
    out (no output is left), KeyboardInterrupt on
    Ctrl-C after a whole frame (the outputs hold the frames done).
    """
    path = lambda p: None if p is None else _os.fspath(p)  # noqa: E731
    return scene._run(frames, path(csv), path(png_dir), path(video), path(events), path(html), width, height, force,
                      strict)


def scenes_dir():
    """The folder of the shipped scenes (atwood.json, simple.json, ...) as a pathlib.Path.

    The installed copy (PREFIX/share/reeve/scenes) when this package is
    installed by `cmake --install`, else the source tree's scenes/.
    """
    here = _pathlib.Path(__file__).resolve().parent
    for parent in here.parents:
        installed = parent / "share" / "reeve" / "scenes"
        if (installed / "scene.schema.json").is_file():
            return installed
    return _pathlib.Path(_SOURCE_SCENES_DIR)
