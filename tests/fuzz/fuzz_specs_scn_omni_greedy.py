"""Fuzz specs of the ``omni-apf`` and ``greedy`` scenarios (registered on import by
``fuzz_specs.py``).

Kept cheap: one short route, runs of at most a second or two of simulated time
(a robot 0.6 m from its target stops after about 4 s whatever the duration), a
greedy pair 0.5 m apart. The greedy scenario needs the TurtleBot3 world map in
``../shared/data``; without it every call raises ``DataNotFoundError``, which
the specs then expect.
"""

from __future__ import annotations

from pathlib import Path

import numpy as np
from fuzz_engine import (
    TRIALS,
    Anything,
    Array,
    Call,
    Flag,
    Function,
    Obj,
    Real,
    Text,
    call,
    method,
    spec,
)

from navkit.errors import DataNotFoundError
from navkit.sim import Trial, TrialResult
from navkit.sim.scenarios import Greedy, OmniApf

A = np.array
P = "navkit.sim.scenarios."
DATA = Path(__file__).resolve().parents[2].parent / "shared" / "data"
HAVE_MAP = (DATA / "ros-map-server-maps" / "turtlebot3_world" / "map.yaml").is_file()
NO_MAP = None if HAVE_MAP else DataNotFoundError

NAN_OK = "a trial that ends before the robot stops has time NaN (and NaN means in the tables)"
RUN_KINDS = {
    "trials": TRIALS,
    "seed": Real(integer=True),
    "workers": Real(integer=True, optional=True),
    "executor": Anything(optional=True),
    "progress": Function(optional=True),
    "keep_traces": Flag(),
}


def omni() -> Call:
    return call(
        OmniApf, noise=True, latency=True, obstacles=False, targets=A([[0.0, 0.6]]), duration=1.0
    )


def greedy() -> Call:
    return call(
        Greedy,
        noise=True,
        pairs=A([[[-2.0, -0.5], [-1.5, -0.5]]]),
        duration=1.0,
        inflation=0.25,
        # A data_dir naming no folder is a ValueError, not a missing data set: with no
        # ../shared/data at all (a bare clone) the scenario looks in its default places.
        data_dir=str(DATA) if DATA.is_dir() else None,
    )


def trial() -> Trial:
    # Built eagerly: Trial is the framework's plain record (its own spec fuzzes it).
    return Trial("case", 0, 0, 12345)


OMNI_VALUES = {
    "target_x": 0.0, "target_y": 0.6, "final_x": 0.0, "final_y": 0.59, "odometry_x": 0.0,
    "odometry_y": 0.588, "error": 0.01, "odometry_error": 0.012, "drift": 0.002, "time": 3.5,
    "reached": 1.0, "collisions": 0.0, "min_clearance": 3.0, "distance": 0.59,
}  # fmt: skip
GREEDY_VALUES = {
    "reached": 1.0, "collisions": 0.0, "time": 3.0, "final_error": 0.05, "path_length": 0.46,
    "astar_length": 0.5, "length_ratio": 0.92, "min_clearance": 0.3, "greedy_steps": 15.0,
    "fallbacks": 0.0,
}  # fmt: skip

for _name, _make, _values, _kinds, _error in (
    ("OmniApf", omni, OMNI_VALUES, {"targets": Array(), "obstacles": Flag(optional=True)}, None),
    ("Greedy", greedy, GREEDY_VALUES, {"pairs": Array(), "data_dir": Text(optional=True)}, NO_MAP),
):
    spec(P + _name, lambda c, m=_make: m(), kinds=_kinds)
    spec(
        P + f"{_name}.cases",
        lambda c, m=_make: method(m(), "cases", 3),
        kinds={"trials": Real(integer=True)},
    )
    spec(
        P + f"{_name}.trials",
        lambda c, m=_make: method(m(), "trials", 2, seed=4),
        kinds={"trials": TRIALS, "seed": Real(integer=True)},
    )
    spec(
        P + f"{_name}.run_trial",
        lambda c, m=_make: method(m(), "run_trial", trial()),
        kinds={"trial": Obj(Trial)},
        nan_ok=NAN_OK,
        inf_ok="min_clearance is inf when nothing is in the world (never here)",
        expect_error=_error,
    )
    spec(
        P + f"{_name}.summarize",
        lambda c, m=_make, v=_values: method(
            m(), "summarize", [TrialResult(trial(), dict(v))], seed=0
        ),
        kinds={"results": Anything(), "seed": Real(integer=True)},
        nan_ok=NAN_OK,
        expect_error=_error,
    )
    spec(
        P + f"{_name}.run",
        lambda c, m=_make: method(m(), "run", 1, seed=2, workers=1),
        kinds=RUN_KINDS,
        nan_ok=NAN_OK,
        expect_error=_error,
    )
