"""robosc: RoboSC models in, proven supervisory controllers for ROS out.

The stable entry points are re-exported here; see :mod:`robosc.api`.
"""

from robosc.api import CheckResult, check_file, check_text, format_text

__all__ = ["CheckResult", "check_file", "check_text", "format_text"]
__version__ = "0.1.0"
