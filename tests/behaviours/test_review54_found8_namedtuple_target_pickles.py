"""Review 54 (FOUND8): a BehaviourTarget pickled when it was a NamedTuple loads with its values.

At 5e5f83f (30 November 2026, 13:28; 0123de4 made it a dataclass 24 minutes
later) ``BehaviourTarget`` was a ``NamedTuple`` in ``navkit.behaviours._soccer``,
and before it (23 November) in ``navkit.planning._soccer``. A NamedTuple pickles
(protocol 2 and above) as ``cls.__new__(cls, goal, obstacles)`` and nothing
else: today's record, a slotted dataclass built by its ``__init__``, loaded
from the 5e5f83f pickle with no field set (``repr`` raised AttributeError; a
strict xfail of review 53). Its ``__new__`` now builds the record from the
values, checked as ``__init__`` checks them, and ``__init__`` finds it built:
a construction checks its arguments once, as before. The finder's class for
the 23 November module (``navkit._shared.moved``), which built the record from
the values, is no longer needed: the old name answers today's class.

Protocol 0 and 1 pickles of the NamedTuple cannot load, and are refused with
TypeError: they are ``copyreg._reconstructor(cls, tuple, values)``, which calls
``tuple.__new__(cls, values)``, refusing a class that is not a tuple (and
returning a tuple subclass as itself, with no later step where a class could
turn it into the record).

Real bytes: ``pickle.dumps(attack(state), protocol=p)`` run on the source of
aa060be and 5e5f83f (``MAKER``; a slow test makes them again).
"""

from __future__ import annotations

import base64
import copy
import dataclasses
import inspect
import pickle
import sys
import zlib
from pathlib import Path
from typing import Any

import numpy as np
import pytest

import navkit.behaviours._soccer as soccer
from navkit.behaviours import BehaviourTarget, GameState, attack

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

#: What runs at each commit: the attack target of one game, pickled with every protocol.
MAKER = r"""
import base64, json, pickle, zlib
import navkit.planning as P
B = P if hasattr(P, "GameState") else __import__("navkit.behaviours", fromlist=["x"])
state = B.GameState((0.0, 0.0), (1.0, 0.0), [[-2.0, 1.0]], [[2.0, 1.0]], (-4.5, 0.0), (4.5, 0.0))
target = B.attack(state)
out = {str(p): base64.b64encode(zlib.compress(pickle.dumps(target, protocol=p), 9)).decode()
       for p in range(6)}
out["module"] = type(target).__module__
print(json.dumps(out))
"""

#: MAKER's pickles (zlib, base64), by commit and protocol.
MADE: dict[str, dict[int, str]] = {
    "aa060be": {
        0: (
            "eNqVUMFqwzAMvb8v6WUhttsmhcHGbrn0MEZOA5O4XhaWOsJ1CvnrfcKktIXtMjaDhLCent6TcyPNNvoOnNwYTilO"
            "Lo0RlGPlQnP+6FNGQxNCH7rMnkbnfMSTf2/O/TjFlyZ2PoEUnLXt1A+pD9YiTTR4kBaK6UhzZt0YfXacuN/E2Mw/"
            "toHMDYhwuPRpjVWVI9GGmd148O4EH6QAbbGqW1CBemh4nwKVDNzhmZRMKCUV764Uh5Yfgyv9Ic3EDIrZ67eSiw2q"
            "POdQAtvKYMFDBvU9N0vs9/vqTmGJhXuHVgY60fA65fx+z58Pf0F9z3w25hdHWoxoMaAN2o6P1N2uotfoFrN6I5jt"
            "1SyrXOAFdwv8S+glP/7NE2ssrxrl7EaUGIWWs+w3Rj7XyL4A+Q6qiA=="
        ),
        1: (
            "eNpljstOwzAQRZ0WCphneb9fK6+idscCCcSuRMrCYtGd5bimjkidjDuplL/iH/gwcNIWCTGLmZHmzrlXqbyohNNj"
            "6pvK7RRdqTB3FAhTVs4+UgyLTFqb2nEoprlS2tEXbeQszUv3Jt1YI4VACZGUaYapFYJiWWSaQssDyklRhULlToeT"
            "0p+lc7L6Y0WhvdBRO5qfYYVFBGFV+ceRVlOqbb1Q6LBhQAhJYG3Y8TOT3q8P6wgbHCjCJoctFgUsaiFsL5gjrAr/"
            "ucOGLf/x/gC7g16PDnp9r9/j0GVRu2E+wn4cx6/fvppWBzhIaq3xrl2yrK/Pp+UKh8ZbH3E4RjhJTJuZee5T49ln"
            "HM6bLEGd5sJ0/6PI8y8SLmvUFYdrhJsE4RbhjsN9+ANxXHl1"
        ),
        2: (
            "eNpVjrtOw0AQRddOCLA8Qni/06ayREeBBKLEUgqLwp213ixZC2edu15HcgdFHPI3/AMfBhuHIDHFzJXmzrnz5nLF"
            "Jq+J8cYpUypRQy/KM86Fpo9CskmSFfqZ6aEwFISrYjQuvYhnWnijIjUJ05qVNNKCZyo3uuDW5ixtVA2WW7g+maLB"
            "7dlA8JwKtRAUzdAhhMRYC1t2pswk6gatCusBNmbYDEB7vuO7U2z9AgemHNu77dC1/pdb7Mw/ZtgN0O75jZp1h71+"
            "v//0batuPjHoxHPZDDtkVV+f9yuJfWnjDgIcGhzF0pH1o8fSpp8EOF2k2/wKZ7L9n0Ee/lg4XzAuAlwaXMUVrt/R"
            "9X4ANsBlSQ=="
        ),
        3: (
            "eNo9jbtOwzAYhe0EKLhcyv0VOnlmQALRrZYyRAzdIsc1dUTr5LhOpWwwtKVvyxuAmxbO8A//+Y6+j1hZuXgvPK+m"
            "0trCTng2L5XSjr1oIxdFWbtX6SbaMxBl61nV8EyVTvNZPfWFdE42LHNalXbuXa0CRncYs+Ndi0iQJeIBzXGwxmGK"
            "o76gIlqiswfHvqk0w/EoIoS8PeBk87UGS9Hti3hEw+8Rp0mSDH9C2iOIx1m+GfRIm+8nsg/OPS5yQ02r7Jngu0xx"
            "tfUF4wrXpvu/Is9/a9x43OYr3H3inv8CH1dS/w=="
        ),
        4: (
            "eNprYJn6mwECesTzEsuyM0v0CnIS8/Iy89L14ovzk5NTi6b08DulZiSWZeaXFoUkFqWnlkyZPKVHLK80t6BSLz45"
            "vyhVL7c0pyQzsagosXJKD098UWpyfl5xSVFpMlglK1jllB72vBSIkslTvBlapzgzJk1pnxI0RcOb0ZupdUoGWw9r"
            "SkllQSpIC1OaxZTODogscw+jzRQ/Pz+v/0AAJrwZSqYkdToLQNz9wR7qAYYpQOEM1gwOkOkZXDCzgaa3TckQgqtn"
            "cIDpA6lvm9I4RQ8A9lpeIQ=="
        ),
        5: (
            "eNprYJ36kAECesTzEsuyM0v0CnIS8/Iy89L14ovzk5NTi6b08DulZiSWZeaXFoUkFqWnlkyZPKVHOK80t6BSLz45"
            "vyhVD8hOLcpMntLDHZ9WlJ+bVJqWBtQ3eYrGNAEGZPDBHsaa0sMKNgBIp5RUFqSCjGRKs5jS2dE+JWiKhjdzD6PN"
            "FD8/P6//QAAmvBlKpiR5M7VO6WF0nlICVJTBim48gwPMmikZPN6M3kxtUzIEQErbpjRO0QMAumxPZg=="
        ),
    },
    "5e5f83f": {
        0: (
            "eNqVUMFqwzAMvb8v6WUhttsmhcHGbrn0MEZOA5O4XhbWJsKxC/nrfcKktIXtMjaDhZCent6TcyPNNvgOHNw4TDEk"
            "F8cAyrFyQ3P+6GPW+vfm3I8pTJmdRud8wNOt9NKEzkeQgrO2Tf0x9oO1iImOHqSFJJ1ozqwbg89OiftNCM38Yx/I"
            "3IAYDpc+rbGqckTaMLMbD95N8IMkoC1WdQsqUB8b3qdAJQN3eCYlE0pJxrsrxV9LxeBKf4gzMYNi9vqt5GSDKs/5"
            "K4FtZbDgIYP6npsl9vt9daew/IV7h1YGOtHwmnJ+v8fPh7+gvkc+G/OLIy1GtBjQBm3HR+puV9FrdItZvRHM9mqW"
            "VS7wgrsF/iX0Eh//5ok1lleNcnYjSoxCy1H2GyPFNbIvCTmraQ=="
        ),
        1: (
            "eNpljklPwzAQhZMWCpi17Pt28ilqbxyQQNxKpB4sDr1ZiWvqiDbJcyaV8q/4D/wwcLogIeYwHnnmfe8pleWVtHrE"
            "XFNZWpAtFWWWweMqjaYfCQWxNtE0yUpbBLLIlNKWvSy/3iI70sTgKynjMhlTkkrJqMzHmqHhEOUkrwKpMquDSenW"
            "kbVR9ceMobm4Y+lwvsYKDz3CqnLCoVYF02k9MLT4wPc8L8baoOXeceT8ulgnbAgwwqbAFg99HjYI2wvmkKrcKXf4"
            "oOEU7w/Y7XU6rNfpuvs9gTYPmzPmI/b7/f7rt6tZqwMcxPWtca5tb1lfn0/LEYfGWR8JHBNOYtPkZp771Dj2mcD5"
            "LItfp7kw7f8o7/kXicsadSVwTbiJCbeEO4H74AfZGHpW"
        ),
        2: (
            "eNpVjrtOw0AQRddOCLA8Qni/aVNZoqNAAlFiyYVF4c5arxfWIrFz1+tI7qCIQ/6Gf+DDYO1gJKaYGc3cOXfebJ6y"
            "6WuinUhINk2yQuVOmGecC0Uf2tETUy9CUxCeFuNJ6YQ8U8IZFyOdMKVYSUMleJbmWhXcyKyljKbxcgvbJTN0uDmL"
            "Bc+pSOuGohtYhJAIK0HP1BHTSXqNXoVVH2tzrPugQ9dy7Rk2foGxLifmbjOwjf75BluLjzm2ffSHbqdh3WLH87zH"
            "bxNNconGIFrIbjAgbXx93rUtdqWx2/Oxr3EQSUs2jx5K437k47h2N/4VTmT/P4Pc/7FwWjPOfJxrXEQVLt9x5fwA"
            "YWlmKg=="
        ),
        3: (
            "eNo9jbtOwzAYhe2EW10uhRZ4hU6eGZBAdMNShoihW2S7BkfQpMdxKmWDobe35Q3ApC3f8A/nP0ffZ6wLOX/PPVfG"
            "ynle1q7iWVVqbRx72kcv0r0Zz0B0UU9nDc906Qyf1h8+l87JhmXO6LKovKt1qNFtjRWT7ReRIAvEI6pwsMJhiqOh"
            "oCJa4HhXnPhmZhhOxhEh5PUOnc16BZaiOxTxmIbsHqdJkjz/BNojiMeZ2ox6pOX7gezAuceFstS2yp4NvssUV3++"
            "YFyib7v/K/K4X2Pgca2WuPnCLf8FDj5T4A=="
        ),
        4: (
            "eNprYJn6lwECeiTzEsuyM0v0klIzEssy80uLivXii/OTk1OLpvTwO8EEQxKL0lNLpkye0iOWV5pbUKkXn5xflKqX"
            "W5pTkplYVJRYOaWHJ74oNTk/r7ikqDQZrJIVrHJKD3teCkTJ5CneDK1TnBmTprRPCZqi4c3ozdQ6JYOthzWlpLIg"
            "FaSFKc1iSmcHRJa5h9Fmip+fn9d/IAAT3gwlU5I6nQUgLv9gD/UCwxSgcAZrBgfI9AwumNlA09umZAjB1TM4wPSB"
            "1LdNaZyiBwDacF8G"
        ),
        5: (
            "eNprYJ36mAECeiTzEsuyM0v0klIzEssy80uLivXii/OTk1OLpvTwO8EEQxKL0lNLpkye0iOcV5pbUKkXn5xflKoH"
            "ZKcWZSZP6eGOTyvKz00qTUsD6ps8RWOaAAMy+GAPY03pYQUbAKRTSioLUkFGMqVZTOnsaJ8SNEXDm7mH0WaKn5+f"
            "138gABPeDCVTkryZWqf0MDpPKQEqymBFN57BAWbNlAweb0ZvprYpGQIgpW1TGqfoAQCHDlBL"
        ),
    },
}
MODULES = {"aa060be": "navkit.planning._soccer", "5e5f83f": "navkit.behaviours._soccer"}
GAME = GameState(
    robot_xy=(0.0, 0.0),
    ball_xy=(1.0, 0.0),
    teammates_xy=[[-2.0, 1.0]],
    opponents_xy=[[2.0, 1.0]],
    own_goal_xy=(-4.5, 0.0),
    opponent_goal_xy=(4.5, 0.0),
)


def _bytes(text: str) -> bytes:
    return zlib.decompress(base64.b64decode(text))


def _same(a: BehaviourTarget, b: BehaviourTarget) -> bool:
    return (
        type(a) is type(b)
        and a.goal_xy.tobytes() == b.goal_xy.tobytes()
        and a.obstacles_xy.tobytes() == b.obstacles_xy.tobytes()
    )


@pytest.mark.parametrize("protocol", [2, 3, 4, 5])
@pytest.mark.parametrize("commit", ["aa060be", "5e5f83f"])
def test_a_named_tuple_target_loads_with_its_values(commit: str, protocol: int) -> None:
    data = _bytes(MADE[commit][protocol])
    assert MODULES[commit].encode() in data  # the module of then, by name
    old = pickle.loads(data)
    today = attack(GAME)
    assert _same(old, today) and repr(old) == repr(today)
    # As a record built today: read-only arrays, frozen, and it copies and pickles.
    assert not old.goal_xy.flags.writeable and not old.obstacles_xy.flags.writeable
    with pytest.raises(AttributeError):
        old.goal_xy = np.zeros(2)
    for again in (copy.copy(old), copy.deepcopy(old), pickle.loads(pickle.dumps(old))):
        assert _same(again, today)


@pytest.mark.parametrize("protocol", [0, 1])
@pytest.mark.parametrize("commit", ["aa060be", "5e5f83f"])
def test_a_protocol_0_or_1_named_tuple_target_is_a_type_error(commit: str, protocol: int) -> None:
    data = _bytes(MADE[commit][protocol])
    assert b"_reconstructor" in data and b"tuple" in data
    with pytest.raises(TypeError, match="BehaviourTarget is not a subtype of tuple"):
        pickle.loads(data)


def test_the_values_of_an_old_pickle_are_checked() -> None:
    # A NamedTuple held whatever it was given: the values are checked as a
    # construction checks them (lists converted, bad shapes refused, naming them).
    made = BehaviourTarget.__new__(BehaviourTarget, [1, 2], [[0, 1], [np.nan, np.nan]])
    assert made.goal_xy.dtype == np.float64 and not made.goal_xy.flags.writeable
    assert np.array_equal(made.obstacles_xy, [[0.0, 1.0], [np.nan, np.nan]], equal_nan=True)
    with pytest.raises(ValueError, match="goal_xy"):
        BehaviourTarget.__new__(BehaviourTarget, [1.0, 2.0, 3.0], [[0.0, 1.0]])
    with pytest.raises(ValueError, match=r"obstacles_xy\[0\]"):
        BehaviourTarget.__new__(BehaviourTarget, [1.0, 2.0], [[np.nan, 1.0]])
    # __new__ alone, as pickles of the dataclass before reduce_record call it: empty.
    empty = BehaviourTarget.__new__(BehaviourTarget)
    assert not hasattr(empty, "goal_xy")


_FIRST = BehaviourTarget((5.0, 5.0), [[2.0, 1.0]])


class _Plain(BehaviourTarget):
    pass


@dataclasses.dataclass(frozen=True, slots=True, eq=False)
class _Labelled(BehaviourTarget):
    label: str = ""


class _Own(BehaviourTarget):
    def __init__(self, goal_xy: Any, obstacles_xy: Any, note: str) -> None:
        super().__init__(goal_xy, obstacles_xy)
        object.__setattr__(self, "note", note)


@pytest.mark.parametrize(
    "build",
    [
        lambda: BehaviourTarget((1.0, 0.0), [[2.0, 1.0]]),
        lambda: BehaviourTarget(goal_xy=(1.0, 0.0), obstacles_xy=[[2.0, 1.0]]),
        lambda: _Plain((1.0, 0.0), [[2.0, 1.0]]),
        lambda: _Labelled(np.array([1.0, 0.0]), np.array([[2.0, 1.0]]), "press"),
        lambda: _Own((1.0, 0.0), [[2.0, 1.0]], "kept"),
        lambda: dataclasses.replace(_FIRST, goal_xy=np.array([1.0, 0.0])),
    ],
    ids=["positional", "keywords", "subclass", "dataclass-subclass", "own-init", "replace"],
)
def test_a_construction_checks_each_argument_once(
    build: Any, monkeypatch: pytest.MonkeyPatch
) -> None:
    calls: list[str] = []
    point, players = soccer._point, soccer._players

    def counted_point(value: Any, name: str) -> Any:
        calls.append(name)
        return point(value, name)

    def counted_players(value: Any, name: str) -> Any:
        calls.append(name)
        return players(value, name)

    monkeypatch.setattr(soccer, "_point", counted_point)
    monkeypatch.setattr(soccer, "_players", counted_players)
    target = build()
    assert calls == ["goal_xy", "obstacles_xy"], calls
    assert target.goal_xy.tolist() == [1.0, 0.0] and target.obstacles_xy.tolist() == [[2.0, 1.0]]
    assert not target.goal_xy.flags.writeable and not target.obstacles_xy.flags.writeable


def test_the_signature_and_refusals_are_the_constructions() -> None:
    assert list(inspect.signature(BehaviourTarget).parameters) == ["goal_xy", "obstacles_xy"]
    assert list(inspect.signature(_Plain).parameters) == ["goal_xy", "obstacles_xy"]
    assert list(inspect.signature(_Labelled).parameters) == ["goal_xy", "obstacles_xy", "label"]
    assert BehaviourTarget.__match_args__ == ("goal_xy", "obstacles_xy")
    with pytest.raises(TypeError, match=r"__init__\(\) missing 1 required positional argument"):
        BehaviourTarget((1.0, 0.0))  # type: ignore[call-arg]
    with pytest.raises(TypeError, match="unexpected keyword argument 'goal'"):
        BehaviourTarget(goal=(1.0, 0.0), obstacles_xy=[])  # type: ignore[call-arg]


@pytest.mark.slow
@pytest.mark.parametrize("commit", ["aa060be", "5e5f83f"])
def test_the_pickles_are_made_again(commit: str, tmp_path: Path) -> None:
    made = made_at(commit, MAKER, tmp_path)
    assert made.pop("module") == MODULES[commit]
    assert {int(p): _bytes(text) for p, text in made.items()} == {
        p: _bytes(text) for p, text in MADE[commit].items()
    }
