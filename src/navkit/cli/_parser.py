"""The command line's grammar: ``navkit {demo,list,run,plan,warmup}`` and their options."""

from __future__ import annotations

import argparse
import contextlib
import math
import re
import sys
from collections.abc import Callable, Sequence
from importlib import metadata
from typing import overload

__all__ = ["Choices", "build_parser", "join_negative_points", "version"]


def version() -> str:
    """navkit's installed version (``"unknown"`` when run from an uninstalled tree)."""
    try:
        return metadata.version("navkit")
    except metadata.PackageNotFoundError:  # pragma: no cover - always installed in tests
        return "unknown"


def join_negative_points(argv: list[str]) -> list[str]:
    """``--start -1.5,2`` as ``--start=-1.5,2``: argparse would take ``-1.5,2`` for an option.

    Examples
    --------
    >>> join_negative_points(["plan", "m.yaml", "--start", "-1.5,-0.5", "--goal", "1,1"])
    ['plan', 'm.yaml', '--start=-1.5,-0.5', '--goal', '1,1']
    """
    out: list[str] = []
    i = 0
    while i < len(argv):
        arg = argv[i]
        following = argv[i + 1] if i + 1 < len(argv) else ""
        if arg in ("--start", "--goal") and re.match(r"-[\d.]", following):
            out.append(f"{arg}={following}")
            i += 2
        else:
            out.append(arg)
            i += 1
    return out


class Choices(Sequence[str]):
    """An argument's choices, looked up only when the argument is parsed or its help shown.

    The names of the scenarios and of the warm-up steps come from the simulator:
    ``navkit --help`` and ``navkit plan`` build the whole parser without
    importing it (issue 17).

    Parameters
    ----------
    names : callable
        The choices, in order (called once, when first needed).
    known : callable, optional
        Whether a value is a choice, when that can be told without listing them
        all (default: ``value in names()``).

    Examples
    --------
    >>> steps = Choices(lambda: ("geometry", "planning"))
    >>> "planning" in steps, list(steps)
    (True, ['geometry', 'planning'])
    """

    def __init__(
        self, names: Callable[[], Sequence[str]], known: Callable[[str], bool] | None = None
    ) -> None:
        self._names = names
        self._known = known
        self._listed: tuple[str, ...] | None = None

    def _list(self) -> tuple[str, ...]:
        if self._listed is None:
            self._listed = tuple(self._names())
        return self._listed

    def __contains__(self, value: object) -> bool:
        if self._known is not None and isinstance(value, str):
            return self._known(value)
        return value in self._list()

    @overload
    def __getitem__(self, index: int) -> str: ...
    @overload
    def __getitem__(self, index: slice) -> Sequence[str]: ...
    def __getitem__(self, index: int | slice) -> str | Sequence[str]:
        return self._list()[index]

    def __len__(self) -> int:
        return len(self._list())


class _Version(argparse.Action):
    """``--version``: ``navkit X.Y.Z`` on one line of standard output.

    argparse's own version action wraps the line to the terminal's width
    (``COLUMNS=10``: ``navkit`` and the version on two lines) and writes it to
    standard error when standard output is closed. As argparse's, a line that
    cannot be written (``navkit --version | true``, a full disk) is dropped
    and the exit code is 0, not a traceback.
    """

    def __call__(
        self,
        parser: argparse.ArgumentParser,
        namespace: argparse.Namespace,
        values: str | Sequence[object] | None,
        option_string: str | None = None,
    ) -> None:
        if sys.stdout is not None:
            # A pipe closed early (BrokenPipeError), a full disk: dropped, as argparse does.
            with contextlib.suppress(OSError):
                sys.stdout.write(f"navkit {version()}\n")
        parser.exit()


def _scenario_names() -> list[str]:
    from navkit.sim.scenarios import SCENARIOS

    return sorted(SCENARIOS)


def _is_scenario(name: str) -> bool:
    """Whether ``name`` is a scenario's, importing that scenario's module alone."""
    from navkit.sim.scenarios import get_scenario

    try:
        get_scenario(name)
    except ValueError:
        return False
    return True


def _warmup_steps() -> tuple[str, ...]:
    from navkit.sim import WARMUP_STEPS

    return WARMUP_STEPS


def _point(text: str) -> tuple[float, float]:
    """``"X,Y"`` (m) as two finite floats."""
    parts = text.split(",")
    try:
        if len(parts) != 2:
            raise ValueError
        x, y = float(parts[0]), float(parts[1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Y in metres, got {text!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise argparse.ArgumentTypeError(f"X,Y must be finite, got {text!r}")
    return x, y


def _count(low: int, high: int) -> type[int]:
    """An integer argument in ``[low, high]``."""

    def parse(text: str) -> int:
        try:
            value = int(text)
        except ValueError:
            if re.fullmatch(r"\s*[+-]?\d[\d_]*\s*", text):  # beyond int()'s digit limit
                raise argparse.ArgumentTypeError(
                    f"must be in [{low}, {high}], got an integer of {len(text.strip())} characters"
                ) from None
            raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}") from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must be in [{low}, {high}], got {value}")
        return value

    parse.__name__ = "integer"
    return parse  # type: ignore[return-value]


def _radius(text: str) -> float:
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a radius in metres, got {text!r}") from None
    if not (math.isfinite(value) and 0.0 <= value <= 100.0):
        raise argparse.ArgumentTypeError(f"must be in [0, 100] m, got {text!r}")
    return value


# MapPlanner.plan's range of start_tolerance (navkit.planning's coordinate limit).
_TOLERANCE_LIMIT = 1e9


def _tolerance(text: str) -> float:
    """``--start-tolerance``: metres in ``[0, 1e9]``, as MapPlanner.plan accepts."""
    try:
        value = float(text)
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected a distance in metres, got {text!r}") from None
    if not (math.isfinite(value) and 0.0 <= value <= _TOLERANCE_LIMIT):
        raise argparse.ArgumentTypeError(f"must be in [0, 1e9] m, got {text!r}")
    return value + 0.0  # -0 as 0


def _late_help(action: argparse.Action, text: str) -> None:
    """Give ``action`` the help ``text``, which lists its :class:`Choices` when shown.

    Python 3.14's ``add_argument`` checks a help string by expanding it at once:
    a ``%(choices)s`` in it would list the choices, importing the simulator,
    while the parser is built. Set afterwards, it is expanded only when the
    help is shown (as ``add_argument`` does on Python 3.11-3.13).
    """
    action.help = text


def _outputs(parser: argparse.ArgumentParser) -> None:
    """Options shared by ``demo`` and ``run``."""
    parser.add_argument("--trials", type=_count(1, 100_000), metavar="N",
                        help="trials per case (default: the scenario's)")  # fmt: skip
    # The library's range of base seeds (navkit.sim.trial_seed): [0, 2**64).
    parser.add_argument("--seed", type=_count(0, 2**64 - 1), default=0, metavar="S",
                        help="base seed in [0, 2**64) (default 0): the same seed, the same "
                             "figures")  # fmt: skip
    parser.add_argument("--plot", metavar="FILE.png", help="write a picture of the scene")
    parser.add_argument("--animate", metavar="FILE.gif", help="write an animation of the run")
    parser.add_argument("--json", metavar="FILE", help="write the result as JSON")
    parser.add_argument("--data", metavar="DIR",
                        help="data folder holding ros-map-server-maps, ... "
                             "(default: $NAVKIT_DATA or shared/data nearby)")  # fmt: skip
    parser.add_argument("--quiet", action="store_true",
                        help="no progress bar and no compilation notice on stderr")  # fmt: skip


def build_parser(scenarios: Sequence[str] | None = None) -> argparse.ArgumentParser:
    """The ``navkit`` argument parser.

    Parameters
    ----------
    scenarios : sequence of str, optional
        ``navkit run``'s choices (default: the registered scenarios, imported
        when a scenario is named).

    Returns
    -------
    argparse.ArgumentParser
        Exits with code 2 and a usage message on bad arguments.

    Examples
    --------
    >>> build_parser(["demo"]).parse_args(["run", "demo", "--trials", "2"]).trials
    2
    """
    parser = argparse.ArgumentParser(
        prog="navkit",
        description="navkit's experiments, demo and planner on the command line.",
    )
    parser.add_argument("--version", action=_Version, nargs=0, default=argparse.SUPPRESS,
                        help="show program's version number and exit")  # fmt: skip
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    demo = sub.add_parser(
        "demo", help="plan, track and localise on a real map (a few seconds)",
        description="A robot plans (A*), tracks (regulated pure pursuit) and localises "
                    "(wheel encoders + IMU fusion) on a three-leg tour of the Willow Garage "
                    "office map (a synthetic office when the data is absent), then prints "
                    "a results table.",
    )  # fmt: skip
    _outputs(demo)
    demo.add_argument("--map", choices=("auto", "willow", "office"), default="auto",
                      help="the map (default auto: Willow Garage if found)")  # fmt: skip

    sub.add_parser("list", help="list the experiments", description="List the experiments.")

    run = sub.add_parser(
        "run", help="run an experiment and print its tables beside the paper's",
        description="Run one of the papers' experiments and print navkit's figures beside "
                    "the paper's.",
    )  # fmt: skip
    if scenarios is None:
        scenarios = Choices(_scenario_names, known=_is_scenario)
    _late_help(run.add_argument("scenario", choices=scenarios, metavar="SCENARIO"),
               "one of: %(choices)s")  # fmt: skip
    _outputs(run)
    run.add_argument("--workers", type=_count(1, 1024), metavar="N",
                     help="local processes (default: every core; 1: this one)")  # fmt: skip
    run.add_argument("--scheduler", metavar="ADDRESS",
                     help="run the trials on a Dask cluster (tcp://host:8786); needs the "
                          "'distributed' extra")  # fmt: skip

    plan = sub.add_parser(
        "plan", help="plan a path on a ROS map_server map",
        description="Plan a path on a ROS map_server map (YAML + image) and print its "
                    "length and the planning time.",
    )  # fmt: skip
    plan.add_argument("map", metavar="MAP.yaml", help="the map's YAML file")
    plan.add_argument("--start", type=_point, required=True, metavar="X,Y",
                      help="start, world metres")  # fmt: skip
    plan.add_argument("--goal", type=_point, required=True, metavar="X,Y",
                      help="goal, world metres")  # fmt: skip
    plan.add_argument("--planner", choices=("astar", "field_dstar"), default="astar",
                      help="astar (8-connected, default) or field_dstar (any angle)")  # fmt: skip
    plan.add_argument("--radius", type=_radius, default=0.0, metavar="R",
                      help="robot radius: obstacles inflated by R metres (default 0)")  # fmt: skip
    plan.add_argument("--start-tolerance", type=_tolerance, default=0.0, metavar="METRES",
                      help="a start within R of an obstacle or unknown space (a drifted "
                           "estimate) first moves straight to the nearest passable cell "
                           "centre within METRES (default 0: such a start is "
                           "refused)")  # fmt: skip
    plan.add_argument("--plot", metavar="FILE.png", help="write a picture of the map and path")
    plan.add_argument("--quiet", action="store_true", help="no compilation notice on stderr")

    warm = sub.add_parser(
        "warmup", help="compile navkit's kernels now, once per install (a minute)",
        description="Compile every numba kernel navkit uses (numba caches them on disk), "
                    "so that no later run waits for compilation; print what was compiled "
                    "and how long it took. Run it at install or image-build time.",
    )  # fmt: skip
    warm.add_argument("--workers", type=_count(1, 1024), metavar="N",
                      help="processes (default: every core; 1: this one)")  # fmt: skip
    _late_help(warm.add_argument("--only", action="append", choices=Choices(_warmup_steps),
                                 metavar="STEP"),
               "only this step (repeatable): %(choices)s")  # fmt: skip
    warm.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return parser
