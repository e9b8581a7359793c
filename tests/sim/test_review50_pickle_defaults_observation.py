"""Review 50 (PARKED): an Observation pickled before ``dt`` existed loads with ``dt`` None.

``Observation`` gained ``dt`` (the command's hold) at commit 2b0934e. Its
pickles of before hold the eight other fields as a list, which the slotted
dataclass's own ``__setstate__`` zipped onto the fields: ``dt`` was left
unset, and ``repr(obs)`` and ``obs.dt`` raised ``AttributeError`` (a
subclass's too). ``Observation`` names ``dt`` in ``_added_fields`` (not
known: None) and restores through ``restore_read_only``, which fills it in.

The pickles below are real: made by navkit at commit 7b0f979 (the one before
2b0934e) from an ``Observation`` and a plain subclass, protocols 0, 2 and 5;
``test_the_pickles_are_the_old_releases`` makes them again there (slow; a git
checkout of the project).
"""

from __future__ import annotations

import base64
import copy
import pickle
import types
from pathlib import Path

import pytest

from navkit.geometry import Pose2D
from navkit.sim import Observation
from old_release import install_module, made_at

OLD_COMMIT = "7b0f979"
MODULE = "review50_old_observations"
SUBCLASSES = "from navkit.sim import Observation\nclass Tagged(Observation):\n    pass\n"
ARGS = (0.25, None, None, None, None, (), Pose2D(1.0, 2.0, 0.5), Pose2D(1.0, 2.0, 0.5))

#: Makes the pickles (run against the source of ``OLD_COMMIT``): base64 by "class/protocol".
MAKER = f"""
import base64, json, pickle, sys, types
mod = types.ModuleType({MODULE!r})
sys.modules[mod.__name__] = mod
exec({SUBCLASSES!r}, mod.__dict__)
from navkit.geometry import Pose2D
from navkit.sim import Observation
args = {ARGS!r}
out = {{}}
for name, obj in (("Observation", Observation(*args)), ("Tagged", mod.Tagged(*args))):
    for protocol in (0, 2, 5):
        data = pickle.dumps(obj, protocol=protocol)
        out[f"{{name}}/{{protocol}}"] = base64.b64encode(data).decode()
print(json.dumps(out))
"""

OLD_PICKLES = {
    "Observation/0": (
        "Y2NvcHlfcmVnCl9yZWNvbnN0cnVjdG9yCnAwCihjbmF2a2l0LnNpbS5fc2ltdWxhdGlvbgpPYnNlcnZh"
        "dGlvbgpwMQpjX19idWlsdGluX18Kb2JqZWN0CnAyCk50cDMKUnA0CihscDUKRjAuMjUKYU5hTmFOYU5h"
        "KHRhY25hdmtpdC5nZW9tZXRyeS5fcG9zZQpQb3NlMkQKcDYKKEYxLjAKRjIuMApGMC41CnRwNwpScDgK"
        "YWc2CihGMS4wCkYyLjAKRjAuNQp0cDkKUnAxMAphYi4="
    ),
    "Observation/2": (
        "gAJjbmF2a2l0LnNpbS5fc2ltdWxhdGlvbgpPYnNlcnZhdGlvbgpxACmBcQFdcQIoRz/QAAAAAAAATk5O"
        "TiljbmF2a2l0Lmdlb21ldHJ5Ll9wb3NlClBvc2UyRApxA0c/8AAAAAAAAEdAAAAAAAAAAEc/4AAAAAAA"
        "AIdxBFJxBWgDRz/wAAAAAAAAR0AAAAAAAAAARz/gAAAAAAAAh3EGUnEHZWIu"
    ),
    "Observation/5": (
        "gAWVowAAAAAAAACMFm5hdmtpdC5zaW0uX3NpbXVsYXRpb26UjAtPYnNlcnZhdGlvbpSTlCmBlF2UKEc/"
        "0AAAAAAAAE5OTk4pjBVuYXZraXQuZ2VvbWV0cnkuX3Bvc2WUjAZQb3NlMkSUk5RHP/AAAAAAAABHQAAA"
        "AAAAAABHP+AAAAAAAACHlFKUaAdHP/AAAAAAAABHQAAAAAAAAABHP+AAAAAAAACHlFKUZWIu"
    ),
    "Tagged/0": (
        "Y2NvcHlfcmVnCl9yZWNvbnN0cnVjdG9yCnAwCihjcmV2aWV3NTBfb2xkX29ic2VydmF0aW9ucwpUYWdn"
        "ZWQKcDEKY19fYnVpbHRpbl9fCm9iamVjdApwMgpOdHAzClJwNAoobHA1CkYwLjI1CmFOYU5hTmFOYSh0"
        "YWNuYXZraXQuZ2VvbWV0cnkuX3Bvc2UKUG9zZTJECnA2CihGMS4wCkYyLjAKRjAuNQp0cDcKUnA4CmFn"
        "NgooRjEuMApGMi4wCkYwLjUKdHA5ClJwMTAKYWIu"
    ),
    "Tagged/2": (
        "gAJjcmV2aWV3NTBfb2xkX29ic2VydmF0aW9ucwpUYWdnZWQKcQApgXEBXXECKEc/0AAAAAAAAE5OTk4p"
        "Y25hdmtpdC5nZW9tZXRyeS5fcG9zZQpQb3NlMkQKcQNHP/AAAAAAAABHQAAAAAAAAABHP+AAAAAAAACH"
        "cQRScQVoA0c/8AAAAAAAAEdAAAAAAAAAAEc/4AAAAAAAAIdxBlJxB2ViLg=="
    ),
    "Tagged/5": (
        "gAWVoQAAAAAAAACMGXJldmlldzUwX29sZF9vYnNlcnZhdGlvbnOUjAZUYWdnZWSUk5QpgZRdlChHP9AA"
        "AAAAAABOTk5OKYwVbmF2a2l0Lmdlb21ldHJ5Ll9wb3NllIwGUG9zZTJElJOURz/wAAAAAAAAR0AAAAAA"
        "AAAARz/gAAAAAAAAh5RSlGgHRz/wAAAAAAAAR0AAAAAAAAAARz/gAAAAAAAAh5RSlGViLg=="
    ),
}


@pytest.fixture
def subclasses(monkeypatch: pytest.MonkeyPatch) -> types.ModuleType:
    """The subclass's module, where the pickles find it."""
    return install_module(monkeypatch, MODULE, SUBCLASSES)


def _check(obs: Observation, name: str, module: types.ModuleType) -> None:
    cls = Observation if name == "Observation" else module.Tagged
    assert type(obs) is cls
    assert obs.dt is None
    assert (obs.t, obs.new, obs.estimate, obs.true_pose) == (0.25, (), ARGS[6], ARGS[7])
    assert obs.scan is None and obs.encoders is None
    assert repr(obs) == repr(cls(*ARGS))
    # Copied and pickled again as today's.
    again = pickle.loads(pickle.dumps(obs))
    assert type(again) is cls
    assert repr(again) == repr(obs)
    assert copy.deepcopy(obs).dt is None


@pytest.mark.parametrize("key", sorted(OLD_PICKLES))
def test_an_observation_pickled_before_dt_loads_with_dt_none(
    key: str, subclasses: types.ModuleType
) -> None:
    data = base64.b64decode("".join(OLD_PICKLES[key]))
    _check(pickle.loads(data), key.split("/")[0], subclasses)


def test_todays_observations_keep_their_dt(subclasses: types.ModuleType) -> None:
    tagged = subclasses.Tagged(*ARGS, dt=0.05)
    tagged.note = "kept"
    for obs in (Observation(*ARGS, dt=0.05), tagged):
        for protocol in range(pickle.HIGHEST_PROTOCOL + 1):
            back = pickle.loads(pickle.dumps(obs, protocol=protocol))
            assert type(back) is type(obs)
            assert repr(back) == repr(obs)
            assert back.dt == 0.05
    assert pickle.loads(pickle.dumps(tagged)).note == "kept"
    assert copy.deepcopy(tagged).note == "kept"


@pytest.mark.slow
def test_the_pickles_are_the_old_releases(tmp_path: Path, subclasses: types.ModuleType) -> None:
    # Made again by the source of OLD_COMMIT: the same bytes, and they load as above.
    fresh = made_at(OLD_COMMIT, MAKER, tmp_path)
    assert fresh == {key: "".join(parts) for key, parts in OLD_PICKLES.items()}
    for key, data in fresh.items():
        _check(pickle.loads(base64.b64decode(data)), key.split("/")[0], subclasses)
