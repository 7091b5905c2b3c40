#!/usr/bin/env bash
# Idempotent setup: system packages, the pinned venv, the CMake path rewrite, the colcon build of src/.
# Each stage is skipped when a stamp of its inputs says nothing changed, so a warm run takes seconds.
set -euo pipefail
ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
PYTHON="${SEMGOAL_PYTHON:-python3.11}"
cd "$ROOT"

step() { printf '\033[1m[setup]\033[0m %s\n' "$*"; }

venv_stamp="$(cat requirements/*.txt | sha256sum | cut -c1-16)-$("$PYTHON" -c 'import sys; print(sys.version.split()[0])')"
ws_stamp="$(cd src && find . -type f ! -name '*.pyc' ! -name '*.so' ! -path '*/__pycache__/*' \
  \( ! -name '*.py' -o -name setup.py \) -print0 | sort -z | xargs -0 sha256sum | sha256sum | cut -c1-16)"
ws_stamp="$ws_stamp-$(find src -name '*.py' ! -path '*/__pycache__/*' | sort | sha256sum | cut -c1-16)"
venv_current() { [ "$(cat "$VENV/.semgoal-stamp" 2>/dev/null)" = "$venv_stamp" ]; }
ws_current() { [ "$(cat ros_ws/.semgoal-stamp 2>/dev/null)" = "$ws_stamp" ] && [ -d ros_ws/install ]; }

if [ "${1:-}" = "--check" ]; then  # used by `./semgoal doctor`
  if venv_current && ws_current; then echo "built and current"; else echo "stale (run make setup)"; fi
  exit 0
fi

# 1. System packages: OSMesa for offscreen MuJoCo rendering; Chromium and its driver for the console's
#    browser test (Debian's, never a test tool's own browser download).
system_packages=(libosmesa6 chromium chromium-driver)
missing=()
for package in "${system_packages[@]}"; do
  dpkg -s "$package" >/dev/null 2>&1 || missing+=("$package")
done
if [ "${#missing[@]}" -gt 0 ]; then
  step "installing ${missing[*]} (offscreen rendering, the console's browser test)"
  SUDO=""; [ "$(id -u)" -eq 0 ] || SUDO="sudo"
  $SUDO apt-get update -qq && $SUDO apt-get install -y -qq "${missing[@]}" >/dev/null
fi

# 2. The venv, pinned by requirements/lock.txt.
if ! venv_current; then
  step "creating the venv (ROS 2 Jazzy wheels, MuJoCo, CPU torch, ...)"
  [ -x "$VENV/bin/python" ] || "$PYTHON" -m venv "$VENV"
  "$VENV/bin/pip" install -q --disable-pip-version-check --upgrade pip==25.2
  "$VENV/bin/pip" install -q --disable-pip-version-check \
    -r requirements/ros.txt -r requirements/py.txt -c requirements/lock.txt
  "$VENV/bin/python" tools/fix_ros_cmake_paths.py
  echo "$venv_stamp" > "$VENV/.semgoal-stamp"
  rm -f ros_ws/.semgoal-stamp
else
  step "venv up to date"
fi

# 3. The colcon workspace (symlink install: Python sources edited in src/ need no rebuild).
if ! ws_current; then
  step "building the workspace (colcon build --symlink-install)"
  (
    export PATH="$VENV/bin:$PATH" CMAKE_PREFIX_PATH="$VENV" AMENT_PREFIX_PATH="$VENV"
    mkdir -p ros_ws && cd ros_ws
    colcon --log-level error build --symlink-install --base-paths ../src \
      --event-handlers console_cohesion- status- summary+ \
      --cmake-args -DPython3_EXECUTABLE="$VENV/bin/python" -DBUILD_TESTING=OFF
  )
  echo "$ws_stamp" > ros_ws/.semgoal-stamp
else
  step "workspace up to date"
fi

# 4. Matplotlib's font list, built once per machine (it asks fc-list, a process `make check`'s pure tests refuse).
"$VENV/bin/python" - <<'PY'
import glob, os, matplotlib
if not glob.glob(os.path.join(matplotlib.get_cachedir(), "fontlist-*.json")):
    print("\033[1m[setup]\033[0m building matplotlib's font list", flush=True)
    import matplotlib.font_manager  # noqa: F401
PY
