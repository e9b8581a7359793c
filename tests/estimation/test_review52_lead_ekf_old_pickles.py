"""ExtendedKalmanFilter pickles from before its state array load and step on (review 52).

Filters pickled before 98b4639 (30 November 2026), attribute by attribute (a
``__dict__`` at 98fb796, slots from 0123de4), raised AttributeError as they
loaded (``__dict__``, ``_validated``: review 52's FOUND4 survey). Their estimate
now goes into a filter as the constructor builds one: the same x and P, the
next steps those of a filter built today with them. Real pickle bytes; a slow
test makes them again from git.
"""

from __future__ import annotations

import base64
import copy
import pickle
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import ExtendedKalmanFilter

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

#: ExtendedKalmanFilter([0, 1, 3], diag(0.5, 0.25, 0.1), angle_states=(2,)) after
#: MAKER's predict and update, pickled at 98fb796 (a __dict__) and 0123de4 (slots).
OLD = {
    "98fb796": (
        "gASVCwIAAAAAAACMFm5hdmtpdC5lc3RpbWF0aW9uLl9la2aUjBRFeHRlbmRlZEthbG1hbkZpbHRlcpSTlCmB"
        "lH2UKIwCX26USwOMAl9wlIwWbnVtcHkuX2NvcmUubXVsdGlhcnJheZSMDF9yZWNvbnN0cnVjdJSTlIwFbnVt"
        "cHmUjAduZGFycmF5lJOUSwCFlEMBYpSHlFKUKEsBSwNLA4aUaAqMBWR0eXBllJOUjAJmOJSJiIeUUpQoSwOM"
        "ATyUTk5OSv////9K/////0sAdJRiiUNIxrUyrYkWhD+gmI1GYFs/PwAAAAAAAAAAoJiNRmBbPz8lWBHuPZDQ"
        "PwAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAClcj8L1KLw/lHSUYowHX2FuZ2xlc5RLAoWUjAJfeJRoCWgMSwCF"
        "lGgOh5RSlChLAUsDhZRoFolDGAtH5gQ8n74/s9EIbOsD8D8AAAAAAAAIQJR0lGKMCl92YWxpZGF0ZWSUfZQo"
        "jAFRlGgJaAxLAIWUaA6HlFKUKEsBSwNLA4aUaBaJQ0h7FK5H4XqEPwAAAAAAAAAAAAAAAAAAAAAAAAAAAAAA"
        "AHsUrkfheoQ/AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAexSuR+F6hD+UdJRijAFSlGgJaAxLAIWUaA6HlFKU"
        "KEsBSwFLAYaUaBaJQwh7FK5H4XqEP5R0lGJ1dWIu"
    ),
    "0123de4": (
        "gASVDgIAAAAAAACMFm5hdmtpdC5lc3RpbWF0aW9uLl9la2aUjBRFeHRlbmRlZEthbG1hbkZpbHRlcpSTlCmB"
        "lE59lCiMB19hbmdsZXOUSwKFlIwCX26USwOMCl92YWxpZGF0ZWSUfZQojAFRlIwWbnVtcHkuX2NvcmUubXVs"
        "dGlhcnJheZSMDF9yZWNvbnN0cnVjdJSTlIwFbnVtcHmUjAduZGFycmF5lJOUSwCFlEMBYpSHlFKUKEsBSwNL"
        "A4aUaA6MBWR0eXBllJOUjAJmOJSJiIeUUpQoSwOMATyUTk5OSv////9K/////0sAdJRiiUNIexSuR+F6hD8A"
        "AAAAAAAAAAAAAAAAAAAAAAAAAAAAAAB7FK5H4XqEPwAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAAHsUrkfheoQ/"
        "lHSUYowBUpRoDWgQSwCFlGgSh5RSlChLAUsBSwGGlGgaiUMIexSuR+F6hD+UdJRidYwCX3CUaA1oEEsAhZRo"
        "EoeUUpQoSwFLA0sDhpRoGolDSMa1Mq2JFoQ/oJiNRmBbPz8AAAAAAAAAAKCYjUZgWz8/JVgR7j2Q0D8AAAAA"
        "AAAAAAAAAAAAAAAAAAAAAAAAAAApXI/C9Si8P5R0lGKMAl94lGgNaBBLAIWUaBKHlFKUKEsBSwOFlGgaiUMY"
        "C0fmBDyfvj+z0Qhs6wPwPwAAAAAAAAhAlHSUYnWGlGIu"
    ),
}
#: The estimate both releases held when they pickled it.
X = [0.11961722488038277, 1.000956937799043, 3.0]
P = [
    [0.009808612440191388, 0.00047846889952153117, 0.0],
    [0.00047846889952153117, 0.2588038277511962, 0.0],
    [0.0, 0.0, 0.11],
]
F = np.array([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])

MAKER = """
import base64, json, pickle
import numpy as np
from navkit.estimation import ExtendedKalmanFilter
ekf = ExtendedKalmanFilter([0.0, 1.0, 3.0], np.diag([0.5, 0.25, 0.1]), angle_states=(2,))
F = np.array([[1.0, 0.1, 0.0], [0.0, 1.0, 0.0], [0.0, 0.0, 1.0]])
ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(3))
ekf.update([0.12], lambda x: x[:1], np.array([[1.0, 0.0, 0.0]]), [[0.01]])
print(json.dumps({"pickle": base64.b64encode(pickle.dumps(ekf)).decode(),
                  "x": ekf.x.tolist(), "P": ekf.P.tolist()}))
"""


def _steps(ekf: ExtendedKalmanFilter) -> tuple[np.ndarray, np.ndarray]:
    ekf.predict(lambda x: F @ x, F, 0.01 * np.eye(3))
    ekf.update([0.3, 2.9], lambda x: x[[0, 2]], np.array([[1.0, 0, 0], [0, 0, 1.0]]),
               np.diag([0.01, 0.02]), angle_measurements=(1,))  # fmt: skip
    return ekf.x, ekf.P


def _check(loaded: object, x: list[float], p: list[list[float]]) -> None:
    assert type(loaded) is ExtendedKalmanFilter
    assert isinstance(loaded, ExtendedKalmanFilter)
    np.testing.assert_array_equal(loaded.x, x)
    np.testing.assert_array_equal(loaded.P, p)
    assert loaded.angle_states == (2,)
    assert loaded.dim == 3
    fresh = ExtendedKalmanFilter(x, p, angle_states=(2,))
    for got, want in zip(_steps(loaded), _steps(fresh), strict=True):
        np.testing.assert_array_equal(got, want)
    # It pickles and copies as a filter of today.
    again = pickle.loads(pickle.dumps(loaded))
    np.testing.assert_array_equal(again.x, loaded.x)
    np.testing.assert_array_equal(copy.deepcopy(loaded).P, loaded.P)


@pytest.mark.parametrize("commit", sorted(OLD))
def test_an_old_pickle_loads_with_its_estimate_and_steps_as_a_new_filter(commit: str) -> None:
    _check(pickle.loads(base64.b64decode("".join(OLD[commit]))), X, P)


class Tagged(ExtendedKalmanFilter):
    __slots__ = ("tag",)


class Noted(ExtendedKalmanFilter):
    pass


def test_a_subclass_still_copies_its_own_attributes() -> None:
    tagged = Tagged(X, P, angle_states=(2,))
    tagged.tag = "a"
    noted = Noted(X, P)
    noted.note = [1, 2]
    assert pickle.loads(pickle.dumps(tagged)).tag == "a"
    copied = copy.deepcopy(noted)
    assert type(copied) is Noted
    assert copied.note == [1, 2]
    np.testing.assert_array_equal(copied.x, X)


def test_a_state_without_an_estimate_is_refused_clearly() -> None:
    shell = object.__new__(ExtendedKalmanFilter)
    with pytest.raises(ValueError, match="holds no estimate"):
        shell.__setstate__((None, {"_angles": (2,), "_n": 3}))
    shell = object.__new__(ExtendedKalmanFilter)
    with pytest.raises(ValueError, match="no attribute 'colour'"):
        shell.__setstate__({"_x": np.array(X), "_p": np.array(P), "colour": "red"})


@pytest.mark.slow
@pytest.mark.parametrize("commit", sorted(OLD))
def test_the_old_pickles_are_what_those_releases_made(commit: str, tmp_path: Path) -> None:
    made = made_at(commit, MAKER, tmp_path)
    assert made["pickle"] == "".join(OLD[commit])
    _check(pickle.loads(base64.b64decode(made["pickle"])), made["x"], made["P"])
