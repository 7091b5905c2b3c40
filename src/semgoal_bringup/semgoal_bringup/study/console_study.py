"""The console's side of study mode: it walks the participant through their session (:class:`StudySession`) on the
running graph. Starting a condition sets the planner's ``concurrent`` parameter for it; each episode resets the
world to its start, is recorded (MCAP, beside the session) and is sent to the planner as an ExecuteGoal; when its
result comes the next episode starts, and after the condition's last the page asks the questionnaires."""

from __future__ import annotations

from pathlib import Path

from semgoal_bringup.study.protocol import Protocol
from semgoal_bringup.study.session import Phase, StudySession
from semgoal_ros.client import RECORDER_MATCH_S, RECORDER_SETTLE_S, GraphUnavailableError
from semgoal_ros.interfaces import send_until_answered

PARAMETER_WAIT_S = 5.0
PLANNER_NODE = "planner"


class StudyDriver:
    def __init__(self, client, protocol: Protocol, participant: str, out_dir: Path, row: int | None = None) -> None:
        from rclpy.parameter_client import AsyncParameterClient

        self.client = client
        self.session = StudySession(protocol, participant, out_dir, row)
        self.parameters = AsyncParameterClient(client.node, PLANNER_NODE)
        self.recorder = None
        self.result = None
        """The ExecuteGoal result future of the episode under way."""
        self.message = ""

    @property
    def people(self) -> bool:
        """Whether the participant may take steps in the condition now."""
        condition = self.session.condition
        return bool(condition and condition.people and self.session.phase == Phase.RUNNING)

    def start(self) -> tuple[bool, str]:
        """The participant pressed Start: set the planner up for the condition and run its first episode."""
        try:
            episode = self.session.start()
        except ValueError as error:
            return False, str(error)
        ok, message = self._set_concurrent(self.session.condition.concurrent)
        return self._run(episode) if ok else self._abort(message)

    def answer(self, name: str, answers: object) -> tuple[bool, str]:
        try:
            value = self.session.answer(name, answers)
        except ValueError as error:
            return False, str(error)
        return True, f"{name} saved (score {value:.1f})"

    def tick(self) -> bool:
        """Called as the console pumps the graph: end the episode whose result has come; whether anything changed."""
        if self.result is None or not self.result.done():
            return False
        outcome = self.result.result().result
        self.result = None
        self.client.spin_until(lambda: False, RECORDER_SETTLE_S)  # the last plan, still on its way to the recorder
        recording = self.recorder.path if self.recorder else None
        if self.recorder is not None:
            self.recorder.close()
            self.recorder = None
        following = self.session.episode_ended(bool(outcome.success), outcome.message, recording)
        self.message = f"episode {'succeeded' if outcome.success else 'failed'}: {outcome.message}"
        if following is not None:
            self._run(following)
        return True

    def _run(self, episode) -> tuple[bool, str]:
        from semgoal_ros.recording import Recorder

        ok, message = self.client.reset(episode.world, episode.seed)
        if not ok:
            return self._abort(f"the world did not reset to {episode.world} seed {episode.seed}: {message}")
        self.recorder = Recorder(self.client.node, self.session.recording_path())
        self.client.spin_until(self.recorder.matched, RECORDER_MATCH_S)
        try:
            handle = self.client.send(episode.goal)
        except GraphUnavailableError as error:
            return self._abort(str(error))
        if handle is None or not handle.accepted:
            return self._abort(f"the planner did not take the goal {episode.goal!r}")
        self.result = handle.get_result_async()
        self.message = ""
        return True, self.message

    def _abort(self, message: str) -> tuple[bool, str]:
        """An episode that could not start ends failed with the reason (the study goes on)."""
        if self.recorder is not None:
            self.recorder.close()
            self.recorder = None
        following = self.session.episode_ended(False, message, None)
        self.message = f"episode failed to start: {message}"
        return (self._run(following) if following is not None else (False, self.message))

    def _set_concurrent(self, concurrent: bool) -> tuple[bool, str]:
        from rclpy.parameter import Parameter

        if not self.parameters.wait_for_services(PARAMETER_WAIT_S):
            return False, "the planner's parameter services did not answer: is planner_node running?"
        # Setting a value is safe to repeat, so a reply lost to the service discovery race is asked again.
        answer = send_until_answered(lambda: self.parameters.set_parameters([Parameter("concurrent", value=concurrent)]),
                                     self.client.spin_until)
        if answer is None:
            return False, "the planner did not answer setting concurrent"
        result = answer.results[0]
        return (True, "") if result.successful else (False, f"the planner refused concurrent: {result.reason}")
