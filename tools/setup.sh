#!/usr/bin/env bash
# Installs the Debian packages Reeve builds with, and the viewer's
# JavaScript (three.js; puppeteer-core and pngjs for its tests) from the
# npm registry into viewer/node_modules, at
# the versions viewer/package-lock.json pins. Idempotent: installs only
# what is missing, so a machine that has everything makes no network call.
set -euo pipefail
cd "$(dirname "$0")/.."
packages=(
  build-essential cmake pkg-config
  libeigen3-dev          # engine maths
  libccd-dev             # contacts: narrow phase (MPR)
  libqhull-dev           # convex-hull shapes: faces
  nlohmann-json3-dev     # scene files
  libpugixml-dev         # MuJoCo models (MJCF XML): reeve import mjcf
  libmujoco-dev libmujoco-samples  # reeve bench peers; MJCF imports checked against MuJoCo itself
  libvalijson-dev        # JSON Schema validation of scenes
  libcli11-dev           # command line
  libcpp-httplib-dev     # reeve view's HTTP server
  libosmesa6-dev         # off-screen OpenGL
  libpng-dev             # PNG frames
  libgtest-dev           # tests
  ffmpeg                 # video (the program, piped to)
  python3-matplotlib     # reeve bench --plot (bench/plot.py), examples/
  pybind11-dev python3-dev  # the Python module (python/)
  python3-numpy          # its arrays
  python3-pytest         # its tests
  python3-distributed    # reeve.sweep (Dask)
  chromium               # the viewer's tests in a real browser (headless)
)
# npm for the viewer's JavaScript: Debian's, unless a Node.js with its own
# npm is there already (NodeSource's, which Debian's npm conflicts with).
command -v npm >/dev/null || packages+=(nodejs npm)
# --sanitizers: what tools/sanitize.sh builds with (clang, its sanitizer and
# libFuzzer runtimes, llvm-symbolizer for readable reports and suppressions).
if [ "${1:-}" = "--sanitizers" ]; then
  packages+=(clang libclang-rt-14-dev llvm)
elif [ $# -gt 0 ]; then
  echo "usage: bash tools/setup.sh [--sanitizers]" >&2
  exit 64
fi
missing=()
for p in "${packages[@]}"; do
  dpkg-query -W -f='${Status}' "$p" 2>/dev/null | grep -q '^install ok installed$' || missing+=("$p")
done
if [ ${#missing[@]} -gt 0 ]; then
  echo "reeve setup: installing ${missing[*]}" >&2
  SUDO=""
  [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  export DEBIAN_FRONTEND=noninteractive
  $SUDO apt-get update -qq
  $SUDO apt-get install -y -qq --no-install-recommends "${missing[@]}" >/dev/null
fi
# The viewer's JavaScript, again when the lock file is newer than what
# npm installed (npm ci writes node_modules/.package-lock.json).
installed=viewer/node_modules/.package-lock.json
if [ ! -f "$installed" ] || [ viewer/package-lock.json -nt "$installed" ]; then
  echo "reeve setup: installing the viewer's JavaScript (npm ci in viewer/)" >&2
  npm ci --prefix viewer --no-audit --no-fund --loglevel=error >/dev/null
fi
