"""One participant's run through a protocol, as plain data and files (no ROS): where they are, what each episode
ended as, their answers. The console drives it (:mod:`semgoal_bringup.study.console_study`).

Everything goes to ``DIR/PARTICIPANT/``: ``session.json`` (the protocol, the order, each episode's outcome and
recording, each questionnaire's answers; rewritten after every change, so a console started again carries on where
it stopped) and ``answers.csv``. Nothing leaves the machine; the participant is known by the ID given alone.
"""

from __future__ import annotations

import csv
import json
import time
from dataclasses import asdict
from pathlib import Path

from semgoal_bringup.study.protocol import Condition, Episode, Protocol, check_participant, participant_row
from semgoal_bringup.study.questionnaires import QUESTIONNAIRES, check_answers, score

SESSION_FILE = "session.json"
ANSWERS_FILE = "answers.csv"


class Phase:
    READY = "ready"
    """Waiting for the participant to start the next condition."""
    RUNNING = "running"
    QUESTIONNAIRE = "questionnaire"
    DONE = "done"


class StudySession:
    def __init__(self, protocol: Protocol, participant: str, out_dir: Path, row: int | None = None) -> None:
        self.protocol, self.participant = protocol, check_participant(participant)
        self.dir = Path(out_dir) / participant
        self.dir.mkdir(parents=True, exist_ok=True)
        self.row = participant_row(participant) if row is None else row
        self.order = protocol.order(self.row)
        self.position, self.episode, self.phase = 0, 0, Phase.READY
        self.outcomes: list[dict] = []
        self.answers: list[dict] = []
        saved = self.dir / SESSION_FILE
        if saved.exists():
            self._resume(json.loads(saved.read_text()))
        self._save()

    # -- where the participant is ----------------------------------------------------------------------
    @property
    def condition(self) -> Condition | None:
        return self.protocol.conditions[self.order[self.position]] if self.position < len(self.order) else None

    @property
    def current(self) -> Episode:
        return self.condition.episodes[self.episode]

    def recording_path(self) -> Path:
        """Where the episode under way is recorded (MCAP)."""
        return self.dir / f"{self.position + 1}-{self.condition.slug}-{self.episode + 1}.mcap"

    def answered(self) -> list[str]:
        """The questionnaires answered for the condition now."""
        return [a["questionnaire"] for a in self.answers if a["position"] == self.position]

    # -- what happens --------------------------------------------------------------------------------
    def start(self) -> Episode:
        """The participant starts the condition: its first episode (ValueError when not ready for one)."""
        if self.phase != Phase.READY:
            raise ValueError(f"cannot start a condition now: the session is {self.phase}")
        self.phase, self.episode = Phase.RUNNING, 0
        self._save()
        return self.current

    def episode_ended(self, success: bool, message: str, recording: Path | None) -> Episode | None:
        """Record how the episode under way ended; the next episode of the condition, or None (questionnaires
        next, or the next condition when the protocol asks none)."""
        if self.phase != Phase.RUNNING:
            raise ValueError(f"no episode is under way: the session is {self.phase}")
        self.outcomes.append({"position": self.position, "condition": self.condition.name, "episode": self.episode,
                              "world": self.current.world, "seed": self.current.seed, "goal": self.current.goal,
                              "success": success, "message": message,
                              "recording": recording.name if recording else "", "ended_at": time.time()})
        self.episode += 1
        if self.episode < len(self.condition.episodes):
            self._save()
            return self.current
        self.phase = Phase.QUESTIONNAIRE
        self._next_if_answered()
        return None

    def answer(self, name: str, answers: object) -> float:
        """Keep the answers to questionnaire ``name`` for the condition just run; its score. ValueError when it is
        not asked now or an answer is missing or off the scale."""
        if self.phase != Phase.QUESTIONNAIRE:
            raise ValueError(f"no questionnaire is asked now: the session is {self.phase}")
        if name not in self.protocol.questionnaires or name in self.answered():
            raise ValueError(f"{name} is not asked now (asked: {', '.join(self.waiting())})")
        checked = check_answers(name, answers)
        value = score(name, checked)
        self.answers.append({"position": self.position, "condition": self.condition.name, "questionnaire": name,
                             "answers": checked, "score": value, "answered_at": time.time()})
        with (self.dir / ANSWERS_FILE).open("a", newline="") as stream:
            writer = csv.writer(stream)
            if stream.tell() == 0:
                writer.writerow(("participant", "condition", "questionnaire", "item", "value"))
            writer.writerows((self.participant, self.condition.name, name, item, v) for item, v in checked.items())
        self._next_if_answered()
        return value

    def waiting(self) -> list[str]:
        """The questionnaires still to answer for the condition just run."""
        return [name for name in self.protocol.questionnaires if name not in self.answered()]

    def view(self) -> dict:
        """What the page shows of the study."""
        condition = self.condition
        return {"protocol": self.protocol.name, "participant": self.participant, "phase": self.phase,
                "condition": condition.name if condition else "", "number": self.position + 1,
                "conditions": len(self.order), "people": condition.people if condition else False,
                "concurrent": condition.concurrent if condition else False,
                "episode": self.episode + 1 if condition and self.phase == Phase.RUNNING else 0,
                "episodes": len(condition.episodes) if condition else 0,
                "goal": self.current.goal if condition and self.phase == Phase.RUNNING else "",
                "questionnaires": [{"name": name, "title": QUESTIONNAIRES[name].title,
                                    "items": [list(item) for item in QUESTIONNAIRES[name].items],
                                    "low": QUESTIONNAIRES[name].low, "high": QUESTIONNAIRES[name].high,
                                    "step": QUESTIONNAIRES[name].step, "anchors": list(QUESTIONNAIRES[name].anchors)}
                                   for name in self.waiting()] if self.phase == Phase.QUESTIONNAIRE else []}

    # -- files ---------------------------------------------------------------------------------------
    def _next_if_answered(self) -> None:
        if not self.waiting():
            self.position, self.episode = self.position + 1, 0
            self.phase = Phase.READY if self.position < len(self.order) else Phase.DONE
        self._save()

    def _save(self) -> None:
        data = {"protocol": asdict(self.protocol), "participant": self.participant, "row": self.row,
                "order": [self.protocol.conditions[i].name for i in self.order], "position": self.position,
                "episode": self.episode, "phase": self.phase if self.phase != Phase.RUNNING else Phase.READY,
                "outcomes": self.outcomes, "answers": self.answers}
        temporary = self.dir / f"{SESSION_FILE}.tmp"
        temporary.write_text(json.dumps(data, indent=1))
        temporary.replace(self.dir / SESSION_FILE)

    def _resume(self, data: dict) -> None:
        """Carry on a saved session of the same protocol: a condition cut short starts again from its first
        episode (its outcomes so far are kept, marked by their position)."""
        if data.get("protocol") != json.loads(json.dumps(asdict(self.protocol))):
            raise ValueError(f"{self.dir / SESSION_FILE} is a session of another protocol: give another --out or ID")
        self.row, self.order = int(data["row"]), self.protocol.order(int(data["row"]))
        self.position, self.phase = int(data["position"]), str(data["phase"])
        self.outcomes, self.answers = list(data["outcomes"]), list(data["answers"])
        self.outcomes = [o for o in self.outcomes if o["position"] < self.position or self.phase != Phase.READY]
