"""Review 53 (FOUND5): fields and Field D* pickled on 23 November 2026 load, or are refused clearly.

Pickles made before 5e5f83f (and up to 0123de4, 30 November) name the modules
``navkit.planning._fields``, ``navkit.planning._field_dstar`` (and
``navkit.planning.reactive._fields``), which moved: loading one raised
ModuleNotFoundError (FOUND4's survey, review 52). Those names now answer with
today's public classes (``navkit._shared.moved``, an import finder, no file):

* the potential fields, then plain slotted classes with other names
  (``goal``, ``rad_thr``, ``r``, ``s``, ``d0``, ``obstacles``), load with their
  values under today's names (``_renamed_fields``), as fields built today with
  them (today's laws, corrected since, as for a 0123de4 pickle);
* a ``FieldDStar`` of then meets the refusal its state has had since review
  51 (no search state to carry over: "build the planner again");
* ``FieldPath`` and ``FieldGrid``, gone since, are a ValueError naming them.

Real pickle bytes made at 98fb796 (``tests/old_release.made_at``); a slow test
makes them again there and at 5e5f83f.
"""

from __future__ import annotations

import base64
import copy
import pickle
import sys
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.planning import (
    BlendedAttraction,
    ConicAttraction,
    KhatibRepulsion,
    ParaboloidAttraction,
    PiecewiseAttraction,
    PiecewiseRepulsion,
    PotentialField,
)

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import made_at

POINTS = np.array([[0.3, 0.4], [1.2, -1.7], [-1.0, 1.5], [2.5, 0.5], [0.9, 1.1]])
OBSTACLES = [[0.0, 0.0], [1.0, 1.0], [-0.5, 2.0]]

#: The fields of MADE_AT_98FB796 built today, with today's names.
TODAY = {
    "ParaboloidAttraction": lambda: ParaboloidAttraction(
        (1.0, -2.0), k_att=2.0, c=0.5, a=1.5, b=0.7
    ),
    "ConicAttraction": lambda: ConicAttraction(
        (1.0, -2.0), m=1.5, u_trans=0.8, threshold_radius=0.3
    ),
    "BlendedAttraction": lambda: BlendedAttraction(
        (1.0, -2.0),
        k_att=1.3,
        c=0.9,
        a=1.1,
        b=0.8,
        threshold_radius=0.4,
        width=0.2,
        m=1.2,
        u_trans=0.9,
    ),
    "PiecewiseAttraction": lambda: PiecewiseAttraction(
        (1.0, -2.0), alpha=2.0, goal_radius=0.3, spread=1.5
    ),
    "KhatibRepulsion": lambda: KhatibRepulsion(OBSTACLES, k_rep=2.0, influence_radius=1.5),
    "PiecewiseRepulsion": lambda: PiecewiseRepulsion(
        OBSTACLES, delta=1.5, beta=0.8, obstacle_radius=0.2, spread=1.3
    ),
    "CompositeField": lambda: (
        ConicAttraction((1.0, -2.0), m=1.5, u_trans=0.8, threshold_radius=0.3)
        + KhatibRepulsion(OBSTACLES, k_rep=2.0, influence_radius=1.5)
    ),
}

#: What the slow test runs at an old commit: the fields of TODAY, with that day's names.
MAKER = """
import base64, json, pickle, zlib
from navkit.planning import (BlendedAttraction, ConicAttraction, KhatibRepulsion,
    ParaboloidAttraction, PiecewiseAttraction, PiecewiseRepulsion)
obstacles = [[0.0, 0.0], [1.0, 1.0], [-0.5, 2.0]]
fields = {
    "ParaboloidAttraction": ParaboloidAttraction((1.0, -2.0), k_att=2.0, c=0.5, a=1.5, b=0.7),
    "ConicAttraction": ConicAttraction((1.0, -2.0), m=1.5, u_trans=0.8, rad_thr=0.3),
    "BlendedAttraction": BlendedAttraction(
        (1.0, -2.0), k_att=1.3, c=0.9, a=1.1, b=0.8, rad_thr=0.4, width=0.2, m=1.2, u_trans=0.9
    ),
    "PiecewiseAttraction": PiecewiseAttraction((1.0, -2.0), alpha=2.0, r=0.3, s=1.5),
    "KhatibRepulsion": KhatibRepulsion(obstacles, k_rep=2.0, d0=1.5),
    "PiecewiseRepulsion": PiecewiseRepulsion(obstacles, delta=1.5, beta=0.8, r=0.2, s=1.3),
}
fields["CompositeField"] = fields["ConicAttraction"] + fields["KhatibRepulsion"]
out = {}
for name, f in fields.items():
    f.force([[0.3, 0.4], [0.9, 1.1]])  # used first, as a pickled field most often is
    out[name] = base64.b64encode(zlib.compress(pickle.dumps(f), 9)).decode()
print(json.dumps(out))
"""

#: The fields of TODAY pickled at 98fb796 with that day's names (zlib, base64).
MADE_AT_98FB796 = {
    "ParaboloidAttraction": (
        "eNotTr1KxEAQzp4XbBQs5HyFs9naQjjligMDQXyBMNkk53J7u2FvIqQQtDj1YLob38dHsbK2tNM1yVcMfD8z"
        "8z2N3yci6kBnFh5WGmVtwFptlzKrdGmKDdPpLXjInXG6uEb0oFA7y3s+f+b0kackgBezn+GMyAP5qjqQUIF8"
        "Dk68ygCRF1fRIIyXDgzTxDbrupWZcr6U68agBu+hZTrKfKmc3aBvFIZ/FHdJpkNb9JE9J9GW5+HnK9/xNBHJ"
        "aMv3xxQX2Nbl/8qouuDdW+8ekLjkNE1vfgO6kUTI+W5+0hf6ng3NPjjIzQvn8g8dD2i3"
    ),
    "ConicAttraction": (
        "eNotjrFOwzAQhuPSKkskmOAVyuKFhQGpQhmQiJSBF7AcJ20tEjtyzkgZkGAoUOm2HgM8De/AU7AxsoGb8A13"
        "0n//f3cP09eERQN4YuTdrQbe1tIYbVZcLHVVlx3hYWqNVpcATirQ1tCOTh8pv6c5soauFj//G2InSwFrF6TP"
        "swGMvQgp0wXp623PO05XVtaEx8Y3bc+Fsq7ija9BS+dkT5gIVylrOnBeQTiFs8FJGJtytOwoizaUsoKe6Ybm"
        "GcsmG1onOCuhb6t9ZLI8p+3LOD1AdkF5nl//BoaSRUDFNj0a3/5ejD36oCD7Jyr4H5npamU="
    ),
    "BlendedAttraction": (
        "eNpNkL9OwzAQxuPSKAsDXeAVypKFhQGpgg5IRMrAwmi5sdtYTZzIuYAyIMFQoJK3HkN5GlYkeAAeAYkBBDs4"
        "f5D4hrO+n7+zT3fVvz8jTiOzo9j5XIKfJ0wpqWY+nUqR8ALN4CgRigt+CKBZBDJTuMLdawwvcWgIw+PR57rW"
        "gyETa97+TGTN+3OtF+POKQOw4LsDJLXma6+R8TTjFGJt0WvX7ZXU/qaK/29cSA6xBU9dpj/LWIJmW5VpXvk0"
        "yrTw0zIBybRmFZpNqkWUqQJ0GYGd2bhNEo2neBtZYeAscGznvsVTHAYk6C0wHhiXQ5WLuqU33cflXXu7YcgB"
        "hmF48mPVlMABnCzHW+0OP0bt6TyixeUNTvxfrHuWxA=="
    ),
    "PiecewiseAttraction": (
        "eNotjsFKw0AQhrO1wR56EAR9hXrZSy8ehCo9FAwE8QXCZrNtF7ebsNkoOQh6qFqYW3/fp+/gi3j0pjHJdxiY"
        "+f+Z+V+GnyMWtNC5FY8P2vPCCGu1XfFkqZXJStDpnVZSPelS3XjvhPQ6t9jj4hXxMyYUClOsBRbXQX+JOSxm"
        "X9MWYmXT/PTKcJULAzqz1aaoeSJzp/imMl4L50QNGidOydyW3lXSNy8obJ2gY5t1lj2iYIs5S/GOe0wiFg22"
        "WI8pzHxdqP+VwfISu49OPSJ2hTiOb38b2hIFHuluftIF+p71mQ9oxtUbUv4H6mZkLg=="
    ),
    "KhatibRepulsion": (
        "eNprYJkqz8gABj3ieYll2ZklegU5iXl5mXnpevFpmak5KcVTevi9MxJLMpOCUgtKc4oz8/OmTJ6i2TjFr3aK"
        "Rg9TisEUd/sfUCNYs+OLUgumuDswQAU485OKSxKTc1KBpojlleYWVOrFJ+cXperlluaUZCYWFSVWTunhAWpK"
        "zs8rLikqTS4Bmt3DClY5pYc9LwWiZPIUb4bWKc6MSVPapwRN0fBm9Gb2ZmqbksHdw5pSUlmQCtLElGYxpbMD"
        "Is/cw2gzxc/Pz+s/EIAJb4aSKUmdzgYMWMEHe1T6wX6ohMMUoLbStilJegCEkWOL"
    ),
    "PiecewiseRepulsion": (
        "eNprYJlqx8gABj3ieYll2ZklegU5iXl5mXnpevFpmak5KcVTeoQCMlOTU8szi1ODUgtKc4oz8/OmTJ6i2TjF"
        "r3aKRg9LUmpJ4hR3+5czQWBWD2tKag5Y4AfUYMYiIOckVJaxGMj5cgYEzvZw5icVlyQm56QCLRHLK80tqNSL"
        "T84vStXLLc0pyUwsKkqsnNLDE1+UmpyfV1xSVJpcArS3hxWsckoPe14KRMnkKd4MrVOcGZOmtE8JmqLhzejN"
        "7M3UNiWDF+iWksqCVJAmpjSLKZ0dEHnmHkabKX5+fl7/gQBMeDOUTEnqdDZgwAo+2KPSD/ZDJRymALWVtk1J"
        "0gMA2yh4zA=="
    ),
    "CompositeField": (
        "eNptUE1Lw0AQTdLWIohWRD15r5dQ8OJBaCVgwUAO/QNhk2ybpclu2GyEHgQ9tLWwt44H/TP6G/QPePXm0Ztu"
        "vkTBd5iBN2923tub5v2LrhWQhxRdTYkwkwhRSujEdMcER0EKctticcJSIvBFzsAajm/BuQa5USlCTe5YjBL/"
        "XAiOfEEY/RF1pR7DsP9ZXWlzFLgi5Ip6PSkg25mrtmiqqPeHHI+yOWEoAnlAsziZma7PODbjLBIEcY5mILdc"
        "jn1GU8EzX6hTslUoQbZpUErWYGtzsHQPljCCrq3bxhzCXdkKxCzB+YoxPoXVXTltSP0MHMe5/FIoiq0J8FZW"
        "p7T90S+79gyKzhbg5ZHtEAnijXCSRenfyEbQ+5W5NVV2ExgOqkfkJvNSgfwIq6/rhHu503C/9tmwjQWERyur"
        "p/2L2kvd356qwaD2toBUVfMbHV+k4w=="
    ),
}
#: FieldDStar pickled at 98fb796 (zlib, base64).
FIELD_DSTAR_98FB796 = (
    "eJztWM1v3EQU383nEqo0ggIt4oyCdr1K0jRaiaBUKaKBlRYEqog44I7HY3tYezwd27ubSpAgCE2KhYoywIFQUsQB"
    "CSHBLeLEH8Ch4i+gBxDHHDhUSFDe+GPJJikHShGIjJR5H/P29948v/E8Z2XgvS/GCsmIH2Go1aRhlbuIMcrsqm5R"
    "4pq6GYRIyHjkKSU9+YISNuRjr8tX5Xg8qAu/Hcj6EHDYd4ErxUN6m5qhI+sj8YDOkSnjB1nk8aUqWAhS9SI3pEgI"
    "tCTjI7og2GdBKCIcAmo8mFjKeJiZqcmGrBdW5ZmiIS/J5+V4vVh/blU6R+JBM1ziRP2kz6rJ9bV0tT8uzspGo/HM"
    "LRjJVC+E0lifX+krZGNn+S7RuTuk/xTeX93Pf3W/fxfeHVMJlRgP65SFRHC5Fo/oru83kUPgiKzBQuD5PhwbxToB"
    "Ri6RZ+d+3LpqLT/+LZwplh60YcWmJ+2euE+3pXOvM6qOiDOWH5A5EI6vz98sFgp3ayuH9N9Nk1Ib0IUTHNbHIb1N"
    "fQzq8OrhcvzgCnkg7qO7LlbnxEHXqqqhiXNj7V9f208XZr+6rOiXo18/8cG51HMJ/r7fOrWh9KevpvSnjH62R7/4"
    "cUp5pucv9+KWjqa4xQx3bPmXWSXneLmf8x9l9P2U1rZ66ZXMT457/mhvvLnfnRez/X2Y2q9sHoyX67+51ou7vQd3"
    "4Z3efedxdOPJ1rc3e/NyPdvPhOy1W9j887gW3+3NZ45381pvnnK8zpVeeS+uqqEDSqfe91byetnpLxQ++eHRZx96"
    "4+Qxevk38t2NY/SlNwufXn97c3v+Rum+n6F/jE9Au2egatIXqn4uqCIDmkEEzWB8v640uxtEXzWe8TD2+ZIgtoxH"
    "9y8e3weoblIkAvjd03Dx2iQxKxkRhS6UgXrIN14hSfPZuJS0tAMMeQQ6UbinZ6aVKQ2zfvZ0PBRQmxF1Xat21ySy"
    "/nCkdr4Knju1GX1mWotYk/ltprmURR3NZhF0zsLHTRK6qEnk4ueQl/LMNKBWysjswESCioa8joZanVOTU6AA3rAm"
    "Z1It9j3ukk4qWDxXW7yWWkKYtVTl+S2RQYXWyQwopC4BrtVJpsmJ6mRFS5mpRJPO4DfxmPM0RK7dldo5h82cMy/k"
    "nNVl+B8A1PJQzrcMj+7mux5bbpeD741Ktv8Wn0o6pAAeSned+xyzEJwqowRcMUw9/RYRqV0XRDEAkWSqK0G2kjiS"
    "ADSMPQ4zxI5dk3h+SBRnuVHg+DxUfNuAdfciET5IkFmQPI5xB5mQAyywyi/uqB3jDuSf2FzAzC5gD9YhlRhmFSZM"
    "08AGdmCgALxYnUBUyralYnUECQh4o6zFMTUrWtOtaG6bV8ruRdhupex58NjAuUESYlIBhZOzAJA9ca+NaAgVwiA2"
    "jcGmOHbhK6uicciPRW1gmhFokySCwAGVC2KREDtUsRZ22qAP24JCJjQOaZgCa0iUQD5VkQiTqwCBiEhJgpmKBIQo"
    "GnqVcoAc6zavBBBq6V1x63D8L8fBhVFMCuNMqZANZQUv/n696cmzuRK+d9T/H0LZgHeu7SNXNiKj+juLuhx+"
)
#: FieldPath pickled at 98fb796 (zlib, base64).
FIELD_PATH_98FB796 = (
    "eJxtjz9LxEAQxZP75x1YitVV2kSQxVJBMHig4EIQv0DYZPfuFnOTZbMRUyhaeHow3Y3fyA9ka6W5RLDxFfN4M+9X"
    "zFPvPfC9RjgGcXerHTOZANAwY/FUq0zGsnDCEo4uNulauDmt6eCZHijAgck1uIJwF8qFqVic5laxRZk5LawVFeF2"
    "bFWaQ+FsmboaxH7TJNwC2VbWxL0XmvgJvdINBdznXd5Z0nyEfekqozZQZ3pMq7f23kX/lKIouvqu1QzuOUpWkyPv"
    "Xw3D1j/PWt/5zeOQagx7aV44ugz3vs4P9z8ecZApmNU//m2G6t4IkEoSPykT9gObymnH"
)


def _load(text: str) -> object:
    return pickle.loads(zlib.decompress(base64.b64decode(text)))


def _check_field(name: str, old: object) -> None:
    today = TODAY[name]()
    assert type(old) is type(today)
    assert isinstance(old, PotentialField)
    # Its values under today's names, and today's laws (corrected since: a field of
    # then gives today's potential and force for them, as a 0123de4 pickle does).
    assert repr(old) == repr(today)
    np.testing.assert_array_equal(old.potential(POINTS), today.potential(POINTS))
    np.testing.assert_array_equal(old.force(POINTS), today.force(POINTS))
    # A record as today's: frozen, copied and pickled as today's.
    with pytest.raises(AttributeError):
        old.k_rep = 3.0  # type: ignore[attr-defined]
    for again in (pickle.loads(pickle.dumps(old)), copy.deepcopy(old)):
        assert type(again) is type(today) and repr(again) == repr(today)
        np.testing.assert_array_equal(again.force(POINTS), today.force(POINTS))


@pytest.mark.parametrize("name", sorted(MADE_AT_98FB796))
def test_a_field_of_the_first_days_loads_with_its_values(name: str) -> None:
    _check_field(name, _load(MADE_AT_98FB796[name]))


def test_arrays_of_an_old_field_are_read_only() -> None:
    old = _load(MADE_AT_98FB796["KhatibRepulsion"])
    assert isinstance(old, KhatibRepulsion)
    assert not old.obstacles_xy.flags.writeable
    old_goal = _load(MADE_AT_98FB796["ConicAttraction"])
    assert isinstance(old_goal, ConicAttraction)
    assert not old_goal.goal_xy.flags.writeable


def test_a_field_dstar_of_then_is_refused_clearly() -> None:
    with pytest.raises(ValueError, match=r"^FieldDStar: a pickle made by navkit before .*build"):
        _load(FIELD_DSTAR_98FB796)


def test_a_class_gone_since_is_named() -> None:
    with pytest.raises(ValueError) as info:
        _load(FIELD_PATH_98FB796)
    message = str(info.value)
    assert message.startswith("navkit.planning._field_dstar.FieldPath: a pickle made by navkit")
    assert "build the object again" in message
    fields_module = __import__("navkit.planning._fields", fromlist=["FieldGrid"])
    with pytest.raises(ValueError, match=r"_fields\.FieldGrid: .* no longer has"):
        fields_module.FieldGrid  # noqa: B018
    with pytest.raises(AttributeError):
        fields_module.__path__  # noqa: B018


def test_no_other_module_name_is_answered() -> None:
    with pytest.raises(ModuleNotFoundError):
        __import__("navkit.planning._astar_old")
    with pytest.raises(ModuleNotFoundError):
        __import__("navkit.planning.reactive._fieldz")


@pytest.mark.slow
@pytest.mark.parametrize("commit", ["98fb796", "5e5f83f"])
def test_fields_pickled_then_load_again(commit: str, tmp_path: Path) -> None:
    made = made_at(commit, MAKER, tmp_path)
    assert sorted(made) == sorted(TODAY)
    for name, text in made.items():
        _check_field(name, _load(text))
