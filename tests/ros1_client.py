"""Helpers for the ROS 1 client scripts of the tests (run by Debian's python3, with rospy)."""

import json
import os
import sys
import threading
import time

import rospy
from geometry_msgs.msg import Twist  # noqa: F401 (used by the scripts)
from sensor_msgs.msg import LaserScan
from std_msgs.msg import Bool, Empty, Float32, Int16, String  # noqa: F401


def _fail(kind, value, trace):
    """A script's failure ends it at once, its traceback printed (rospy's and actionlib's threads
    would keep the process alive until the test's time limit, the reason unsaid)."""
    sys.__excepthook__(kind, value, trace)
    sys.stderr.flush()
    os._exit(1)


REPORTED = {}  # namespace -> what its stand-in drivers report (a script changes it as they move)


def start(name="robosc_test"):
    sys.excepthook = _fail
    rospy.init_node(name, anonymous=True, disable_signals=True)
    for namespace, states in json.loads(os.environ.get("ROBOSC_TEST_REPORTS") or "{}").items():
        REPORTED[namespace] = reports(states, namespace)


class Recorder:
    """Every message on a topic, with its arrival time."""

    def __init__(self, topic, kind):
        self.items = []
        self.lock = threading.Lock()
        self.subscriber = rospy.Subscriber(topic, kind, self.callback, queue_size=100)

    def callback(self, message):
        with self.lock:
            self.items.append((time.time(), message))

    def messages(self, since=0.0):
        with self.lock:
            return [m for t, m in self.items if t >= since]

    def clear(self):
        with self.lock:
            self.items = []


class State(Recorder):
    """The node's /state (JSON)."""

    def __init__(self):
        Recorder.__init__(self, "/state", String)

    def last(self):
        found = self.messages()
        return json.loads(found[-1].data) if found else None

    def value(self, name):
        state = self.last()
        if state is None:
            return None
        return {**state["automata"], **state["variables"]}.get(name)


def reports(states, namespace=""):
    """Drivers that report where their components are when the node asks (std_srvs/Trigger
    <namespace>/robosc/report/<component>): each answers what ``states`` says then."""
    from std_srvs.srv import Trigger, TriggerResponse

    def answer(component):
        return lambda request: TriggerResponse(component in states, states.get(component, ""))

    for component in list(states):
        rospy.Service(namespace + "/robosc/report/" + component, Trigger, answer(component))
    return states


def wait_for(condition, timeout=10.0):
    end = time.time() + timeout
    while time.time() < end:
        if condition():
            return True
        time.sleep(0.02)
    return condition()


def publisher(topic, kind, subscribers=1, timeout=10.0, queue_size=10):
    """A publisher, once the node under test has subscribed."""
    pub = rospy.Publisher(topic, kind, queue_size=queue_size)
    if not wait_for(lambda: pub.get_num_connections() >= subscribers, timeout):
        raise AssertionError("nobody subscribed to " + topic)
    return pub


def scan(ranges):
    message = LaserScan()
    message.ranges = list(ranges)
    return message


def done(result):
    """Print the result and end at once (actionlib's server threads would keep the process alive)."""
    print(json.dumps(result))
    sys.stdout.flush()
    rospy.signal_shutdown("done")
    os._exit(0)
