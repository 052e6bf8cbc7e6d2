# -*- coding: utf-8 -*-
"""The part of robosc that runs on the robot: the supervisor cycle, data conversion,
event recording, supervision-layer matching and the ROS 1 / ROS 2 adapters.

Written once, tested like the rest of robosc, and copied verbatim into every
generated package (as ``onboard/``) next to a small generated module per robot.
Standard library only, Python 3.8 or newer (ROS Noetic). A generated module
calls :func:`check_version` first, so a package never runs a runtime it was not
generated for.
"""

from __future__ import absolute_import, annotations

VERSION = "0.2.0"


class RuntimeMismatch(ImportError):
    """A generated module meets a runtime of another robosc version."""


def check_version(wanted: str) -> None:
    """Refuse to run a generated module with a runtime of another version."""
    if wanted != VERSION:
        raise RuntimeMismatch(
            "this supervisor was generated for robosc runtime %s, but onboard/ holds %s: "
            "generate the package again" % (wanted, VERSION)
        )
