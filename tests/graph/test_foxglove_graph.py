"""The Foxglove live view on real nodes, seen by a plain WebSocket client (``websockets``, the SDK's
subprotocol): the advertised channels and services, a 3-D scene with the blocks and the arm, a mesh asset,
and the plan read and edited through the services (an edit applied, an invalid one refused with the planner's
reason, a malformed request failed with the field named)."""

import asyncio
import json
import struct

import pytest
import websockets

from conftest import GraphProbe, NodeProcesses, free_port
from semgoal_msgs.msg import GoalRequest, Plan
from semgoal_ros import interfaces as topics

SUBPROTOCOL = "foxglove.sdk.v1"
MESSAGE_DATA, SERVICE_CALL_REQUEST, SERVICE_CALL_RESPONSE, FETCH_ASSET_RESPONSE = 1, 2, 3, 4
"""Binary opcodes of the Foxglove WebSocket protocol (first byte of a binary frame)."""


class FoxgloveClient:
    """Just enough of the protocol's client side. Every frame read, whatever a caller waits for, is kept by
    kind (messages per topic, service answers and asset answers by id), so none is lost to another wait."""

    def __init__(self, socket_connection) -> None:
        self.ws = socket_connection
        self.channels: dict[str, int] = {}
        self.services: dict[str, int] = {}
        self.subscriptions: dict[int, str] = {}
        self.messages: dict[str, list[bytes]] = {}
        self.answers: dict[int, dict] = {}
        self.assets: dict[int, tuple[int, bytes]] = {}

    async def _read(self) -> None:
        frame = await self.ws.recv()
        if isinstance(frame, str):
            message = json.loads(frame)
            if message["op"] == "advertise":
                self.channels.update({c["topic"]: c["id"] for c in message["channels"]})
            elif message["op"] == "advertiseServices":
                self.services.update({s["name"]: s["id"] for s in message["services"]})
            elif message["op"] == "serviceCallFailure":
                self.answers[message["callId"]] = {"failure": message["message"]}
        elif frame[0] == MESSAGE_DATA:  # opcode, subscription id, log time: 13 bytes, then the payload
            topic = self.subscriptions.get(struct.unpack_from("<I", frame, 1)[0])
            self.messages.setdefault(topic, []).append(frame[13:])
        elif frame[0] == SERVICE_CALL_RESPONSE:
            _, _, call_id, encoding_length = struct.unpack_from("<BIII", frame)
            self.answers[call_id] = json.loads(frame[13 + encoding_length:])
        elif frame[0] == FETCH_ASSET_RESPONSE:
            _, request_id, status, error_length = struct.unpack_from("<BIBI", frame)
            self.assets[request_id] = (status, frame[10:] if status == 0 else frame[10:10 + error_length])

    async def _until(self, condition, timeout: float = 30) -> None:
        async def wait() -> None:
            while not condition():
                await self._read()
        await asyncio.wait_for(wait(), timeout)

    async def read_advertisements(self, topics_wanted: set[str], services_wanted: set[str]) -> None:
        await self._until(lambda: topics_wanted <= set(self.channels) and services_wanted <= set(self.services))

    async def subscribe(self, topic: str) -> None:
        subscription = len(self.subscriptions) + 1
        self.subscriptions[subscription] = topic
        await self.ws.send(json.dumps({"op": "subscribe",
                                       "subscriptions": [{"id": subscription, "channelId": self.channels[topic]}]}))

    async def next_message(self, topic: str) -> bytes:
        """The oldest message on ``topic`` not yet taken."""
        await self._until(lambda: self.messages.get(topic))
        return self.messages[topic].pop(0)

    async def call(self, service: str, request: dict, call_id: int) -> dict:
        """The JSON answer, or {"failure": message} for a call the server failed."""
        encoding = b"json"
        await self.ws.send(struct.pack("<BIII", SERVICE_CALL_REQUEST, self.services[service], call_id, len(encoding))
                           + encoding + json.dumps(request).encode())
        await self._until(lambda: call_id in self.answers)
        return self.answers[call_id]

    async def fetch_asset(self, uri: str, request_id: int) -> tuple[int, bytes]:
        """(status, data): status 0 and the asset's bytes, or 1 and the error text."""
        await self.ws.send(json.dumps({"op": "fetchAsset", "uri": uri, "requestId": request_id}))
        await self._until(lambda: request_id in self.assets)
        return self.assets[request_id]


async def connect(port: int) -> FoxgloveClient:
    for _ in range(150):  # the node starts in a few seconds on a busy machine
        try:
            return FoxgloveClient(await websockets.connect(f"ws://127.0.0.1:{port}", subprotocols=[SUBPROTOCOL]))
        except OSError:
            await asyncio.sleep(0.2)
    pytest.fail(f"no Foxglove server on port {port}")


def test_the_live_view_shows_the_scene_and_edits_the_plan(nodes: NodeProcesses, probe: GraphProbe) -> None:
    port = free_port()
    nodes.start("semgoal_sim", "sim_node", params={"scene": "desk_cleanup", "task": "DC-3", "seed": 6})
    nodes.start("semgoal_sim", "predicate_node")
    nodes.start("semgoal_planner", "planner_node", params={"scene": "desk_cleanup", "require_approval": True})
    nodes.start("semgoal_bringup", "foxglove_node", params={"port": port})
    plans: list[Plan] = []
    probe.node.create_subscription(Plan, topics.PLAN, plans.append, topics.LATCHED)
    goals = probe.node.create_publisher(GoalRequest, topics.GOAL, 10)

    async def session() -> None:
        client = await connect(port)
        await client.read_advertisements(
            {"/semgoal/scene", topics.PLAN, topics.SEMANTIC_STATE, topics.CAMERA_IMAGE},
            {topics.GET_PLAN, topics.EDIT_PLAN})
        await client.subscribe("/semgoal/scene")
        await client.subscribe(topics.PLAN)
        scene = await client.next_message("/semgoal/scene")
        for entity in (b"block_red", b"block_green", b"block_blue", b"bin_floor", b"robot0:gripper_link",
                       b"robot0:r_gripper_finger_link"):
            assert entity in scene, f"{entity!r} is not in the scene"
        assert b"block_yellow" not in scene  # DC-3 has three blocks: the fourth is not drawn

        status, stl = await client.fetch_asset("package://semgoal_sim/meshes/robot0%3Agripper_link.stl", 7)
        assert status == 0
        triangles = struct.unpack_from("<I", stl, 80)[0]
        assert triangles > 100 and len(stl) == 84 + 50 * triangles
        status, _ = await client.fetch_asset("package://semgoal_sim/meshes/nothing.stl", 8)
        assert status == 1

        for call_id in range(100, 200):  # until the planner has decided on a semantic state: it plans from one
            read = await client.call(topics.GET_PLAN, {}, call_id)
            if read.get("state", {}).get("objects"):
                break
            await asyncio.sleep(0.2)
        assert not read["success"] and read["plan"]["status"] == Plan.STATUS_EMPTY
        probe.spin_until(lambda: goals.get_subscription_count() > 0, 30, "the planner's goal topic")
        goals.publish(GoalRequest(task="DC-3"))
        probe.spin_until(lambda: plans and plans[-1].status == Plan.STATUS_AWAITING_APPROVAL, 30, "a plan to approve")
        plan = plans[-1]

        read = await client.call(topics.GET_PLAN, {}, 1)
        assert read["success"] and [s["action"] for s in read["plan"]["steps"]] == [s.action for s in plan.steps]

        edited = await client.call(topics.EDIT_PLAN, {"op": "assign", "index": 1, "action": "human"}, 2)
        assert edited["success"], edited["message"]
        assert edited["plan"]["steps"][1]["assignee"] == "human"
        probe.spin_until(lambda: plans[-1].steps[1].assignee == "human", 30, "the edited plan on the plan topic")

        refused = await client.call(topics.EDIT_PLAN, {"op": "remove", "index": 99}, 3)
        assert not refused["success"] and refused["message"]
        assert refused["plan"]["revision"] == edited["plan"]["revision"]  # the plan is as it was

        malformed = await client.call(topics.EDIT_PLAN, {"op": "approve", "colour": "red"}, 4)
        assert "colour" in malformed["failure"]
        wrong_type = await client.call(topics.EDIT_PLAN, {"op": "remove", "index": -1}, 5)
        assert "index" in wrong_type["failure"]

        while True:  # the plan channel carries each plan as JSON, with the text an operator reads
            shown = json.loads(await client.next_message(topics.PLAN))
            if shown["revision"] == edited["plan"]["revision"]:
                break
        step_line = next(line for line in shown["text"].splitlines() if line.split()[:1] == ["1."])
        assert shown["steps"][1]["assignee"] == "human" and "human" in step_line
        await client.ws.close()

    asyncio.run(session())


def test_with_a_second_arm_the_scene_shows_both_robots(nodes: NodeProcesses) -> None:
    port = free_port()
    nodes.start("semgoal_sim", "sim_node", params={"scene": "desk_cleanup", "task": "DC-4", "seed": 6, "arms": 2,
                                                   "mode": "realtime"})
    nodes.start("semgoal_bringup", "foxglove_node", params={"port": port})

    async def session() -> None:
        client = await connect(port)
        await client.read_advertisements({"/semgoal/scene"}, set())
        await client.subscribe("/semgoal/scene")
        scene = await client.next_message("/semgoal/scene")
        while b"robot2/" not in scene:  # a first update may come before the sim's joint states of both arms
            scene = await client.next_message("/semgoal/scene")
        for entity in (b"robot0:gripper_link", b"robot2/robot0:gripper_link", b"robot2/robot0:r_gripper_finger_link",
                       b"block_yellow"):
            assert entity in scene, f"{entity!r} is not in the scene"
        await client.ws.close()

    asyncio.run(session())
