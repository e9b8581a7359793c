"""Fuzz specs of ``navkit.sim.warmup`` and its records (registered on import by ``fuzz_specs.py``).

Kept cheap: every call warms only the ``geometry`` step (two small kernels,
loaded from the cache after the first call) in this process.
"""

from __future__ import annotations

from fuzz_engine import Function, Ignored, Real, SequenceOf, Text, call, spec

from navkit.sim import WarmupReport, WarmupStep, warmup

P = "navkit.sim."


def step() -> object:
    return call(WarmupStep, "astar", ("navkit.k1", "navkit.k2"), ("navkit.k3",), 1.5, 1.25)


STEP_KINDS = {
    "name": Text(),
    "compiled": Ignored(),
    "loaded": Ignored(),
    "seconds": Real(allow={"posinf"}),
    "cpu_seconds": Real(allow={"posinf"}),
}

spec(P + "WarmupStep", lambda c: step(), kinds=STEP_KINDS)
spec(
    P + "WarmupReport",
    lambda c: call(WarmupReport, (step(),), 2.0, 1),
    kinds={
        "steps": SequenceOf(WarmupStep),
        "seconds": Real(allow={"posinf"}),
        "workers": Real(integer=True),
    },
)
spec(
    P + "warmup",
    lambda c: call(warmup, workers=1, only=["geometry"]),
    kinds={
        "workers": Real(integer=True, optional=True),
        "progress": Function(optional=True),
        "only": Ignored(),
    },
)
