"""The synthesis stage: an automata network to a supervisor (a guard per controllable event).

:func:`synthesize` is the symbolic (BDD) method; :func:`synthesize_explicit`
enumerates states and serves as an independent cross-check on small models.
"""

from robosc.synthesis.explicit import synthesize_explicit
from robosc.synthesis.result import EventGuard, Explanation, Step, SynthesisResult
from robosc.synthesis.state import NetworkState, describe
from robosc.synthesis.symbolic import synthesize_symbolic as synthesize

__all__ = [
    "EventGuard",
    "Explanation",
    "NetworkState",
    "Step",
    "SynthesisResult",
    "describe",
    "synthesize",
    "synthesize_explicit",
]
