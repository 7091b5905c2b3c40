"""The planner node's ear on the world: each semantic state is screened (another scene, an older episode, a
state that does not fit the scene, a world started again; with two arms, held back until its world state came:
:mod:`~semgoal_planner.arm_worlds`), then ticks the executive and, unless the source
marks it stale or the plan relies on a literal it is unsure of, is observed; a world gone silent fails the
goal with the reason. A mix-in of :class:`~semgoal_planner.planner_node.PlannerNode`."""

from __future__ import annotations

import time

from semgoal_core.names import UNDER_WAY
from semgoal_core.vocabulary import LAYOUTS, Literal, VocabularyError
from semgoal_msgs.msg import SemanticState
from semgoal_planner.doubt import unsure_literals
from semgoal_planner.executive import Observation
from semgoal_planner.plan_messages import sim_time
from semgoal_ros.messages import literal


class WorldWatch:
    """Semantic states in, for the planner node."""

    def semantic_callback(self, msg: SemanticState) -> None:
        if msg.scene != self.executive.planner.scene:
            self.get_logger().warn(f"ignored a semantic state of scene {msg.scene!r}", throttle_duration_sec=5.0)
            return
        if self.worlds is not None and self.worlds.hold_back(msg):  # two arms: decided once its world state came
            return
        if self.last_state is not None and sim_time(msg) < sim_time(self.last_state):  # one sim's clock never goes back
            self.world_restarted(msg)
        if msg.episode < self.min_episode:  # a state of the world before the reset the goal was sent for
            self.get_logger().warn(f"ignored a semantic state of episode {msg.episode} (the goal is for "
                                   f"episode {self.min_episode})", throttle_duration_sec=5.0)
            return
        literals = [literal(p) for p in msg.predicates]
        try:
            LAYOUTS[msg.scene].check_state(tuple(msg.objects), literals, (*msg.fallen, *msg.moving))
        except VocabularyError as error:
            self.get_logger().warn(f"ignored a semantic state: {error}", throttle_duration_sec=5.0)
            return
        try:
            unsure = unsure_literals(literals, list(msg.confidence), self.relied_on(), self.doubt.threshold)
        except ValueError as error:
            self.get_logger().warn(f"ignored a semantic state: {error}", throttle_duration_sec=5.0)
            return
        if self.journaled is not None:
            self.take_up_journal(msg)
        self.last_state, self.heard_at = msg, time.monotonic()
        for waiter in self.state_waiters:
            if not waiter.done():
                waiter.set_result(True)
        self.state_waiters.clear()
        replans = self.executive.replans
        with self.deciding.time():
            self.executive.tick(int(msg.step))
            if msg.stale:  # the source says this state is not to be acted on: hold the plan until one is
                self.executive.pause_blind(msg.stale)
            elif self.doubt.holds(unsure, int(msg.step), int(msg.episode)):
                self.executive.resume_sighted()
                self.counters["states held in doubt"] += 1
                self.get_logger().info("deciding nothing on " + ", ".join(f"{lit} ({sure:.0%} sure)" for lit, sure in unsure),
                                       throttle_duration_sec=1.0)
            else:
                self.executive.resume_sighted()
                self.executive.observe(Observation(tuple(msg.objects), literals, int(msg.step), tuple(msg.fallen),
                                                   tuple(msg.moving)))
        self.counters["re-plans"] += max(0, self.executive.replans - replans)
        self.publish(decided=True)

    def relied_on(self) -> list[Literal]:
        """The literals the plan's decisions rest on now: the goal's and the active step's."""
        active = self.executive.active
        return [*self.executive.goal, *(active.subgoal.literals() if active else ())]

    def check_silence(self) -> None:
        silent = time.monotonic() - self.heard_at
        if self.world_silence_s <= 0 or self.executive.status not in UNDER_WAY or silent <= self.world_silence_s:
            return
        reason = (f"no semantic state for {silent:.1f} s (are sim_node and predicate_node running?): the goal cannot "
                  "be followed; send it again once the world is back")
        self.get_logger().warn(reason)
        self.executive.cancel(reason)
        self.publish()

    def world_restarted(self, msg: SemanticState) -> None:
        """A world whose clock went back (a sim started again: its clock and episodes count from the start): the
        goal under way was for the world before, so it fails with the reason rather than waiting for ever."""
        reason = (f"the world started again (sim time {sim_time(msg):.2f} s after {sim_time(self.last_state):.2f} s: "
                  "was sim_node restarted?); the goal was for the world before: send it again")
        self.get_logger().warn(reason)
        self.min_episode = self.reset_episode = 0
        self.executive.cancel(reason)
        self.publish()
