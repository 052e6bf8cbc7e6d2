"""robosc: RoboSC models in, proven supervisory controllers for ROS out.

The stable entry points are re-exported here; see :mod:`robosc.api`.
"""

from robosc.api import (
    CheckResult,
    InputError,
    ModelError,
    check_file,
    check_text,
    format_text,
    load_model,
    synthesize_file,
    synthesize_model,
)

__all__ = [
    "CheckResult",
    "InputError",
    "ModelError",
    "check_file",
    "check_text",
    "format_text",
    "load_model",
    "synthesize_file",
    "synthesize_model",
]
__version__ = "0.1.0"
