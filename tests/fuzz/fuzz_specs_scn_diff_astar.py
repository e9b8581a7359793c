"""Fuzz specs of the ``diff-astar`` scenario (registered on import by ``fuzz_specs.py``).

Kept cheap: the house only (no data needed), runs of at most half a second of
simulated time; ``run`` is fuzzed noise-free, where every case runs once.
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

from navkit.sim import Trial, TrialResult
from navkit.sim.scenarios import DiffAStar

P = "navkit.sim.scenarios.DiffAStar"
NAN_OK = (
    "a trial cut short by its duration has NaN travel times and cross-track figures "
    "(and NaN means in the tables)"
)
KINDS = {
    "parts": Anything(),
    "building": Choice("auto", "willow", "corridor"),
    "data_dir": Text(optional=True),
    "duration": Real(optional=True),
}


def house(noise: bool = True) -> Call:
    return call(DiffAStar, parts=("house",), building="corridor", noise=noise, duration=0.5)


def trial() -> Trial:
    # Built eagerly: Trial is the framework's plain record (its own spec fuzzes it).
    return Trial("house", 0, 0, 12345)


VALUES = {
    "leg1_path_length": 7.97, "leg1_travel_time": 42.9, "leg1_xte_mean": 0.014,
    "leg1_xte_max": 0.065, "leg2_path_length": 5.68, "leg2_travel_time": 32.5,
    "leg2_xte_mean": 0.013, "leg2_xte_max": 0.069, "xte_mean": 0.0135, "xte_max": 0.069,
    "xte_est_mean": 0.0135, "xte_est_max": 0.067, "reached": 1.0, "collisions": 0.0,
    "min_clearance": 0.089, "loc_error_mean": 0.007, "loc_error_max": 0.05,
}  # fmt: skip

spec(P, lambda c: house(), kinds=KINDS)
spec(P + ".cases", lambda c: method(house(), "cases", 3), kinds={"trials": Real(integer=True)})
spec(
    P + ".trials",
    lambda c: method(house(), "trials", 2, seed=4),
    kinds={"trials": TRIALS, "seed": Real(integer=True)},
)
spec(
    P + ".run_trial",
    lambda c: method(house(), "run_trial", trial()),
    kinds={"trial": Obj(Trial)},
    nan_ok=NAN_OK,
)
spec(
    P + ".summarize",
    lambda c: method(house(), "summarize", [TrialResult(trial(), dict(VALUES))], seed=0),
    kinds={"results": Anything(), "seed": Real(integer=True)},
    nan_ok=NAN_OK,
)
spec(
    P + ".run",
    # Noise-free: one trial per case whatever ``trials`` says, so large counts stay cheap.
    lambda c: method(house(noise=False), "run", 1, seed=2, workers=1),
    kinds={
        "trials": Real(integer=True, optional=True),
        "seed": Real(integer=True),
        "workers": Real(integer=True, optional=True),
        "executor": Anything(optional=True),
        "progress": Function(optional=True),
        "keep_traces": Flag(),
    },
    nan_ok=NAN_OK,
)
