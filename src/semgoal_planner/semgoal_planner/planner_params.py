"""The planner node's parameters, declared with descriptions and ranges (``semgoal_ros.parameters``)."""

from __future__ import annotations

from semgoal_core.arms import MAX_ARMS
from semgoal_core.vocabulary import SCENES
from semgoal_planner.semantic import AUTO_SEARCH
from semgoal_ros import interfaces as topics
from semgoal_ros.parameters import Param
from strips_planner.search import SEARCHES

PARAMS = (
    Param("scene", "desk_cleanup", "the scene whose vocabulary and domain the planner uses", choices=tuple(SCENES)),
    Param("search", AUTO_SEARCH, "auto (the scene's own: A* on the tabletop, else bfs) | bfs (shortest plans) | astar | gbfs | lazy",
          choices=(AUTO_SEARCH, *SEARCHES)),
    Param("stall_steps", 150, "control steps a robot step may take without holding before a re-plan",
          low=1, high=1_000_000, runtime=True),
    Param("human_steps", 3000, "control steps a person's step may take before the goal fails (2 min at 25 Hz)",
          low=1, high=10_000_000, runtime=True),
    Param("contradiction_steps", 10, "control steps the observed state may contradict the plan before a re-plan",
          low=1, high=100_000, runtime=True),
    Param("max_replans", 10, "re-plans before the goal fails with a reason", low=0, high=10_000, runtime=True),
    Param("require_approval", False, "a new plan waits for the operator's approve", runtime=True),
    Param("concurrent", True, "the robot and people work at once, each on a step whose predecessors are done; false: "
          "one step at a time, in plan order (in turns)", runtime=True),
    Param("arms", 1, "robot arms at the table: 2 gives a robot's turn to the free arm on its block's side and "
          "publishes the second arm's sub-goal on /semgoal/robot2/subgoal", low=1, high=MAX_ARMS),
    Param("world_topic", topics.WORLD_STATE, "with two arms, the world state that says where the blocks and hands are "
          f"(whose turn a step is): the sim's, or the camera's perception ({topics.PERCEIVED_WORLD})",
          choices=(topics.WORLD_STATE, topics.PERCEIVED_WORLD)),
    Param("state_wait_s", 5.0, "ExecuteGoal before any semantic state: wait this long for one",
          low=0.0, high=3600.0, runtime=True),
    Param("world_silence_s", 3.0, "a goal under way fails once no semantic state has come for this long (the sim "
          "or the predicates gone; the lockstep sim's heartbeat keeps a still world talking); 0: wait for ever",
          low=0.0, high=3600.0, runtime=True),
    Param("state_dir", "", "a folder for the planner's journal (SQLite): goal, plan, edits and revision survive a "
          "restart on the same world; empty: nothing survives"),
    Param("min_confidence", 0.9, "a literal the plan relies on that the source (the camera) is less sure of than this "
          "holds the planner's decisions", low=0.0, high=1.0, runtime=True),
    Param("unsure_wait_steps", 25, "control steps the planner holds its decisions for unsure literals before it takes "
          "the state as it is", low=0, high=100_000, runtime=True),
)
EXECUTIVE_PARAMS = ("stall_steps", "human_steps", "contradiction_steps", "max_replans", "require_approval", "concurrent")
"""Parameters that are the executive's settings of the same name."""
