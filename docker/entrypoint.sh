#!/usr/bin/env bash
# Source ROS 2 Jazzy and the semgoal workspace, then run the given command (ros2 run ..., bash).
set -e
source /opt/ros/jazzy/setup.bash
source /semgoal/install/setup.bash
exec "$@"
