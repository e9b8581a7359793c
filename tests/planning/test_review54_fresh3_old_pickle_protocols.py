"""Old pickles at protocols 0 and 1, and the old module names under importlib (review 54, FRESH3).

Review 53's first-days pickles (OLDMODS) were made with pickle's default
protocol; protocols 0 and 1 take another way: ``copyreg._reconstructor(cls,
object, None)`` and the state set after (``BUILD``), the class looked up by
its old module name all the same. Real bytes of aa060be at protocols 0 and 1
(``tests/old_release.made_at``, MAKER of review 53's OLDMODS test with
``protocol=``): the records load as today's, and the paths gone since are
refused by name, as at the default protocol. (A ``BehaviourTarget``, a
NamedTuple then, cannot load at these protocols: review 54's FOUND8 test;
``PotentialFieldController`` and the potential fields, plain slotted classes
then, could not be pickled at them.)

The old names' modules under importlib's other ways in (review 53's tests
cover ``importlib.reload`` of the finder's module, ``python -m`` and
``hasattr``): a reload of an old module keeps answering; an old name is no
package (a name under it is ModuleNotFoundError, not a crash of its
``__getattr__``); :func:`pkgutil.resolve_name`, which configuration files'
``module:object`` strings go through, answers as pickle does; and
:func:`inspect.getmodule`, which walks every module in ``sys.modules`` asking
for ``__file__``, passes over them.
"""

from __future__ import annotations

import base64
import importlib
import importlib.util
import inspect
import pickle
import pkgutil
import zlib
from pathlib import Path

import pytest

from navkit.behaviours import GameState
from navkit.mapping import LocalGrid
from navkit.mapping.io import CarmenLog, read_carmen
from navkit.planning import GreedyStep, greedy_step

#: aa060be's MAKER objects pickled with protocols 0 and 1 (zlib, base64).
MADE_AT_AA060BE = {
    0: {
        "CarmenLog": (
            "eNqlVE1r20AQvfRQhv6NFl8i9lsSFBpoCRiCKSn4VBCr9Va4taVFWhf0r3vssTNrxbHTUNREoNGwO/Pm6T2tnOvC"
            "WPW+AQyua4fYH1zseggMFq61P39sY7a3IWzbJquc7fe+hY/pcds1EDi4qqoP213ctlUFXf3duwhBwCoGCXdBwWIX"
            "NCyap+AGZ1u4tYPvv1AWDDSpMcfGghpLcO1hH0ac3PU+2x9wjO17O16wRRYJnSqh3RwLAuewWDKIgQvk6LqNdwP4"
            "lhLclLBY1/hUsN5Z5M4x11RscDbPKSsoKxGEgCSuCDbRgU0cA6II3Fl/KzARsGQMb05l9N5Cpab1e9zUsFqtllcc"
            "0k2UhIGaGprE4+uB4fXv+OvDnKpjvJ5T9OYameXIgN5a0LuKEjPJoLY3VzzTOctLI4XJS1WUxoC9eXKRZQyjzDTY"
            "la3J5ubeRskRVQoyUkqcRHsnV6TCFdJZaqoyZzpLpIX6/Z9Av2cJ9GqWNq9RG1lM2siSPmOirPiLtEEAAfbiJDS+"
            "2/vY4/cdusHDZwziEwQlJwWVotmaFFQGEI8nVJGihEnvh3I6OCqdHFVSuTovRxbIQbOJw0ObJp908klLmFifZum/"
            "xmhipRMrnVjJs3p5nJKDfWS4LibDNQlq2GS4wBXDn2H421lWvkMrjZisNHQyjaJMo5WPCKJlR4KGZDTFRBCPdeoo"
            "Txwv/nj1GP0AIUeoeBdy+gHkAsHr7A8QEGcJ"
        ),
        "GameState": (
            "eNq11M2K2zAQAOD7HPsUudRY/zYUuqeWXHJowaeCkRXX6zaRhCV3ydvtI/UROuN4Ib5tAjVIHiyN9ElIdi7ESzv1"
            "A2Dlgk95ml0OE8QSds7bP7/HXMST9X70Q9Gm4Fw/wVd77r9nm3uIDFzbdvN4yqNvWwjdr95liBwOOQr4FiXsjlFB"
            "M4Uu4HcNzs/neClaF6a+OM+YZ6fJXjbzQzQ0O3UEf7y2xwp2+xJyrHFGF469S9B7ChCB2KbDN4PmZFHCMObYlxGB"
            "SYoURRrHYFiWNrNa4JgvkUbBGZqfFQY17MsSC8NuvMRETkkCmk+4Mlza4bD/yGApJOICOkoYFsePucTn/9VIkDgV"
            "LYHTorimyECXms6eTthcwYD7N7xtGK+xO+2BoKUIdrMHgsPAGdyH//v5frIQK1lIMiiKNJHDi2+HYJEtzJYtqjd2"
            "TeeovGFL9gD7w+v9bMlXtlzOMmmkWtgxBt/7vNql3tqlWe2yorz6xq7KR+xP99sVW+2Ko0EJiiTZc2/PZ7y8Cfuo"
            "rVvp1a0M5VSrG7nLQPUD9Gv9+r6DhT+IclVrhgK9ROJ2x1Gt5Vat1arWmnLMVq2rh9VP71bXq9rQFTP03zCc1DGk"
            "1Kc0Bt9O9jjOqDcCvpQFXt3UPNvUXu+skQvw5mC9jPn5rVHBIXXFP5eEh+8="
        ),
        "GreedyStep": (
            "eNpVkEFOhTAQhvdzEjaSdigFEpO3e4YNC03YklIqorwygaLhKCYuvIZH8TZOn24kmc6f/vNPv2DtQke3uhH4sIvf"
            "wrrbsKxAAhLrzevLFFKajfeTH9NuXJ0bDri7tofgCEiC7bp+n+Yw+a6DpX92NgAhNIEyuCcFyUA5tNbNM5CGpJYS"
            "aqkgUAFb+2YOWibPiRKs3y90pJ1dVpdedt5o1tUc/9CAqggWB8EPvz5Jhq0Fb5SRxi6Dsxs4HwWbCEnbc8+gnQ1T"
            "StbxeZkzntRRFVGVkY0L4031RwNDOIi3ID/RPpYsmF4ILsljiBzEjEO8/JZNBU3T1Dc8EysiYQ59DIxXjo/3+H2f"
            "Pq/968QRzVbEwQiBZVQV9Fs7AmUCziJVEjMpco25loXWyH/tiT0JZ5lqVaFCzAWqQmjFljV+mAYT3MYzCLXKStj6"
            "9AfO3ZGW"
        ),
        "GridPath": (
            "eNrFVE1LxDAQxa89zC/pxZKk3bYLnpVeFvGQk1DSNNRqNw1JKvbfO7N6Ebx4CBaSPsibNy8DL1ovbuu8GQE3vdgQ"
            "/arj4sExyLRV729TzN2srJ3smHcqROXhwU/Do4ov4DjoruvXaY6T7TpY+lejIzgBx+gKeHIlZIPbg9RmngO4CrRd"
            "T27LO714k59WrFPeq+1Hd3A19SYi2OHr3DWQtQyiO2BHvQxGBzCWAJpAq7LHPwc5K3TCEQvkcrLAS0J7QhVqcFoM"
            "2vN5/e0Hhrg5UsIucmoQHKBlyGIcaYJhsaDCAuQd3g6vdzy2txzOi1yJAnoqGM9enleGX7r94r+pl0lUr5KoXidR"
            "vUkyrF2SYe2SDGuXZFh/UMUglhg4CrKgeIuKUA19kHoJ9Ao1cH/IG9GUouairMsKYx2k+XDKDmZAAqYcX4YgZ2NH"
            "es4K9ltFn38CaGVgyA=="
        ),
        "WorldPath": (
            "eNqtVLtKxUAQBQuLKQT/4jaG7OZ1A8K1EtJcxCI2Qkg2a4zm7g7JRszX+Qt+hh9wSwtnoo0gkiKBnRyYM2fPFGeV"
            "sjgVvW6AirJmcP2onO0BfdgoU748t87DrjSmNY1XMCqwdI9wZ/uuvmGEAlRRVGPbudYUBdjqSSsHKGHvMIBbDGFT"
            "YwQ52ta4ATAGZcYDTl6hbK+9w0iDZd+X0y8PgAk7YCKY+ruPW9hkPjhM6Upla60G0IYBuSDDeUV/AXlXkhVBWBJX"
            "sAcRMooYxaQh+PiQzf3kxw/UbkJWolvyhy2BFDKfWL4gmvRpWPJgAPklrUf77ffZhYD5sCsZQMUDzezlfvTp+78e"
            "d0tYn2+LWIu0jou0Tq7W0zpdUWuu5YqCZytqnS/S+lhR631Nrd2KO+4oHyHlgPMlOXUyZpRANeTKDvw6bOE69FIR"
            "ShFEsQySwE8jGPJOm4YfFZn+3devWJpa14ABJZMSPVTeF3v0Vzk="
        ),
    },
    1: {
        "CarmenLog": (
            "eNqNU8tu00AUddJQyhCgvFPeBVqmQEPSQilQiKEBU1JFaGCRjWXZzjQONLaPPUHKp8BXdAkrFqzYISEh8SmIBYwf"
            "iVPRBXdx52p87rnnnpFt2/MHRsA7RCbbc0MR9G3hBQQKtV3z3duuKPdM3++6nbJhm0GPu2Q9Pja9DkHONgyr390W"
            "XdcwiGe94bYgyDcFJhgKOvZR6uxBFNqmSzbNkAevogqTTtSyn2FKxwEJ7/f8gRznBbzc60tyMwjMwS6FBCTFEbed"
            "fMZB2lAEirZsbHM7JNyNCoJDtJVTFMXC4dakPLdNqbaKIwLTDEcFjjEcp40cbUwInEg522Lgy86TtJWXHVurOLVR"
            "qZCNSpUInGYoSXDMuYaZZrP54o+MOEUCzlgR1pFTZ5RhfNmppZWaHEUVZx0p4RzDeYELlvb51+zv1/XFklYbFsNe"
            "TS0mRZNb0kwnMesiwyUds9Qh1EkWv+zIZa4wXB0uM+eU9lDyMVVSSJVMqZiPlFxjoAIL/6tE4Pr403a41+MikK/m"
            "eyEnL2VaqhPciLXeZFjUUaZa7dP7KD5ota/D4vtyHMlqCfwWQ0VHVcJ//gP/sRVHNH+JZi3LDLd13KGZ1GzUt+Rm"
            "fMIKw10dq3Q0fgw+EiRwLzP3fmTuA4a12Ny8wMPM3OmRuXOpp/MqHkWe1hhUgcdWxvMk4llnqMc8SqMg8DRh2vUn"
            "WQPBQ4JnCwyawHOLW+W/rLgTuA=="
        ),
        "GameState": (
            "eNpt0tly0zAUBmAn3QWFNlD2fRWbSVgLFBLWkGYmF+LGdx5ZMbHBkXysYzq5YIZH4h36ArwRSDaOh6G+kD2Szqff"
            "xxZCpTM/CyfEDEJJjVkuUGUEHCok//Y1RjdNuJSxnLi+VkKEGenzafgJOYYEGsL3gzxOMJa+T1TwJRRIoDlCWGCw"
            "+B2WqLfkOE6mAoWwLGQ+TWeuL1QWutPcVPEs47N/ziawQst9RI7LZVilQwdhTZjCcSg0CaV9IECo1zB6AIe8ZXNP"
            "uInRgcMI6wyOIBxlsEGHDTpsImz+Ncc4S01li3pNU/F5G44N2m0yaHcIwnEGW3S4UJg7cGI0Gu3+Nlcx2AAnA7s3"
            "MqduOP9fcCoyJ59mcAbhbOAt2mA8SeBctEKj8g3ORybVBQYXq1SXoq2K3JxD+z+7c/OyNa8wuIpwLfBWzZTak/5E"
            "8QSu1+4N695kQCv31kFua//H3L1t3TsM7iLcC7x166apkqHEEndr/L7F2ww6Ff6gxus+tHpz+6G1HzF4jPAk8NbM"
            "FIZ8OjX/i4antbtt3WcMnhduw8ovarlVN7aKbfoCO9Z+yeAVQre0q9waerX92tpvGLyt7XcHtcTp1fR7S39g0Ef4"
            "GBR7UqV1qHWspJ/xcZxrGPS7v8qK4ltEXPvFN961dJF53sa9GKNycTjKA/cPuLbnbg=="
        ),
        "GreedyStep": (
            "eNpVULtOwzAUTdpSisv7/SyMnqJ2Y0DKWJWIDGHJFiWOSQOpk5vegDIgvqMSAwMSf4DEGj4CiY3fYAEnBSFs6V77"
            "+rxkxuIkd1IeEFlYLMaYZgzjlIBCmXCvr0LUksgVIhSB5gQp535O+lU7R54QUJnjeFkYYSgch8TeJWdIoGYi1C1o"
            "3MIMtRuKojAeRdCkRttYRJi1W3J04+ZJHAqEFhPZKMk1h8Up10aZ1HLT1M3/RSIwR6c4IvzpMxBqKAhtJok+Z2PC"
            "RXkgME9tVRp4sGA3ZY9cGa4H0njJgmWEFQtWqaFSo4aw9qPpY55I5jq1a5JxcQwbg26XDLo9grBpwRY16pXmCWyb"
            "pnn6JVdVygA7XokdSteORBT3xeR3v0704uHvWrzosDuUOfYs2Ec48CrJADp9/Z0Zb3cfT9VgCId9/bMaPNqk/DxX"
            "+KHvIh/D0dmzmnnaN2ndluQ="
        ),
        "GridPath": (
            "eNp1kL1OwzAQx5O0DcV8lO9vWBjwFLUbAwNbVSJFKFO2yHGsJhCcnHNBZOBBmGDkaXgZHgCcFpAI4oY7/+3/7846"
            "zvOiDpWYEp14LktUFcdcETAol+z+NkWnyJiUqZw6ISuRKTJWaXzNMCFg8jCMqjTDVIYhyaMbwZGA5SF0fOg+Qo8G"
            "PcMwuMiyEmwuq7uidkKeK+HcVZpiSrH612QCC3TuIzKeP0OfugbCItdgLHhJhGwOBAgNTN09gqXA1jVj+hsjWEZY"
            "8WEVYeDDGnVN6hLXQlj/6hpjXWh2gwaWZtJz2JwMh2QyHBGELR+2qduZdb2AHc/zrj50zFLzhd2o8SZ67ovxN8x/"
            "qtXSnZbutnSvxdktzm5xdov71rCX6F3s+3CAcBgFjZ3nJcLR+PL09ezp+e096Os78VAwGYsYjt3BfI9CTjGBkx9b"
            "FTmfGRl+IA=="
        ),
        "WorldPath": (
            "eNplkLtOw1AMhtO0lHK4lFLut5UzRe3GgNRuqESKUBayRclJaALpSZw4iAy8AysTax+gIxIS7LwMDwAnbSNE48H6"
            "9dm/bZmxMMrM2B0SkVjIE4xThmFMQKKMWw/3PipRYHHu86Fi5sqMLPTITRgHznWuoMJM0079AH1umiS071yGBGQN"
            "oapD7QmWqFGXJCkKfY4J1BlPR1GmmCyMXWWUCpsVx1b2bz+BZTrrI9yZlaFBVQlhhQmj47KEuDwXBAg1KmK8DavT"
            "NYEl7ujCGsK6DhsITR02qVqhKlFlhNZ8qoNZJLxb1JCF5/Yc2oNOhww6XYKwrcMOVavTqRewq2na1Y+IacpP2LPz"
            "Xk/snUhFfE56c/H28V6oAk0KJPcXSb1ESIlslEirIOMSeS6T3qKpB/ue+M+BDocIR7ZRE5SFCcLxZb89Pnt5/fqe"
            "vdLlQ/Tg5I82BHUfI4s7rgOnajO1lV/VdqEs"
        ),
    },
}

GAME = {
    "robot_xy": (0.0, 0.0),
    "ball_xy": (1.0, 0.0),
    "teammates_xy": [[-2.0, 1.0]],
    "opponents_xy": [[2.0, 1.0]],
    "own_goal_xy": (-4.5, 0.0),
    "opponent_goal_xy": (4.5, 0.0),
}
LOG = (
    "FLASER 3 1.0 2.0 3.5 0.1 0.2 0.3 0.0 0.1 0.25 10.5 host 10.5\n"
    "FLASER 3 1.5 2.5 3.0 0.4 0.2 0.35 0.3 0.1 0.3 11.0 host 11.0\n"
)


def _load(text: str) -> object:
    return pickle.loads(zlib.decompress(base64.b64decode(text)))


def _today(name: str, tmp_path: Path) -> object:
    if name == "GameState":
        return GameState(**GAME)  # type: ignore[arg-type]
    if name == "GreedyStep":
        local = LocalGrid.from_points([[0.5, 0.1], [0.6, -0.2]], half_width=1.0, resolution=0.1)
        return greedy_step(local, (2.0, 0.5))
    path = tmp_path / "log.log"
    path.write_text(LOG)
    return read_carmen(path)


@pytest.mark.parametrize("protocol", [0, 1])
@pytest.mark.parametrize(
    ("name", "kind"),
    [("CarmenLog", CarmenLog), ("GameState", GameState), ("GreedyStep", GreedyStep)],
)
def test_a_record_pickled_at_protocol_0_or_1_loads_as_todays(
    protocol: int, name: str, kind: type, tmp_path: Path
) -> None:
    data = zlib.decompress(base64.b64decode(MADE_AT_AA060BE[protocol][name]))
    assert b"copy_reg\n_reconstructor" in data  # the protocols' own way
    old = pickle.loads(data)
    assert type(old) is kind
    assert repr(old) == repr(_today(name, tmp_path))


@pytest.mark.parametrize("protocol", [0, 1])
@pytest.mark.parametrize(
    ("name", "module"),
    [("GridPath", "navkit.planning._astar"), ("WorldPath", "navkit.planning._plan_path")],
)
def test_a_path_pickled_at_protocol_0_or_1_is_refused_by_name(
    protocol: int, name: str, module: str
) -> None:
    with pytest.raises(ValueError, match=f"^{module}.{name}: a pickle made by navkit"):
        _load(MADE_AT_AA060BE[protocol][name])


def test_a_reloaded_old_module_still_answers() -> None:
    old = importlib.import_module("navkit.mapping._carmen")
    assert importlib.reload(old) is old
    assert old.CarmenLog is CarmenLog
    with pytest.raises(AttributeError, match="'nothing'"):
        old.nothing  # noqa: B018


def test_an_old_name_is_no_package() -> None:
    importlib.import_module("navkit.planning._fields")
    with pytest.raises(ModuleNotFoundError, match=r"navkit\.planning\._fields\.sub"):
        importlib.import_module("navkit.planning._fields.sub")
    spec = importlib.util.find_spec("navkit.planning._fields")
    assert spec is not None and spec.origin is None and spec.submodule_search_locations is None


def test_resolve_name_answers_as_pickle_does() -> None:
    assert pkgutil.resolve_name("navkit.planning._soccer:GameState") is GameState
    assert pkgutil.resolve_name("navkit.planning._greedy.GreedyStep") is GreedyStep
    with pytest.raises(ValueError, match="names GridPath, which navkit no longer has"):
        pkgutil.resolve_name("navkit.planning._astar:GridPath")


def test_getmodule_passes_over_the_old_names() -> None:
    importlib.import_module("navkit.mapping._carmen")
    importlib.import_module("navkit.planning._soccer")
    assert inspect.getmodule(CarmenLog) is importlib.import_module("navkit.mapping.io._carmen")
    assert inspect.getmodule(GameState) is importlib.import_module("navkit.behaviours._soccer")
