"""The warehouse's processes other than the coordinator, as the fault test (test_faults_ros.py)
and the fault benchmark (benchmarks/faults.py) run them: bot2's driver on ROS 2 and on ROS 1,
the ROS 1 world (warehouse_world.World on rospy: the robots without drivers of their own and the
door, with their report services), the ROS 1 world's side of the coordinator killed three ways,
and the side that kills it.

Plain Python 3.8+ (the scripts run on Debian's python3 for ROS 1)."""

import os
import signal
import time

# bot2's driver, a process of its own: it moves as the commands say, answers charged, and reports
# where it is; printing each as a JSON line (warehouse_world.take_driver reads them)
DRIVER = """
import json, sys, time, threading
task = ("depot", "out1", "out2", "out3", "shelf", "back3", "back2", "back1")
where = ["depot"]
def say(**fields):
    print(json.dumps(dict(t=time.time(), where=where[0], **fields)), flush=True)
def go(_):
    say(received="bot2.go")
    if where[0] != "charging":
        where[0] = task[(task.index(where[0]) + 1) % len(task)]
def dock(_):
    say(received="bot2.dock")
    where[0] = "charging"
    def done():
        time.sleep(0.3)
        where[0] = "depot"
        say(sent="bot2.charged")
        charged()
    threading.Thread(target=done, daemon=True).start()
"""
DRIVER_ROS2 = DRIVER + """
import rclpy
from std_msgs.msg import Empty
from std_srvs.srv import Trigger
rclpy.init(domain_id=int(sys.argv[1]))
node = rclpy.create_node("bot2_driver")
publisher = node.create_publisher(Empty, "/bot2/charged", 10)
charged = lambda: publisher.publish(Empty())
def report(request, response):
    response.success, response.message = True, where[0]
    return response
node.create_subscription(Empty, "/bot2/go", go, 100)
node.create_subscription(Empty, "/bot2/dock", dock, 100)
node.create_service(Trigger, "/robosc/report/bot2", report)
say(started=True)
rclpy.spin(node)
"""
DRIVER_ROS1 = DRIVER + """
import rospy
from std_msgs.msg import Empty
from std_srvs.srv import Trigger, TriggerResponse
rospy.init_node("bot2_driver", disable_signals=True)
publisher = rospy.Publisher("/bot2/charged", Empty, queue_size=10)
charged = lambda: publisher.publish(Empty())
rospy.Subscriber("/bot2/go", Empty, go, queue_size=100)
rospy.Subscriber("/bot2/dock", Empty, dock, queue_size=100)
rospy.Service("/robosc/report/bot2", Trigger, lambda _: TriggerResponse(True, where[0]))
say(started=True)
rospy.spin()
"""
IN_THE_AISLE = ("out1", "out2", "out3", "back3", "back2")

# the ROS 1 world, after ros1_client's helpers (start, done): format with robots (those it drives),
# twice (every answer twice) and control (a file it writes "kill" lines to)
ROS1_WORLD = """
sys.path.insert(0, {tests!r})
from warehouse_world import World, COMMANDS, ANSWERS, ROBOTS, topic
from std_srvs.srv import Trigger, TriggerResponse
start()
robots = {robots!r}  # the robots this world drives (the others have drivers of their own)
world = World(delay=0.3, twice={twice!r}, again={again!r}, muted=[r for r in ROBOTS if r not in robots])
lock = threading.Lock()
ours = lambda event: "." not in event or event.partition(".")[0] in robots
publishers = dict((e, rospy.Publisher("/" + topic(e), Empty, queue_size=100)) for e in ANSWERS if ours(e))
def heard(event):
    def take(_):
        with lock:
            world.command(event)
    return take
for event in COMMANDS:
    if ours(event):
        rospy.Subscriber("/" + topic(event), Empty, heard(event), queue_size=100)
def report(component):
    def answer(_):
        with lock:
            return TriggerResponse(True, world.rules.report(component))
    return answer
for component in robots + ("Door",):
    rospy.Service("/robosc/report/" + component, Trigger, report(component))
def publish(name):
    publishers[name].publish(Empty())
def gos():
    return dict((r, sum(1 for _, e in world.received if e == r + ".go")) for r in ROBOTS)
def run(seconds, until=None):
    end = time.time() + seconds
    while time.time() < end:
        with lock:
            world.step(publish)
            if until is not None and until():
                return True
        time.sleep(0.01)
    return until is None
control = open({control!r}, "w", buffering=1)  # what the other side reads: when to kill
"""

# the world's side of the coordinator killed three ways (after ROS1_WORLD): format with wait (the
# seconds a restarted coordinator has to move the robots on); its result tells the moments never
# reached (missed) and the restarts after which nothing moved in time (frozen)
ROS1_KILLED_THREE_WAYS = """
missed, frozen = [], 0
run(60, lambda: len(world.received) > 0)
for moment in ("a command just went out", "an answer is due", "robots in the aisle"):
    before = len(world.received)
    if moment == "a command just went out":
        condition = lambda: len(world.received) > before
    elif moment == "an answer is due":
        condition = lambda: any(not d[2] for d in world.due)
    else:
        condition = lambda: any(w in ("out2", "out3", "shelf", "back3", "back2") for w in world.rules.where.values())
    if not run(60, condition):
        missed.append(moment)
    control.write("kill\\n")
    run(2.5)  # down, and started again
    done_gos = sum(gos().values())
    if not run({wait!r}, lambda: sum(gos().values()) >= done_gos + 6):
        frozen += 1
with lock:
    result = json.loads(world.dump())
result.update(missed=missed, frozen=frozen)
done(result)
"""


def kill_when_told(control, world, node, restart, down=1.0):
    """The other side of ROS1_KILLED_THREE_WAYS: while ``world`` (its process) runs, ``kill -9`` the
    coordinator (``node``) at each "kill" line in ``control`` and, ``down`` seconds later, start it
    again with ``restart()``. Returns (kills, the coordinator running now)."""
    seen = 0
    while world.poll() is None if hasattr(world, "poll") else world.is_alive():
        kills = control.read_text().count("kill") if control.exists() else 0
        if kills > seen:
            seen = kills
            node.send_signal(signal.SIGKILL)
            node.wait(10)
            time.sleep(down)
            node = restart()
        time.sleep(0.005)
    return seen, node


def stop_and_kill(driver, pause=0.2):
    """A driver dies: stopped (it neither acknowledges nor answers), then killed ``pause`` seconds
    later. Returns when it was stopped (this machine's wall clock)."""
    os.kill(driver.pid, signal.SIGSTOP)
    stopped_at = time.time()
    time.sleep(pause)
    driver.send_signal(signal.SIGKILL)
    driver.wait(10)
    return stopped_at
