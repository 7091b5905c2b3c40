# Source me: the environment every semgoal command runs in (venv, workspace overlay, DDS on this host).
# ROS_DOMAIN_ID: the caller's value wins; otherwise a per-user default, so that an operator's separate
# terminals (`./semgoal up` in one, `./semgoal goal` in another) find each other. Tests and `make demo`
# pick their own random domain per run.
SEMGOAL_ROOT="$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)"
export SEMGOAL_ROOT
export VIRTUAL_ENV="$SEMGOAL_ROOT/.venv"
export PATH="$VIRTUAL_ENV/bin:$PATH"
if [ -f "$SEMGOAL_ROOT/ros_ws/install/local_setup.bash" ]; then
  # shellcheck disable=SC1091
  source "$SEMGOAL_ROOT/ros_ws/install/local_setup.bash"
fi
export AMENT_PREFIX_PATH="${AMENT_PREFIX_PATH:+$AMENT_PREFIX_PATH:}$VIRTUAL_ENV"
# The ROS wheels' own bootstrapper re-executes every Python start with these set; setting them here once
# spares each process that second start.
if [ -d "$VIRTUAL_ENV/lib" ]; then
  ros_libs="$(find "$VIRTUAL_ENV"/lib/python3.*/site-packages -maxdepth 1 -name 'ros_*.libs' -type d 2>/dev/null | tr '\n' ':')"
  export LD_LIBRARY_PATH="$VIRTUAL_ENV/lib:$ros_libs${LD_LIBRARY_PATH:-}"
  export _ROS_WHEELS_BOOTSTRAP_COMPLETE=1
fi
export ROS_AUTOMATIC_DISCOVERY_RANGE=LOCALHOST
export ROS_DOMAIN_ID="${ROS_DOMAIN_ID:-$(( 20 + $(id -u) % 80 ))}"
export RMW_IMPLEMENTATION="${RMW_IMPLEMENTATION:-rmw_fastrtps_cpp}"
export MUJOCO_GL="${MUJOCO_GL:-osmesa}"
export PYOPENGL_PLATFORM="${PYOPENGL_PLATFORM:-osmesa}"
export PYTHONUNBUFFERED=1
