"""foxglove_node: the running graph, live in Foxglove (``./semgoal up --foxglove [PORT]``, the ``foxglove`` launch
argument). A Foxglove WebSocket server (foxglove-sdk) on 127.0.0.1 serves:

- ``/semgoal/scene`` (foxglove.SceneUpdate): floor, table, bin, blocks and the Fetch's meshes (both arms' with a
  second arm) where MuJoCo puts them for the latest joint and world states (:class:`semgoal_sim.scene_view.SceneView`); meshes are
  fetched as ``package://semgoal_sim/meshes/NAME.stl`` assets;
- ``/semgoal/plan`` and ``/semgoal/semantic_state`` as JSON (every field, plus the plan as the operator reads
  it and the literals that hold), ``/semgoal/camera/image_raw`` (foxglove.RawImage) while the sim renders;
- the services ``/semgoal/get_plan`` and ``/semgoal/edit_plan`` (JSON in and out, the fields of GetPlan /
  EditPlan), passed to the planner, so a Foxglove Service Call panel edits the plan.

Open it in Foxglove with "Open connection" → ``ws://127.0.0.1:PORT`` and the layout
``share/semgoal_bringup/foxglove/semgoal.json``.
"""

from __future__ import annotations

import ipaddress
import json
import threading
import urllib.parse

import foxglove
from foxglove.channels import RawImageChannel, SceneUpdateChannel
from foxglove.messages import (
    Color,
    CubePrimitive,
    CylinderPrimitive,
    ModelPrimitive,
    Pose,
    Quaternion,
    RawImage,
    SceneEntity,
    SceneUpdate,
    SpherePrimitive,
    Timestamp,
    Vector3,
)
from foxglove.websocket import Capability, MessageSchema, Service, ServiceRequest, ServiceSchema
from rclpy.node import Node
from sensor_msgs.msg import Image, JointState

from semgoal_msgs.msg import Plan, SemanticState, WorldState
from semgoal_msgs.srv import EditPlan, GetPlan
from semgoal_ros import interfaces as topics
from semgoal_ros.json_messages import json_schema, message_from_dict, message_to_dict
from semgoal_ros.messages import block_poses, format_plan
from semgoal_ros.parameters import Param, ParameterValueError, declare
from semgoal_sim.scene_view import GeomView, SceneView

SCENE_TOPIC = f"{topics.NAMESPACE}/scene"
MESH_URI = "package://semgoal_sim/meshes/{}.stl"
ANSWER_WAIT_S = 5.0

PARAMS = (
    Param("host", "127.0.0.1", "the address to serve on: a loopback address only (the protocol has no "
          "authentication and the services edit the plan; reach it from elsewhere through an SSH tunnel)"),
    Param("port", 8765, "the WebSocket port (0: any free port, logged)", low=0, high=65535),
    Param("scene_hz", 10.0, "scene updates per second at most (a new one only after a new state)", low=0.5, high=60.0),
)


class FoxgloveNode(Node):
    def __init__(self) -> None:
        super().__init__("foxglove")
        values = declare(self, PARAMS)
        host = str(values["host"])
        if not _is_loopback(host):
            raise ParameterValueError(f"foxglove: parameter host={host!r} must be a loopback address "
                                      "(127.0.0.1, ::1): the live view has no authentication")
        self.views: dict[tuple[str, int], SceneView] = {}
        """By scene and number of arms."""
        self.view: SceneView | None = None
        self.joints: dict[str, float] = {}
        self.world: WorldState | None = None
        self.dirty = False
        self.get_plan_client = self.create_client(GetPlan, topics.GET_PLAN)
        self.edit_plan_client = self.create_client(EditPlan, topics.EDIT_PLAN)
        self.scene_channel = SceneUpdateChannel(SCENE_TOPIC)
        self.camera_channel = RawImageChannel(topics.CAMERA_IMAGE)
        self.plan_channel = foxglove.Channel(topics.PLAN, schema=_plan_schema())
        self.semantic_channel = foxglove.Channel(topics.SEMANTIC_STATE, schema=_semantic_schema())
        self.server = foxglove.start_server(
            name="semgoal", host=host, port=int(values["port"]), capabilities=[Capability.Services],
            supported_encodings=["json"], asset_handler=self._asset,
            services=[_service(topics.GET_PLAN, GetPlan, self._get_plan),
                      _service(topics.EDIT_PLAN, EditPlan, self._edit_plan)])
        self.create_subscription(WorldState, topics.WORLD_STATE, self._on_world, topics.STREAM)
        self.create_subscription(JointState, topics.JOINT_STATES, self._on_joints, topics.STREAM)
        self.create_subscription(Plan, topics.PLAN, self._on_plan, topics.LATCHED)
        self.create_subscription(SemanticState, topics.SEMANTIC_STATE, self._on_semantic, topics.LATCHED)
        self.create_subscription(Image, topics.CAMERA_IMAGE, self._on_image, topics.CAMERA)
        self.create_timer(1.0 / float(values["scene_hz"]), self._publish_scene)
        self.get_logger().info(f"Foxglove live view on ws://{host}:{self.server.port}")

    # -- ROS to Foxglove -------------------------------------------------------------------------------
    def _on_world(self, msg: WorldState) -> None:
        self.world, self.dirty = msg, True

    def _on_joints(self, msg: JointState) -> None:
        self.joints.update(zip(msg.name, msg.position, strict=False))
        self.dirty = True

    def _publish_scene(self) -> None:
        if not self.dirty or self.world is None:
            return
        world = self.world
        key = (world.scene, 1 + min(1, len(world.other_grippers)))  # the first arm's world state names the other's hand
        if key not in self.views:
            try:
                self.views[key] = SceneView(*key)
            except KeyError:
                self.get_logger().warn(f"world state of an unknown scene {world.scene!r}: not drawn")
                return
        self.view = view = self.views[key]
        view.pose(self.joints, {name: (pose[:3], pose[3:]) for name, pose in zip(world.block_names, block_poses(world),
                                                                                   strict=True)})
        self.scene_channel.log(scene_update(view.geoms(), _timestamp(world.header.stamp)))
        self.dirty = False

    def _on_plan(self, msg: Plan) -> None:
        self.plan_channel.log({**message_to_dict(msg), "text": format_plan(msg)})

    def _on_semantic(self, msg: SemanticState) -> None:
        holds = [f"{p.name}({','.join(p.args)})" for p in msg.predicates if p.value]
        self.semantic_channel.log({**message_to_dict(msg), "holds": holds})

    def _on_image(self, msg: Image) -> None:
        self.camera_channel.log(RawImage(timestamp=_timestamp(msg.header.stamp), frame_id=msg.header.frame_id,
                                         width=msg.width, height=msg.height, encoding=msg.encoding, step=msg.step,
                                         data=bytes(msg.data)))

    # -- Foxglove to ROS (called on the server's threads) ----------------------------------------------
    def _asset(self, uri: str) -> bytes | None:
        prefix, _, suffix = MESH_URI.partition("{}")
        view = self.view
        if view is None or not (uri.startswith(prefix) and uri.endswith(suffix)):
            return None
        name = urllib.parse.unquote(uri[len(prefix):-len(suffix)])
        return view.mesh_stl(name) if name in view.meshes() else None

    def _get_plan(self, request: ServiceRequest) -> bytes:
        return self._call(self.get_plan_client, GetPlan, request)

    def _edit_plan(self, request: ServiceRequest) -> bytes:
        return self._call(self.edit_plan_client, EditPlan, request)

    def _call(self, client, service_type: type, request: ServiceRequest) -> bytes:
        """The planner's answer as JSON; a malformed request or no answer raises, which the server sends back
        as the call's failure with the message."""
        try:
            fields = json.loads(request.payload or b"{}")
        except ValueError as error:
            raise ValueError(f"{request.service_name}: the request is not JSON ({error})") from None
        ros_request = message_from_dict(service_type.Request, fields)
        if not client.service_is_ready():
            raise RuntimeError(f"{request.service_name}: the planner is not running")
        answered = threading.Event()
        future = client.call_async(ros_request)
        future.add_done_callback(lambda _: answered.set())
        if not answered.wait(ANSWER_WAIT_S):
            client.remove_pending_request(future)
            raise TimeoutError(f"{request.service_name}: the planner did not answer in {ANSWER_WAIT_S:.0f} s")
        return json.dumps(message_to_dict(future.result())).encode()

    def destroy_node(self) -> None:
        self.server.stop()
        super().destroy_node()


def scene_update(geoms: list[GeomView], stamp: Timestamp) -> SceneUpdate:
    """One entity per geom, in the world frame (a mesh as a model asset, the rest as primitives)."""
    return SceneUpdate(entities=[SceneEntity(timestamp=stamp, frame_id="world", id=geom.name, **_primitive(geom))
                                 for geom in geoms])


def _primitive(geom: GeomView) -> dict[str, list]:
    """The SceneEntity field that draws ``geom``: ``cubes``, ``spheres``, ``cylinders`` or ``models``."""
    pose = Pose(position=Vector3(x=geom.position[0], y=geom.position[1], z=geom.position[2]),
                orientation=Quaternion(w=geom.quaternion[0], x=geom.quaternion[1], y=geom.quaternion[2],
                                       z=geom.quaternion[3]))
    size = Vector3(x=geom.size[0], y=geom.size[1], z=geom.size[2])
    color = Color(r=geom.rgba[0], g=geom.rgba[1], b=geom.rgba[2], a=geom.rgba[3])
    if geom.shape == "mesh":
        return {"models": [ModelPrimitive(pose=pose, scale=size, color=color, override_color=True,
                                          url=MESH_URI.format(urllib.parse.quote(geom.mesh, safe="")),
                                          media_type="model/stl")]}
    if geom.shape == "sphere":
        return {"spheres": [SpherePrimitive(pose=pose, size=size, color=color)]}
    if geom.shape == "cylinder":
        return {"cylinders": [CylinderPrimitive(pose=pose, size=size, color=color, bottom_scale=1.0, top_scale=1.0)]}
    return {"cubes": [CubePrimitive(pose=pose, size=size, color=color)]}


def _service(name: str, service_type: type, handler) -> Service:
    def schema(message_class: type) -> MessageSchema:
        return MessageSchema(encoding="json", schema=foxglove.Schema(
            name=f"{service_type.__name__}.{message_class.__name__.rpartition('_')[2]}", encoding="jsonschema",
            data=json.dumps(json_schema(message_class)).encode()))

    return Service(name=name, schema=ServiceSchema(
        name=f"semgoal_msgs/srv/{service_type.__name__}",
        request=schema(service_type.Request), response=schema(service_type.Response)), handler=handler)


def _plan_schema() -> dict:
    schema = json_schema(Plan)
    schema["properties"]["text"] = {"type": "string", "title": "the plan as the operator reads it"}
    return schema


def _semantic_schema() -> dict:
    schema = json_schema(SemanticState)
    schema["properties"]["holds"] = {"type": "array", "items": {"type": "string"}, "title": "the literals that hold"}
    return schema


def _timestamp(stamp) -> Timestamp:
    return Timestamp(sec=int(stamp.sec), nsec=int(stamp.nanosec))


def _is_loopback(host: str) -> bool:
    try:
        return ipaddress.ip_address(host).is_loopback
    except ValueError:
        return host == "localhost"


def main(args: list[str] | None = None) -> None:
    topics.run_node(FoxgloveNode, args)

