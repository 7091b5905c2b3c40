"""A STRIPS planner for PDDL, on its own: no ROS, no semgoal (README.md)."""
