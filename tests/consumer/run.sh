#!/bin/sh
# Installs the build into a fresh prefix, then configures, builds and runs
# the consumer project against it, as someone else's project would.
# With PYTHON (the interpreter the module was built for), the installed
# Python package must import from the prefix and find the installed scenes.
# usage: run.sh BUILD_DIR WORK_DIR CMAKE CXX [PYTHON]
set -eu
build=$1 work=$2 cmake=$3 cxx=$4 python=${5:-}
here=$(cd "$(dirname "$0")" && pwd)
rm -rf "$work"
mkdir -p "$work"
prefix=$work/prefix
"$cmake" --install "$build" --prefix "$prefix" > "$work/install.log"
for f in lib/cmake/Reeve/ReeveConfig.cmake lib/cmake/Reeve/ReeveConfigVersion.cmake include/reeve/scene/scene.h \
         include/reeve/render/renderer.h bin/reeve share/reeve/scenes/atwood.json share/reeve/scenes/scene.schema.json; do
  [ -e "$prefix/$f" ] || { echo "run.sh: the install has no $f" >&2; exit 1; }
done
"$prefix/bin/reeve" validate "$prefix/share/reeve/scenes/atwood.json"
"$cmake" -S "$here" -B "$work/build" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
  -DCMAKE_BUILD_TYPE=Release > "$work/configure.log"
"$cmake" --build "$work/build" > "$work/build.log"
"$work/build/consumer"
# Built for a wider x86-64 (AVX2 and FMA, as -march=native on most machines
# is) against the library built for any: the same layouts of its types
# (EIGEN_MAX_STATIC_ALIGN_BYTES, engine/CMakeLists.txt), the same answer.
# Run only where the CPU has both.
if grep -qw avx2 /proc/cpuinfo 2>/dev/null && grep -qw fma /proc/cpuinfo; then
  "$cmake" -S "$here" -B "$work/build-wide" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
    -DCMAKE_BUILD_TYPE=Release -DCMAKE_CXX_FLAGS="-mavx2 -mfma" > "$work/configure-wide.log"
  "$cmake" --build "$work/build-wide" > "$work/build-wide.log"
  "$work/build-wide/consumer"
else
  echo "run.sh: no AVX2 and FMA here: the consumer built for them is not run"
fi
# 0.x: another minor version is another API, and is refused.
if "$cmake" -S "$here" -B "$work/build-0.3" -DCMAKE_PREFIX_PATH="$prefix" -DCMAKE_CXX_COMPILER="$cxx" \
     -DREEVE_WANTED=0.3 > "$work/configure-0.3.log" 2>&1; then
  echo "run.sh: find_package(Reeve 0.3) accepted version 0.2" >&2
  exit 1
fi
echo "run.sh: find_package(Reeve 0.3) refused, as it should be"
if [ -n "$python" ]; then
  site=$(echo "$prefix"/lib*/python3*/dist-packages)
  [ -d "$site/reeve" ] || { echo "run.sh: the install has no Python package under $prefix" >&2; exit 1; }
  PYTHONPATH=$site "$python" -c '
import sys, reeve
scenes = reeve.scenes_dir()
assert str(scenes) == sys.argv[1], (str(scenes), sys.argv[1])
scene = reeve.load(scenes / "atwood.json")
scene.step(30)
print("run.sh: the installed Python package steps", scene.name, "to t =", scene.time_s, "s")
' "$prefix/share/reeve/scenes"
fi
