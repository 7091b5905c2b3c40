"""`./semgoal console [--host H] [--port P] [--token T] [--log-dir DIR]` (``ros2 run semgoal_bringup
console_node``, ``./semgoal up --console``): the collaboration console, a web page where a person sets the
goal, reads and edits the plan, does steps themselves, and the robot carries on.

One process, one asyncio loop: a Starlette app served by uvicorn, and the graph's one client
(:class:`~semgoal_ros.client.GraphClient`) whose executor the loop pumps between requests. The page
(``share/semgoal_bringup/console/console.html``, no file from outside the machine) talks over one WebSocket:
it sends the person's requests, the console answers each and pushes the state (plan, what holds, whose step
it is) when it changes; the camera view is ``/camera.jpg``: the RGB-D camera's latest frame with the
perception's estimates drawn on it when the graph runs from the camera, else rendered offscreen from the
published states. Literals the perception is unsure of are listed as such.

Every request, the page's included, carries the token (``?token=``): one is made up at start unless given
(``--token`` or ``SEMGOAL_CONSOLE_TOKEN``), and the URL to open is printed. A request without it is refused
with 403 and changes nothing. The server binds 127.0.0.1 unless ``--host`` says otherwise. Every action of
the person and every change of the plan goes to the study log, ``LOG_DIR/console-YYYYmmdd-HHMMSS.csv``.
"""

from __future__ import annotations

import argparse
import asyncio
import hmac
import io
import json
import os
import secrets
import time
from pathlib import Path

import numpy as np

from semgoal_bringup.study.session import Phase
from semgoal_bringup.tools.console_core import PLACES, StudyLog, place_position, region_taken, sentences, unsure_sentences
from semgoal_core.arguments import natural
from semgoal_core.names import Assignee, StepStatus, agent
from semgoal_core.vocabulary import SCENES
from semgoal_planner.goals import parse_goal
from semgoal_ros.client import GraphUnavailableError
from semgoal_ros.messages import block_centres, block_poses, estimated_blocks, literal
from semgoal_ros.package_data import share_path
from semgoal_ros.parameters import Param

STATE_PERIOD_S = 0.2
"""How often the state is pushed to the page when it changed."""
CAMERA_PERIOD_S = 0.25
"""A camera image is rendered at most this often (older requests get the last one)."""
CAMERA_FRESH_S = 2.0
"""An RGB-D frame older than this (wall time) is not shown: the view falls back to the rendered scene."""
CAMERA_VIEW = "the robot's RGB-D camera, with what the perception makes of it"
RENDERED_VIEW = "rendered from the simulator's poses (no camera in this graph)"
"""What the page's picture is: the camera's frame with the estimates drawn, or a render of the published states."""
PUMP_PERIOD_S = 0.005
MAX_REQUEST_CHARS = 10_000
"""A WebSocket request longer than this is refused unread."""
OPS = ("approve", "pause", "resume", "replan", "insert", "remove", "move", "replace", "assign", "claim")


class SeenByCamera:
    """The RGB-D camera's latest frame, its intrinsics and pose, and the perception's latest estimates."""

    def __init__(self, node) -> None:
        from sensor_msgs.msg import CameraInfo, Image
        from tf2_msgs.msg import TFMessage

        from semgoal_msgs.msg import BlockEstimates
        from semgoal_ros import interfaces as topics

        self.frame = self.info = self.estimates = self.pose = None
        self.frame_at = 0.0
        node.create_subscription(Image, topics.RGBD_COLOUR, self._on_frame, topics.CAMERA)
        node.create_subscription(CameraInfo, topics.RGBD_INFO, lambda m: setattr(self, "info", m), topics.CAMERA)
        node.create_subscription(BlockEstimates, topics.BLOCK_ESTIMATES, lambda m: setattr(self, "estimates", m),
                                 topics.STREAM)
        node.create_subscription(TFMessage, topics.TF_STATIC, self._on_static, topics.LATCHED)

    def _on_frame(self, msg) -> None:
        self.frame, self.frame_at = msg, time.monotonic()

    def _on_static(self, msg) -> None:
        from semgoal_perception.perception_node import CAMERA_FRAME, pose_matrix

        for transform in msg.transforms:
            if transform.child_frame_id == CAMERA_FRAME:
                self.pose = pose_matrix(transform.transform)

    def live(self) -> bool:
        """Whether the camera sent a frame lately and its intrinsics and pose are known."""
        return not (self.frame is None or self.info is None or self.pose is None
                    or time.monotonic() - self.frame_at > CAMERA_FRESH_S)

    def drawn(self):
        """The latest frame with the estimates drawn (a PIL image), or None without a recent frame."""
        if not self.live():
            return None
        from semgoal_bringup.tools.perception_view import draw_estimates
        from semgoal_perception.geometry import PinholeCamera
        from semgoal_perception.perception_node import image_array

        try:
            rgb = image_array(self.frame, "rgb8", 3, np.uint8)
        except ValueError:
            return None
        k = self.info.k
        camera = PinholeCamera(k[0], k[4], k[2], k[5], self.pose)
        return draw_estimates(rgb, camera, estimated_blocks(self.estimates) if self.estimates else [])


class Console:
    """The graph seen and driven for the page: the latest states, the requests, the study log."""

    def __init__(self) -> None:
        from sensor_msgs.msg import JointState

        from semgoal_msgs.msg import OperatorEvent, Plan
        from semgoal_ros import interfaces as topics
        from semgoal_ros.client import GraphClient

        self.client = GraphClient("console", watch=True, lockstep=False, handle_signals=False)
        self.plan = None
        self.events: list[dict] = []
        self.joints: dict[str, float] = {}
        self.version = 0
        """Counts changes of what the page shows; the state goes out when it moves."""
        self.client.node.create_subscription(Plan, topics.PLAN, self._on_plan, topics.LATCHED)
        self.client.node.create_subscription(OperatorEvent, topics.OPERATOR_EVENTS, self._on_event, topics.EVENTS_LIVE)
        self.client.world_listeners.append(lambda _: self._changed())
        self.client.node.create_subscription(JointState, topics.JOINT_STATES, self._on_joints, topics.STREAM)
        self.seen = SeenByCamera(self.client.node)
        self.log: StudyLog | None = None
        self._painter = None
        self._camera: tuple[float, bytes] = (0.0, b"")
        self._logged_plan: tuple = ()
        self.study = None
        self.person = str(Assignee.HUMAN)
        """Who the page's person is in the plan: ``human``, or a named person (``human:alice``, ``--person``)."""
        """The participant's session in study mode (:class:`~semgoal_bringup.study.console_study.StudyDriver`)."""

    def open_log(self, log_dir: Path) -> None:
        self.log = StudyLog(log_dir / time.strftime("console-%Y%m%d-%H%M%S.csv"))

    # -- from the graph --------------------------------------------------------------------------------
    def _changed(self) -> None:
        self.version += 1

    def _on_plan(self, msg) -> None:
        self.plan = msg
        self._changed()
        key = (msg.revision, msg.status, msg.current, tuple((s.action, s.assignee, s.status) for s in msg.steps))
        if key != self._logged_plan and self.log is not None:
            self._logged_plan = key
            doing = ", ".join(f"{s.assignee} {s.action}" for s in msg.steps if s.status == StepStatus.ACTIVE) or "-"
            self.log.write(self.sim_time(), "planner", "plan",
                           f"revision {msg.revision}, doing: {doing}; "
                           + ", ".join(f"{s.index}. {s.action} ({s.assignee}, {s.status})" for s in msg.steps),
                           msg.status)

    def _on_event(self, msg) -> None:
        self.events = [*self.events, {"kind": msg.kind, "request": msg.request, "accepted": msg.accepted,
                                      "answer": msg.answer}][-20:]
        self._changed()

    def _on_joints(self, msg) -> None:
        self.joints = dict(zip(msg.name, msg.position, strict=False))

    def sim_time(self) -> float:
        world = self.client.world
        return world.header.stamp.sec + world.header.stamp.nanosec * 1e-9 if world else 0.0

    def pump(self) -> None:
        """Hand the client's executor whatever has come in (without waiting); carry the study on."""
        for _ in range(64):
            self.client.executor.spin_once(timeout_sec=0)
        if self.study is not None and self.study.tick():
            self._changed()

    # -- what the page shows ---------------------------------------------------------------------------
    def state(self) -> dict:
        world, semantic, plan = self.client.world, self.client.semantic, self.plan
        holds = [(p.name, tuple(p.args)) for p in semantic.predicates if p.value] if semantic else []
        steps = []
        if plan is not None:
            steps = [{"index": s.index, "action": s.action, "status": s.status, "assignee": s.assignee,
                      "after": list(s.after), "active": s.status == "active" and plan.status in ("executing", "paused")}
                     for s in plan.steps]
        human = next((s for s in steps if s["active"] and s["assignee"] == self.person), None)
        blocks = list(world.block_names) if world else []
        return {"type": "state", "scene": world.scene if world else "", "task": world.task if world else "",
                "episode": world.episode if world else 0, "step": int(world.step) if world else 0,
                "sim_time": round(self.sim_time(), 2), "blocks": blocks, "has_bin": bool(world and world.has_bin),
                "view": CAMERA_VIEW if self.seen.live() else RENDERED_VIEW,
                "holds": sentences(holds), "moving": list(semantic.moving) if semantic else [],
                "unsure": unsure_sentences((p.name, tuple(p.args), p.value, c)
                                           for p, c in zip(semantic.predicates, semantic.confidence, strict=False))
                if semantic else [],
                "plan": {"goal": plan.goal, "status": plan.status, "revision": plan.revision,
                         "replans": plan.replans, "current": plan.current, "steps": steps} if plan else None,
                "person": self.person, "human_step": human, "doing": {s["assignee"]: s["action"] for s in steps if s["active"]},
                "events": self.events,
                "study": {**self.study.session.view(), "message": self.study.message} if self.study else None}

    def camera_jpeg(self) -> bytes:
        """The scene as the sim last published it, rendered offscreen (at most every CAMERA_PERIOD_S)."""
        rendered_at, image = self._camera
        world = self.client.world
        if world is None or (image and time.monotonic() - rendered_at < CAMERA_PERIOD_S):
            return image
        from PIL import Image

        if (drawn := self.seen.drawn()) is not None:
            buffer = io.BytesIO()
            drawn.save(buffer, format="JPEG", quality=85)
            self._camera = (time.monotonic(), buffer.getvalue())
            return self._camera[1]

        from semgoal_bringup.tools.episode_video import Frame, FramePainter, arms_named

        key = (world.scene, len(world.block_names), arms_named(self.joints))
        if self._painter is None or self._painter[0] != key:
            if self._painter is not None:
                self._painter[1].close()
            self._painter = (key, FramePainter(*key, width=480, height=360))
        subgoal = self.client.subgoal
        caption = subgoal.action if subgoal and subgoal.action else (self.plan.status if self.plan else "")
        poses = dict(zip(world.block_names, block_poses(world), strict=True))
        pixels = self._painter[1].image(Frame(int(world.step), self.joints, poses, caption))
        buffer = io.BytesIO()
        Image.fromarray(pixels).save(buffer, format="JPEG", quality=85)
        self._camera = (time.monotonic(), buffer.getvalue())
        return self._camera[1]

    # -- what the person asks --------------------------------------------------------------------------
    def handle(self, request: dict) -> dict:
        """One request of the page, answered: {"ok": bool, "message": str, ...}; every one is logged."""
        op = request.get("op")
        handler = {"parse": self._parse, "goal": self._goal, "edit": self._edit, "move": self._move,
                   "study": self._study, "answers": self._answers}.get(op)
        if handler is None:
            answer = {"ok": False, "message": f"unknown request {op!r}: parse, goal, edit, move, study or answers"}
        else:
            try:
                answer = handler(request)
            except (KeyError, TypeError, ValueError) as error:
                answer = {"ok": False, "message": f"{op}: malformed request ({error})"}
            except GraphUnavailableError as error:
                answer = {"ok": False, "message": str(error)}
        detail = json.dumps({k: v for k, v in request.items() if k not in ("op", "id")}, sort_keys=True)
        if self.log is not None:
            self.log.write(self.sim_time(), "person", str(op), detail,
                           ("ok: " if answer["ok"] else "refused: ") + answer["message"])
        return answer

    def _literals(self, text: str) -> list[str]:
        world, semantic = self.client.world, self.client.semantic
        if world is None:
            raise ValueError("no world yet: is the sim running?")
        state = [literal(p) for p in semantic.predicates] if semantic else []
        return [str(literal) for literal in parse_goal(text, world.scene, tuple(world.block_names), state)]

    def _parse(self, request: dict) -> dict:
        text = str(request["text"])
        try:
            literals = self._literals(text)
        except ValueError as error:
            return {"ok": False, "message": str(error)}
        return {"ok": True, "message": " & ".join(literals), "literals": literals}

    def _goal(self, request: dict) -> dict:
        parsed = self._parse(request)
        if not parsed["ok"]:
            return parsed
        if not self.client.publish_goal(str(request["text"]), wait_s=2.0):
            return {"ok": False, "message": "no planner listens on the goal topic: is planner_node running?"}
        return {"ok": True, "message": f"goal sent: {parsed['message']}", "literals": parsed["literals"]}

    def _edit(self, request: dict) -> dict:
        op = str(request["edit"])
        if op not in OPS:
            return {"ok": False, "message": f"unknown edit {op!r}: one of {', '.join(OPS)}"}
        to_person = op == "claim" or (op == "assign" and str(request.get("action", "")).startswith(Assignee.HUMAN))
        if to_person and (refusal := self._study_refusal()):
            return {"ok": False, "message": refusal}
        index, to_index = int(request.get("index", 0)), int(request.get("to_index", 0))
        if not (0 <= index < 2 ** 32 and 0 <= to_index < 2 ** 32):
            return {"ok": False, "message": "step numbers are 0 or more"}
        reply = self.client.edit(op, index, str(request.get("action", "")), to_index, int(request.get("revision", 0)))
        return {"ok": bool(reply.success), "message": reply.message}

    def _move(self, request: dict) -> dict:
        if refusal := self._study_refusal():
            return {"ok": False, "message": refusal}
        world = self.client.world
        if world is None:
            return {"ok": False, "message": "no world yet: is the sim running?"}
        blocks = block_centres(world)
        place = str(request["place"])
        if place not in PLACES:
            return {"ok": False, "message": f"unknown place {place!r}: one of {', '.join(PLACES)}"}
        steps = [(s.action, s.assignee, s.status) for s in self.plan.steps] if self.plan else []
        if taken := region_taken(place, steps):
            return {"ok": False, "message": taken}
        target = place_position(place, str(request["block"]), blocks, SCENES[world.scene].bin, str(request.get("other", "")))
        ok, message = self.client.move_block(str(request["block"]), *target)
        return {"ok": ok, "message": message}

    def _study_refusal(self) -> str:
        """Why the participant may not take a step in the study's condition now ("" when they may, or no study)."""
        if self.study is None or self.study.people:
            return ""
        condition, phase = self.study.session.condition, self.study.session.phase
        if condition is None or phase not in (Phase.RUNNING, Phase.QUESTIONNAIRE):
            return "no condition is under way: press Start first"
        # a claim that reaches the console just after the robot finished still gets the condition's reason
        return f"in the condition {condition.name!r} the robot works alone" + (": watch it" if phase == Phase.RUNNING else "")

    def _study(self, request: dict) -> dict:
        if self.study is None:
            return {"ok": False, "message": "this console runs no study (./semgoal study run)"}
        if str(request.get("action")) != "start":
            return {"ok": False, "message": "study takes the action start"}
        ok, message = self.study.start()
        return {"ok": ok, "message": message}

    def _answers(self, request: dict) -> dict:
        if self.study is None:
            return {"ok": False, "message": "this console runs no study (./semgoal study run)"}
        ok, message = self.study.answer(str(request["questionnaire"]), request["answers"])
        return {"ok": ok, "message": message}

    def close(self) -> None:
        if self.study is not None and self.study.recorder is not None:
            self.study.recorder.close()
        if self._painter is not None:
            self._painter[1].close()
        if self.log is not None:
            self.log.close()
        self.client.close()


def make_app(console: Console, token: str):
    """The Starlette app: the page, the camera, the WebSocket; every route checks the token."""
    from starlette.applications import Starlette
    from starlette.responses import HTMLResponse, Response
    from starlette.routing import Route, WebSocketRoute
    from starlette.websockets import WebSocket, WebSocketDisconnect

    page = share_path("semgoal_bringup", "console", "console.html").read_text()

    def allowed(given: str | None) -> bool:
        return given is not None and hmac.compare_digest(given.encode(), token.encode())

    async def index(request):
        if not allowed(request.query_params.get("token")):
            return Response("a valid token is needed (?token=...)\n", status_code=403)
        return HTMLResponse(page, headers={"Cache-Control": "no-store"})

    async def camera(request):
        if not allowed(request.query_params.get("token")):
            return Response("a valid token is needed\n", status_code=403)
        image = console.camera_jpeg()
        if not image:
            return Response("no world state yet\n", status_code=503)
        return Response(image, media_type="image/jpeg", headers={"Cache-Control": "no-store"})

    async def socket(websocket: WebSocket):
        if not allowed(websocket.query_params.get("token")):
            await websocket.close(code=1008)
            return
        await websocket.accept()
        sent = -1

        async def push() -> None:
            nonlocal sent
            while True:
                if console.version != sent:
                    sent = console.version
                    await websocket.send_text(json.dumps(console.state()))
                await asyncio.sleep(STATE_PERIOD_S)

        pusher = asyncio.create_task(push())
        try:
            while True:
                text = await websocket.receive_text()
                if len(text) > MAX_REQUEST_CHARS:
                    answer = {"ok": False, "message": f"request refused: over {MAX_REQUEST_CHARS} characters"}
                    request = {}
                else:
                    try:
                        request = json.loads(text)
                        if not isinstance(request, dict):
                            raise ValueError("not a JSON object")
                    except ValueError as error:
                        request, answer = {}, {"ok": False, "message": f"request refused: {error}"}
                    else:
                        answer = console.handle(request)
                console.version += 1
                await websocket.send_text(json.dumps({"type": "reply", "id": request.get("id"), **answer}))
        except WebSocketDisconnect:
            pass
        finally:
            pusher.cancel()

    return Starlette(routes=[Route("/", index), Route("/camera.jpg", camera), WebSocketRoute("/ws", socket)])


async def serve(console: Console, token: str, host: str, port: int) -> None:
    import uvicorn

    server = uvicorn.Server(uvicorn.Config(make_app(console, token), host=host, port=port, log_level="warning",
                                           ws="websockets-sansio"))

    async def pump() -> None:
        while not server.should_exit:
            console.pump()
            await asyncio.sleep(PUMP_PERIOD_S)

    pumping = asyncio.create_task(pump())
    print(f"[console] open http://{'127.0.0.1' if host in ('0.0.0.0', '::') else host}:{port}/?token={token}"
          f"  (study log: {console.log.path if console.log else '-'})", flush=True)
    try:
        await server.serve()
    finally:
        pumping.cancel()


PARAMS = (
    Param("host", "127.0.0.1", "the address to serve the page on (127.0.0.1: this machine only)"),
    Param("port", 8080, "the page's port", low=1, high=65535),
    Param("log_dir", "study-logs", "the folder of the study logs (a CSV per console session)"),
)


def main(argv: list[str] | None = None) -> int:
    """`./semgoal console` and `ros2 run semgoal_bringup console_node`: flags or ROS parameters (the node is
    ``console``: ``--ros-args -p port:=8081``, or the params file's ``console`` section)."""
    import rclpy
    from rclpy.signals import SignalHandlerOptions

    from semgoal_ros.parameters import ParameterValueError, declare

    parser = argparse.ArgumentParser(prog="semgoal console", description=__doc__.split("\n\n")[0])
    parser.add_argument("--host", help="address to serve on (default 127.0.0.1: this machine only)")
    parser.add_argument("--port", type=int, help="default 8080")
    parser.add_argument("--token", default=os.environ.get("SEMGOAL_CONSOLE_TOKEN", ""),
                        help="the token every request must carry (default: $SEMGOAL_CONSOLE_TOKEN, else a new one)")
    parser.add_argument("--log-dir", help="where the study log CSVs go (default study-logs)")
    parser.add_argument("--person", default=Assignee.HUMAN, help="who this page's person is in the plan: human "
                        "(default) or a named person human:NAME, one console each")
    parser.add_argument("--study", type=Path, help="study mode: a protocol (YAML) to walk the participant through")
    parser.add_argument("--participant", help="study mode: the participant's ID (all that identifies them)")
    parser.add_argument("--out", type=Path, default=Path("study-results"), help="study mode: where sessions go")
    parser.add_argument("--row", type=natural, help="study mode: the row of the conditions' Latin square (default: "
                        "from the participant's ID)")
    args, ros_args = parser.parse_known_args(argv)
    try:
        person = agent(args.person)
    except ValueError as error:
        parser.error(str(error))
    study = None
    if args.study is not None:
        from semgoal_bringup.study.protocol import ProtocolError, check_participant, load_protocol

        try:
            study = (load_protocol(args.study), check_participant(args.participant or ""))
        except ProtocolError as error:
            parser.error(str(error))
    overrides = [f"{name}:={value}" for name, value in (("host", args.host), ("port", args.port),
                                                        ("log_dir", args.log_dir)) if value is not None]
    rclpy.init(args=["semgoal_console", *ros_args, *(["--ros-args", *(f for o in overrides for f in ("-p", o))]
                                                    if overrides else [])],
               domain_id=int(os.environ.get("ROS_DOMAIN_ID", "0")), signal_handler_options=SignalHandlerOptions.NO)
    console = None
    try:
        console = Console()
        console.person = person
        values = declare(console.client.node, PARAMS)
        if study is not None:
            from semgoal_bringup.study.console_study import StudyDriver

            console.study = StudyDriver(console.client, *study, args.out, args.row)
            values["log_dir"] = str(console.study.session.dir)  # the participant's study log beside their session
        console.open_log(Path(str(values["log_dir"])))
        token = args.token or secrets.token_urlsafe(16)
        asyncio.run(serve(console, token, str(values["host"]), int(values["port"])))
    except ParameterValueError as error:
        print(f"semgoal console: {error}", flush=True)
        return 2
    except KeyboardInterrupt:
        pass
    finally:
        if console is not None:
            console.close()
    return 0
