#!/usr/bin/env bash
# Source ROS 2 Jazzy and the semgoal install, then run the given command (ros2 launch ..., bash). The `--`
# keeps the container's arguments away from the setup scripts, which would read them as their own.
set -e
source /opt/ros/jazzy/setup.bash --
source /semgoal/install/setup.bash --
exec "$@"
