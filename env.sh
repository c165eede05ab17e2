# Owl Kit Lab shell environment: `source env.sh` (bash or zsh) from anywhere.
# Activates the venv with the ROS 2 wheels and the colcon workspace overlay, so the course's
# commands (colcon build, ros2 run ..., the installed nodes) work in this shell.

if [ -n "${BASH_VERSION:-}" ]; then
  OWL_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)"
elif [ -n "${ZSH_VERSION:-}" ]; then
  # shellcheck disable=SC2296
  OWL_ROOT="$(cd "$(dirname "${(%):-%x}")" && pwd)"
else
  OWL_ROOT="$(pwd)"
fi
export OWL_ROOT

# Network mode. private (the default): ROS 2 in this shell discovers only nodes on this machine, so in
# a classroom nobody's robot answers anybody else's commands. open: discovery reaches the local
# subnet, for real Olive modules (10.42.0.x over USB Ethernet) or a robot shared by a class.
case "${OWL_NETWORK:-private}" in
  private) _owl_range=LOCALHOST ;;
  open) _owl_range=SUBNET ;;
  *)
    echo "env.sh: OWL_NETWORK must be 'private' or 'open', not '${OWL_NETWORK}'; nothing in this shell was changed" >&2
    return 1 2>/dev/null || exit 1 ;;
esac

if [ ! -x "$OWL_ROOT/.venv/bin/python" ]; then
  echo "Owl Kit Lab is not set up yet: run 'make setup' in $OWL_ROOT first." >&2
  return 1 2>/dev/null || exit 1
fi

# shellcheck disable=SC1091
. "$OWL_ROOT/.venv/bin/activate"

_owl_prepend() {  # _owl_prepend VAR DIR: put DIR first in the colon list VAR, once
  eval "_owl_val=\${$1:-}"
  case ":$_owl_val:" in
    *":$2:"*) ;;
    *) eval "export $1=\"$2\${_owl_val:+:\$_owl_val}\"" ;;
  esac
  unset _owl_val
}

# The venv is the underlay, as /opt/ros/<distro> is on a normal install.
_owl_prepend AMENT_PREFIX_PATH "$VIRTUAL_ENV"
_owl_prepend CMAKE_PREFIX_PATH "$VIRTUAL_ENV"
# The wheels' shared libraries. Setting them here (and marking it done) saves every Python
# process the re-exec that the ros_wheels_bootstrapper .pth hook would otherwise do.
for _owl_libs in "$VIRTUAL_ENV"/lib/python3.*/site-packages/ros_*.libs; do
  [ -d "$_owl_libs" ] && _owl_prepend LD_LIBRARY_PATH "$_owl_libs"
done
unset _owl_libs
_owl_prepend LD_LIBRARY_PATH "$VIRTUAL_ENV/lib"
export _ROS_WHEELS_BOOTSTRAP_COMPLETE=1
export RMW_IMPLEMENTATION="${RMW_IMPLEMENTATION:-rmw_fastrtps_cpp}"
# Faster DDS discovery (see the file for why); a profile of your own takes precedence. Jazzy's
# Fast DDS 2.14 reads only this name: FASTDDS_DEFAULT_PROFILES_FILE is Fast DDS 3's (Kilted on).
export FASTRTPS_DEFAULT_PROFILES_FILE="${FASTRTPS_DEFAULT_PROFILES_FILE:-$OWL_ROOT/config/fastdds.xml}"
export ROS_AUTOMATIC_DISCOVERY_RANGE="$_owl_range"
if [ "$_owl_range" = LOCALHOST ]; then
  echo "Owl Kit Lab: network private: ROS 2 here sees only this machine's nodes (for real modules or a shared robot: export OWL_NETWORK=open; source env.sh)"
else
  echo "Owl Kit Lab: network open: ROS 2 here reaches the local subnet, ROS_DOMAIN_ID ${ROS_DOMAIN_ID:-0} (back to private: export OWL_NETWORK=private; source env.sh)"
fi
unset _owl_range
export ROS_DISTRO="${ROS_DISTRO:-jazzy}"
export ROS_VERSION=2
export ROS_PYTHON_VERSION=3
# Log lines reach terminals and pipes as they happen, not when a buffer fills.
export RCUTILS_LOGGING_BUFFERED_STREAM="${RCUTILS_LOGGING_BUFFERED_STREAM:-1}"
# One thread for numpy's OpenBLAS: every ROS message module imports numpy, and OpenBLAS otherwise
# starts a thread per CPU that spins at start-up: 0.1 s of the 0.29 s CPU a Python node takes to start
# (2 CPUs; more on a class server's many), for matrices far too small to share out. Yours wins if set.
export OPENBLAS_NUM_THREADS="${OPENBLAS_NUM_THREADS:-1}"
unset -f _owl_prepend

# Tab completion of ros2's commands, packages, executables, nodes, topics and types.
if [ -n "${BASH_VERSION:-}" ] && command -v register-python-argcomplete >/dev/null 2>&1; then
  eval "$(register-python-argcomplete ros2)"
fi

# The workspace overlay, once `make setup` (or `colcon build`) has built it.
if [ -n "${ZSH_VERSION:-}" ] && [ -f "$OWL_ROOT/install/local_setup.zsh" ]; then
  # shellcheck disable=SC1091
  . "$OWL_ROOT/install/local_setup.zsh"
elif [ -f "$OWL_ROOT/install/local_setup.bash" ] && [ -n "${BASH_VERSION:-}" ]; then
  # shellcheck disable=SC1091
  . "$OWL_ROOT/install/local_setup.bash"
elif [ -f "$OWL_ROOT/install/local_setup.sh" ]; then
  COLCON_CURRENT_PREFIX="$OWL_ROOT/install"
  # shellcheck disable=SC1091
  . "$OWL_ROOT/install/local_setup.sh"
fi
