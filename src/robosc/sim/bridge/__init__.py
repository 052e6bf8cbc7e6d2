"""The simulator's ROS node: it publishes the simulated robots' sensors and ``/clock`` and
passes their commands to the simulation, which runs in robosc's process and talks to this
node over its standard input and output (JSON Lines, see ``protocol``).

Standard library plus the middleware only, Python 3.8+: ``robosc sim`` copies this folder
and runs it with the interpreter that has the middleware (Debian's python3 for rospy).
"""
