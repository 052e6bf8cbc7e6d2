"""The synthesis stage: an automata network to a supervisor (a guard per controllable event).

:func:`synthesize` is the symbolic (BDD) method; :func:`synthesize_explicit`
enumerates states and serves as an independent cross-check on small models.
Names are imported on first use, so that reading a model never loads the BDD library.
"""

from __future__ import annotations

import importlib
from typing import Any

_EXPORTS = {
    "EventGuard": "robosc.synthesis.result",
    "Explanation": "robosc.synthesis.result",
    "Restriction": "robosc.synthesis.result",
    "Step": "robosc.synthesis.result",
    "SynthesisResult": "robosc.synthesis.result",
    "NetworkState": "robosc.synthesis.state",
    "describe": "robosc.synthesis.state",
    "synthesize_explicit": "robosc.synthesis.explicit",
    "synthesize": "robosc.synthesis.methods",
}

__all__ = sorted(_EXPORTS)


def __getattr__(name: str) -> Any:
    if name not in _EXPORTS:
        raise AttributeError(f"module 'robosc.synthesis' has no attribute '{name}'")
    module = importlib.import_module(_EXPORTS[name])
    return getattr(module, "synthesize_symbolic" if name == "synthesize" else name)
