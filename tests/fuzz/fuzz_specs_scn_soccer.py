"""Fuzz specs of the ``soccer`` scenario (registered on import by ``fuzz_specs.py``).

Kept cheap: the smallest Table 6 map (50 cells) and games cut at half a second
of simulated time.
"""

from __future__ import annotations

import math

from fuzz_engine import TRIALS, Anything, Call, Flag, Function, Obj, Real, call, method, spec

from navkit.sim import Trial, TrialResult
from navkit.sim.scenarios import Soccer

P = "navkit.sim.scenarios.Soccer"
NAN_OK = (
    "a game not finished has NaN times; Table 6 has NaN ring radius and trap depth for "
    "wide widths (and the tables show them as '-')"
)
KINDS = {"table_cells": Real(integer=True)}


def soccer() -> Call:
    return call(Soccer, max_speed=1.5, perception_noise=0.02, wheel_slip=0.02, duration=0.5,
                table_cells=50)  # fmt: skip


def trial() -> Trial:
    # Built eagerly: Trial is the framework's plain record (its own spec fuzzes it).
    return Trial("attack, no opponent", 0, 0, 12345)


GAME = {
    "reached": 1.0, "collisions": 0.0, "stalled": 0.0, "time": 10.8, "time_to_ball": 3.1,
    "distance": 13.9, "min_clearance": 0.59, "opponents": 0.0,
}  # fmt: skip
TABLE6 = {"linear_min": -0.5, "paraboloid_min": 0.0}
for _px in (1, 10, 50, 100):
    TABLE6 |= {
        f"w{_px}_blended_min": -0.01, f"w{_px}_min_radius": 0.0, f"w{_px}_false_minima": 0.0,
        f"w{_px}_ring_radius": math.nan, f"w{_px}_trap_depth": math.nan,
    }  # fmt: skip


def results() -> list[TrialResult]:
    table = Trial("Table 6", 9, 0, 7)
    return [TrialResult(trial(), dict(GAME)), TrialResult(table, dict(TABLE6))]


spec(P, lambda c: soccer(), kinds=KINDS)
spec(P + ".cases", lambda c: method(soccer(), "cases", 3), kinds={"trials": Real(integer=True)})
spec(
    P + ".trials",
    lambda c: method(soccer(), "trials", 2, seed=4),
    # Nine cases a count: a generated 100000 builds 900,001 trials (about 14 s), which
    # the watchdog would take for a hang; large valid counts only cost time.
    kinds={"trials": TRIALS, "seed": Real(integer=True)},
)
spec(
    P + ".run_trial",
    lambda c: method(soccer(), "run_trial", trial()),
    kinds={"trial": Obj(Trial)},
    nan_ok=NAN_OK,
)
spec(
    P + ".summarize",
    lambda c: method(soccer(), "summarize", results(), seed=0),
    kinds={"results": Anything(), "seed": Real(integer=True)},
    nan_ok=NAN_OK,
)
spec(
    P + ".run",
    lambda c: method(soccer(), "run", 1, seed=2, workers=1),
    kinds={
        "trials": TRIALS,
        "seed": Real(integer=True),
        "workers": Real(integer=True, optional=True),
        "executor": Anything(optional=True),
        "progress": Function(optional=True),
        "keep_traces": Flag(),
    },
    nan_ok=NAN_OK,
)
