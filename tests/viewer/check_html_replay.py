"""`reeve run --html` in a real browser (issue 31): headless Chromium opens
the replay from a file:// URL with no server, plays it to the end, and the
tensions it plotted must be the CSV's of the same run, frame by frame; a
screenshot of its last frame must show each moving body where the page's
camera projects it. Exit 77 (skipped) where Chromium is not installed.

usage: check_html_replay.py REEVE SCENE WORKDIR
"""
import csv
import html
import json
import math
import pathlib
import re
import shutil
import subprocess
import sys

import matplotlib.image
import numpy as np


def chromium():
    for name in ("chromium", "chromium-browser", "google-chrome"):
        if shutil.which(name):
            return shutil.which(name)
    return None


def browse(browser, url, profile, *flags):
    # --virtual-time-budget runs the page's timers in virtual time, so a
    # replay of seconds plays in a moment and the same way on any machine.
    # A profile of its own and no /dev/shm: a container's HOME and shared
    # memory may be read-only or tiny.
    cmd = [browser, "--headless=new", "--no-sandbox", "--disable-gpu", "--disable-dev-shm-usage",
           "--enable-unsafe-swiftshader", f"--user-data-dir={profile}", "--no-first-run",
           "--virtual-time-budget=5000", "--window-size=1000,700", *flags, url]
    return subprocess.run(cmd, check=True, capture_output=True, text=True, timeout=120).stdout


def projected(projection, width, height):
    """Pixel of each body's centre in a window of width x height, as the
    page's camera (three.js: a perspective of the view's aspect) draws it;
    those under the panel or outside the view are left out."""
    view_h = height - projection["view_inset_bottom_px"]
    tan_half = math.tan(math.radians(projection["fov_y_deg"]) / 2)
    view = np.array(projection["view_matrix"]).reshape(4, 4).T  # column-major
    left, top, right, bottom = projection["panel_px"]
    out = {}
    for name, centre in projection["centres"].items():
        x, y, z, _ = view @ np.array([*centre, 1.0])
        if z >= 0:
            continue  # behind the camera
        ndc_x, ndc_y = x / -z / (tan_half * width / view_h), y / -z / tan_half
        px, py = (ndc_x + 1) / 2 * width, (1 - ndc_y) / 2 * view_h
        if 0 <= px < width and 0 <= py < view_h and not (left <= px <= right and top <= py <= bottom):
            out[name] = (px, py)
    return out


def main(reeve, scene, workdir):
    browser = chromium()
    if browser is None:
        print("skipped: no chromium (tools/setup.sh installs it)")
        return 77
    work = pathlib.Path(workdir)
    work.mkdir(parents=True, exist_ok=True)
    page, table = work / "replay.html", work / "replay.csv"
    subprocess.run([reeve, "run", scene, "--frames", "45", "--html", str(page), "--csv", str(table), "--force"],
                   check=True, capture_output=True)
    dom = browse(browser, page.resolve().as_uri(), work / "profile", "--dump-dom")
    found = re.search(r'<pre id="reeve-status">(.*?)</pre>', dom, re.S)
    assert found and found.group(1), "the page never reported playing to the end"
    status = json.loads(html.unescape(found.group(1)))
    assert status["played_to_end"] and status["webgl"], status.get("webgl")

    with open(table, newline="") as f:
        rows = list(csv.DictReader(f))
    assert status["frames"] == len(rows), (status["frames"], len(rows))
    cable = status["cable"]
    columns = sorted((k for k in rows[0] if k.startswith(cable + ".") and k.endswith(".tension_N")),
                     key=lambda k: int(k.split(".")[-2]))
    assert columns, f"no tension columns for cable {cable!r}"
    for frame, row in enumerate(rows):
        assert float(row["time_s"]) == status["t"][frame], (frame, row["time_s"], status["t"][frame])
        plotted = status["tensions"][frame]
        assert [float(row[c]) for c in columns] == plotted, (frame, [row[c] for c in columns], plotted)
    assert max(max(t) for t in status["tensions"]) > 0.0, "the cable never pulled"

    shot = work / "replay.png"
    browse(browser, page.resolve().as_uri(), work / "profile", f"--screenshot={shot}")
    image = matplotlib.image.imread(shot)[:, :, :3]
    drawn = projected(status["projection"], image.shape[1], image.shape[0])
    assert drawn, "no body centre in the 3D view"
    background = image[2, image.shape[1] // 2]  # the view's top edge: the sky
    for name, (x, y) in drawn.items():
        px = image[int(round(y)), int(round(x))]
        assert abs(px - background).max() > 0.05, f"body {name!r} not drawn at its projection ({x:.0f}, {y:.0f})"
    print(f"ok: {status['frames']} frames, {len(columns)} spans of {cable!r} as in the CSV, "
          f"{len(drawn)} bodies where projected")
    return 0


if __name__ == "__main__":
    sys.exit(main(*sys.argv[1:]))
