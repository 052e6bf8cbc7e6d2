"""Synthesis for fleets of identical robots: the counter abstraction of symmetric agents.

An *agent* is a component with its communications' plants. Agents whose automata are the
same up to renaming (the instances of ``component bot[N]``, or components copied and
renamed by hand) form a *group*. When every guard and requirement treats a group's agents
alike (each agent's requirements are the same up to renaming, and other agents appear only
through ``all``/``any``/``count`` over the whole group, or the chains of ``and``/``or`` those
expand to), the state of the fleet matters only up to permuting agents: synthesis may count
how many agents are in each local state instead of tracking which agent is where.

The counted network (one counter per local state, an event per local transition of a
group's representative) goes through the same fixed point as any network (robosc.synthesis.symbolic);
its size grows polynomially with the number of agents where the monolithic network's
grows exponentially. Because the system is symmetric, its bad states and the supervisor's
guards are those of the monolithic method, read through the counters: each added guard is
written with ``count(...)`` over the group, which the runtime evaluates as it is.

When no group qualifies, :func:`~robosc.synthesis.counting.network.counted` says why and synthesis is monolithic.


The wing, in the order the work flows: ``groups`` (finding the copies), ``moves`` (a group's
local states and moves), ``translate`` (requirements and guards into counts), ``network`` (the
counted network), ``synthesis`` (the fixed point and the result, or the monolithic method
saying why), ``supervisor`` (the counted supervisor asked about the original network's states,
its conditions in the fleet's names), ``explain`` (explanations naming the fleet's robots,
made on request).
"""
