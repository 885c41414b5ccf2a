"""The ROS 1 side of ``ocean-warp ros`` (:mod:`ocean_warp.envs.ros.node`): registering the node and shutting it down,
/use_sim_time, publishers by topic that take :mod:`ocean_warp.ros.topics`' messages, subscribers, the reset
service and log lines, all through the ``rospy`` module :func:`ocean_warp.ros.ros1.import_rospy` found."""

from __future__ import annotations

from . import ros1
from .topics import TF_STATIC, bus_name

__all__ = ["Ros1Bus"]



class Ros1Bus:
    """The node's rospy side: init and shutdown, /use_sim_time, publishers by topic (boat topics relative, so
    ``__ns`` moves them), subscribers, the service and log lines."""

    def __init__(self, rospy, uri: str, remaps, *, node_name: str, program: str):
        self.rospy, self.uri, self.remaps = rospy, uri, list(remaps)
        self.node_name, self.program = node_name, program
        self._publishers: dict = {}
        self._sim_time = None
        """/use_sim_time before the node set it (None: not set)."""
        self._param_set = self._started = False

    def start(self) -> None:
        """Set /use_sim_time true and register the node (it has its own signal handlers: rospy's are off)."""
        import rosgraph

        master = rosgraph.Master(f"/{self.node_name}_setup", master_uri=self.uri)
        self._sim_time = master.getParam("/use_sim_time") if master.hasParam("/use_sim_time") else None
        master.setParam("/use_sim_time", True)
        self._param_set = True
        self.rospy.init_node(self.node_name, argv=[self.program] + self.remaps, disable_signals=True)
        self._started = True

    @property
    def caller_id(self) -> str:
        return self.rospy.get_caller_id()

    def stop(self, reason: str) -> None:
        """Put /use_sim_time back as it was and shut rospy down (idempotent)."""
        if self._param_set:
            self._param_set = False
            try:
                import rosgraph

                master = rosgraph.Master(f"/{self.node_name}_setup", master_uri=self.uri)
                if self._sim_time is None:
                    master.deleteParam("/use_sim_time")
                else:
                    master.setParam("/use_sim_time", self._sim_time)
            except Exception:  # noqa: BLE001 - the master may be gone already; nothing to restore then
                pass
        if self._started:
            self._started = False
            self.rospy.signal_shutdown(reason)

    name = staticmethod(bus_name)
    """The name a publisher or subscriber gets (``topics.bus_name``)."""

    def publisher(self, topic: str, type_name: str, *, latch: bool = False):
        found = self._publishers.get(topic)
        if found is None:
            queue = 2 if "camera" in topic else 10
            found = self._publishers[topic] = self.rospy.Publisher(
                self.name(topic), ros1.message_class(type_name), queue_size=queue, latch=latch)
        return found

    def publish(self, messages, *, latched=()) -> None:
        """Publish :class:`~ocean_warp.ros.topics.Message` s (converted only where someone listens or the topic
        is latched: ``latched`` topics and /tf_static)."""
        for message in messages:
            latch = message.topic == TF_STATIC or message.topic in latched
            publisher = self.publisher(message.topic, message.type, latch=latch)
            if latch or publisher.get_num_connections() > 0:
                publisher.publish(ros1.to_ros1(message.type, message.fields))

    def subscribe(self, topic: str, type_name: str, callback) -> None:
        self.rospy.Subscriber(self.name(topic), ros1.message_class(type_name), callback, queue_size=10)

    def service(self, name: str, handler) -> None:
        """The std_srvs/Trigger service ``name``; ``handler(request)`` returns (success, message)."""
        from std_srvs.srv import Trigger, TriggerResponse

        self.rospy.Service(name, Trigger, lambda request: TriggerResponse(*handler(request)))

    def resolve_name(self, name: str) -> str:
        return self.rospy.resolve_name(name)

    def shut_down(self) -> bool:
        return self.rospy.is_shutdown()

    def info(self, text: str) -> None:
        self.rospy.loginfo(text)

    def warn(self, text: str) -> None:
        self.rospy.logwarn(text)
