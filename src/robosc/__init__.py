"""robosc: RoboSC models in, proven supervisory controllers for ROS out.

The stable entry points are re-exported here; see :mod:`robosc.api`. They are imported
on first use, so that ``import robosc.language.model`` (or ``robosc --version``) does not
load the whole tool.
"""

from __future__ import annotations

from typing import Any

from robosc.runtime.onboard import VERSION as __version__

__all__ = [  # noqa: RUF022
    "__version__",
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


def __getattr__(name: str) -> Any:
    if name not in __all__ or name == "__version__":
        raise AttributeError(f"module 'robosc' has no attribute '{name}'")
    import robosc.api

    return getattr(robosc.api, name)
