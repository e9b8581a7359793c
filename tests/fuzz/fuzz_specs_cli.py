"""Fuzz specs of ``navkit.sim.sweep``, the ``demo`` scenario and ``navkit.cli.main``
(registered on import by ``fuzz_specs.py``).

Kept cheap: the demo on the synthetic office (no data needed) with legs cut to
0.2 s of simulated time, sweeps in this process, and ``main`` with harmless
arguments (``list``) that write nothing.
"""

from __future__ import annotations

from fuzz_engine import (
    TRIALS,
    Anything,
    Call,
    Choice,
    Flag,
    Function,
    Obj,
    Real,
    Text,
    call,
    method,
    spec,
)

from navkit.cli import main
from navkit.sim import Trial, TrialResult, sweep
from navkit.sim.scenarios import Demo

P = "navkit.sim.scenarios.Demo"

NAN_OK = "a leg cut short before the tracker moves has no cross-track yet (NaN)"
RUN_KINDS = {
    "trials": TRIALS,
    "seed": Real(integer=True),
    "workers": Real(integer=True, optional=True),
    "executor": Anything(optional=True),
    "progress": Function(optional=True),
    "keep_traces": Flag(),
}


def demo() -> Call:
    return call(Demo, map="office", duration=0.2)


def trial() -> Trial:
    # Built eagerly: Trial is the framework's plain record (its own spec fuzzes it).
    return Trial("leg 1", 0, 0, 12345)


VALUES = {
    "plan_length": 22.6, "plan_wall_time": 0.001, "travel_time": 47.2, "final_error": 0.1,
    "cross_track_mean": 0.02, "cross_track_max": 0.09, "estimate_error": 0.07,
    "estimate_error_max": 0.07, "min_clearance": 0.24, "collisions": 0.0, "reached": 1.0,
    "distance": 22.0, "willow": 0.0,
}  # fmt: skip

spec(
    P,
    lambda c: demo(),
    kinds={
        "data_dir": Text(optional=True),
        "map": Choice("office", "auto", "willow"),
        "duration": Real(),
    },
)
spec(P + ".cases", lambda c: method(demo(), "cases", 2), kinds={"trials": Real(integer=True)})
spec(
    P + ".trials",
    lambda c: method(demo(), "trials", 2, seed=4),
    kinds={"trials": TRIALS, "seed": Real(integer=True)},
)
spec(
    P + ".run_trial",
    lambda c: method(demo(), "run_trial", trial()),
    kinds={"trial": Obj(Trial)},
    nan_ok=NAN_OK,
)
spec(
    P + ".summarize",
    lambda c: method(demo(), "summarize", [TrialResult(trial(), dict(VALUES))], seed=0),
    kinds={"results": Anything(), "seed": Real(integer=True)},
)
spec(
    P + ".run",
    lambda c: method(demo(), "run", 1, seed=2, workers=1),
    kinds=RUN_KINDS,
    nan_ok=NAN_OK,
)
spec(
    "navkit.sim.sweep",
    lambda c: call(sweep, demo(), trials=1, seeds=3, workers=1),
    kinds={
        "scenario": Anything(),
        "trials": TRIALS,
        "seeds": Real(integer=True),
        "workers": Real(integer=True, optional=True),
        "executor": Anything(optional=True),
        "progress": Function(optional=True),
        "keep_traces": Flag(),
    },
    nan_ok=NAN_OK,
)
spec("navkit.cli.main", lambda c: call(main, ["list"]), kinds={"argv": Anything(optional=True)})
