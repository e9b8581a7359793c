"""Fuzz specs of the ``indoor-nav`` scenario (registered on import by ``fuzz_specs.py``).

Kept cheap: the floor plan as the map (``map_source="plan"``: no mapping tour, whose
scans take seconds; the map built from scans is covered by the scenario's tests), a
coarse map (0.1 m cells), a tour to one target (about 6 m, a fraction of a second),
one tracking path; the trial run directly is a planning route (milliseconds).
"""

from __future__ import annotations

from fuzz_engine import TRIALS, Anything, Call, Choice, Obj, Real, call, method, spec
from fuzz_specs_scn_omni_greedy import RUN_KINDS  # the kinds of Scenario.run's arguments

from navkit.sim import Trial, TrialResult
from navkit.sim.scenarios import IndoorNav

P = "navkit.sim.scenarios.IndoorNav"

NAN_OK = "means over no runs (a case left out of the results) are NaN in the tables and summary"
#: The values of one localisation trial (what ``summarize`` reads of it).
TOUR_VALUES = {
    "targets_reached": 1.0, "collisions": 0.0, "distance": 5.8, "duration": 30.0,
    "wheel_x": 0.05, "wheel_y": 0.04, "wheel_heading": 0.03, "fused_x": 0.02, "fused_y": 0.02,
    "fused_heading": 0.01,
}  # fmt: skip


def indoor() -> Call:
    return call(
        IndoorNav, targets=1, paths=1, furniture=True, resolution=0.1, map_source="plan",
        compare_speed=None,
    )  # fmt: skip


def planning_trial() -> Trial:
    # Built eagerly: Trial is the framework's plain record (its own spec fuzzes it).
    return Trial("planning: Field D* vs 8-connected A*", 1, 0, 12345)


INT = {"targets": Real(integer=True), "paths": Real(integer=True)}
OPTIONS = INT | {"map_source": Choice("scans", "plan"), "compare_speed": Real(optional=True)}
spec(P, lambda c: indoor(), kinds=OPTIONS)
spec(P + ".cases", lambda c: method(indoor(), "cases", 3), kinds={"trials": Real(integer=True)})
spec(
    P + ".trials",
    lambda c: method(indoor(), "trials", 2, seed=4),
    kinds={"trials": TRIALS, "seed": Real(integer=True)},
)
spec(
    P + ".run_trial",
    lambda c: method(indoor(), "run_trial", planning_trial()),
    kinds={"trial": Obj(Trial)},
)
spec(
    P + ".summarize",
    lambda c: method(
        indoor(), "summarize", [TrialResult(Trial("tour", 0, 0, 7), dict(TOUR_VALUES))], seed=0
    ),
    kinds={"results": Anything(), "seed": Real(integer=True)},
    nan_ok=NAN_OK,
)
spec(
    P + ".run",
    lambda c: method(indoor(), "run", 1, seed=2, workers=1),
    kinds=RUN_KINDS,
    nan_ok=NAN_OK,
)
