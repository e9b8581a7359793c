"""The command line's grammar: ``navkit {demo,list,run,plan,warmup}`` and their options."""

from __future__ import annotations

import argparse
import contextlib
import difflib
import math
import re
import sys
from collections.abc import Callable, Iterable, Sequence
from importlib import metadata
from typing import Any, overload

__all__ = [
    "Choices",
    "build_parser",
    "closest_choice",
    "join_negative_points",
    "parse_command_line",
    "version",
]


def version() -> str:
    """navkit's installed version (``"unknown"`` when run from an uninstalled tree)."""
    try:
        return metadata.version("navkit")
    except metadata.PackageNotFoundError:  # pragma: no cover - always installed in tests
        return "unknown"


def join_negative_points(
    argv: Sequence[str], *, parser: argparse.ArgumentParser | None = None
) -> list[str]:
    """``--start -1.5,2`` as ``--start=-1.5,2``: argparse would take ``-1.5,2`` for an option.

    After an option of the command that takes one value (a point, a number, a
    name or a file: ``--start``, ``--radius``, ``--seed``, ``--plot``,
    ``--json``, ...), a value beginning with one ``-`` is joined to it,
    whatever follows the dash, as a GNU program's option takes its next word:
    argparse takes only plain negative numbers (``-1``, ``-0.5``) for values
    and answered ``--start -inf,0``, ``--radius -inf`` or ``--plot -x.png``
    with "expected one argument"; joined, the option reads it and its own
    check names any problem ("X,Y must be finite, got '-inf,0'"). ``-h`` and
    ``--...`` stay options. An abbreviation the command reads as one option
    (``--go -1,2``) is joined too; an ambiguous one (``--st`` for ``--start``
    and ``--start-tolerance``) is left as typed, for argparse to name it as
    typed; nothing after ``--`` is changed.

    Parameters
    ----------
    argv : sequence of str
        The arguments after the program name.
    parser : argparse.ArgumentParser, optional
        The parser whose commands' options are read (default
        :func:`build_parser`'s).

    Returns
    -------
    list of str
        ``argv`` with those values joined (a new list).

    Examples
    --------
    >>> join_negative_points(["plan", "m.yaml", "--start", "-1.5,-0.5", "--go", "-inf,1"])
    ['plan', 'm.yaml', '--start=-1.5,-0.5', '--go=-inf,1']
    >>> join_negative_points(["plan", "m.yaml", "--plot", "-x.png", "--st", "-1,0"])
    ['plan', 'm.yaml', '--plot=-x.png', '--st', '-1,0']
    """
    argv = list(argv)
    # The command is the first word not beginning with "-": navkit's own options
    # (--help, --version) take no value.
    at = next((i for i, arg in enumerate(argv) if not arg.startswith("-")), len(argv))
    commands = _commands(build_parser() if parser is None else parser)
    command = commands.get(argv[at]) if at < len(argv) else None
    if command is None:  # no command, or a mistyped one argparse will name
        return argv
    names = [n for action in command._actions for n in action.option_strings if n.startswith("--")]
    takes_value = {
        n for action in command._actions if action.option_strings and action.nargs in (None, 1)
        for n in action.option_strings
    }  # fmt: skip
    out = argv[: at + 1]
    i = at + 1
    while i < len(argv):
        arg = argv[i]
        following = argv[i + 1] if i + 1 < len(argv) else ""
        if arg == "--":  # the rest are positional arguments, as the user wrote them
            return out + argv[i:]
        if _option(arg, names) in takes_value and _dash_value(following):
            out.append(f"{arg}={following}")
            i += 2
        else:
            out.append(arg)
            i += 1
    return out


def parse_command_line(parser: argparse.ArgumentParser, argv: Sequence[str]) -> argparse.Namespace:
    """``parser.parse_args(argv)``, an unknown option reported by the command it was given to.

    argparse reports an option no command has (``navkit demo --trail 3``,
    ``navkit plan ... --robot-radius 0.2``) from the top-level parser: its
    usage, ``navkit [-h] [--version] COMMAND ...``, lists none of the
    command's options. Here the command's parser reports it, with its own
    usage, and names the command's option closest to the first unknown one.

    Parameters
    ----------
    parser : argparse.ArgumentParser
        :func:`build_parser`'s parser.
    argv : sequence of str
        The arguments after the program name.

    Returns
    -------
    argparse.Namespace
        The parsed arguments; bad arguments exit with code 2 and the usage.

    Examples
    --------
    >>> parse_command_line(build_parser(["demo"]), ["run", "demo", "--trials", "2"]).trials
    2
    """
    args, extras = parser.parse_known_args(argv)
    if extras:
        command = _commands(parser).get(str(getattr(args, "command", "")))
        reporter = parser if command is None else command
        message = f"unrecognized arguments: {' '.join(extras)}"
        # Words after a "--" are no options: guessed from, "-- --trials" was answered
        # "maybe you meant '--trials'?", the very word typed. Told apart by their place,
        # not their text: the same word may be typed before the "--" too.
        after = _after_dashdash(argv, extras)
        options = [e for e, late in zip(extras, after, strict=True)
                   if not late and e.startswith("--") and e != "--"]  # fmt: skip
        typed = options[0].partition("=")[0] if options else None
        if typed is None and any(
            late and e.startswith("--") for e, late in zip(extras, after, strict=True)
        ):
            message += " (after '--' no word is read as an option)"
        # --help is left out: "--step" is closer to it than to anything a user meant.
        names = [
            n for a in reporter._actions if not isinstance(a, (argparse._HelpAction, _Version))
            for n in a.option_strings if n.startswith("--")
        ]  # fmt: skip
        guess = None if typed is None else closest_choice(typed, names)
        reporter.error(message if guess is None else f"{message}, maybe you meant {guess!r}?")
    return args


def _after_dashdash(argv: Sequence[str], extras: Sequence[str]) -> list[bool]:
    """Whether each of ``extras`` (argparse's unread words) stands after ``argv``'s first ``--``.

    ``extras`` keep ``argv``'s order; matched from the end, each takes the last
    place of its text not yet taken, so a word typed both before the ``--`` (and
    read there, as ``--trials 1``) and after it is the one after it.

    Examples
    --------
    >>> _after_dashdash(["demo", "--trail", "--", "--trail"], ["--trail", "--", "--trail"])
    [False, False, True]
    """
    words = list(argv)
    cut = words.index("--") if "--" in words else len(words)
    flags: list[bool] = []
    j = len(words)
    for extra in reversed(extras):
        j -= 1
        while j >= 0 and words[j] != extra:
            j -= 1
        flags.append(j > cut)
    return flags[::-1]


def _commands(parser: argparse.ArgumentParser) -> dict[str, argparse.ArgumentParser]:
    """``parser``'s commands by name (none for a parser without commands)."""
    # argparse lists a parser's options and commands only in private attributes,
    # the same on Python 3.11-3.14.
    for action in parser._actions:
        if isinstance(action, argparse._SubParsersAction):
            return dict(action._name_parser_map)
    return {}


def _option(arg: str, names: Sequence[str]) -> str | None:
    """The option among ``names`` that ``arg`` names or alone abbreviates, as argparse reads it."""
    if not arg.startswith("--") or "=" in arg or len(arg) <= 2:
        return None
    if arg in names:
        return arg
    matches = [n for n in names if n.startswith(arg)]
    return matches[0] if len(matches) == 1 else None


def _dash_value(text: str) -> bool:
    """Whether ``text`` begins with one ``-`` and more (``-1,2``, ``-inf,0``, ``-x``), not ``-h``.

    A lone ``-`` is a value to argparse already; ``--goal`` and the like are options.
    """
    return len(text) > 1 and text[0] == "-" and text[1] != "-" and text != "-h"


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


def closest_choice(value: str, choices: Iterable[object]) -> str | None:
    """The choice ``value`` was most likely meant to be, or None when none is close.

    Case and ``_`` against ``-`` are ignored; otherwise a choice that alone
    starts with ``value``, else the closest by :func:`difflib.get_close_matches`.

    Examples
    --------
    >>> names = ("demo", "diff-astar", "omni-apf", "soccer")
    >>> closest_choice("omni_apf", names), closest_choice("diff", names)
    ('omni-apf', 'diff-astar')
    >>> closest_choice("Soccer", names), closest_choice("xyz", names)
    ('soccer', None)
    """
    names = [c for c in choices if isinstance(c, str)]

    def normal(name: str) -> str:
        return name.casefold().replace("_", "-")

    wanted = normal(value)
    by_normal = {normal(n): n for n in reversed(names)}  # the first of equal spellings
    if wanted in by_normal:
        return by_normal[wanted]
    starting = [n for n in names if wanted and normal(n).startswith(wanted)]
    if len(starting) == 1:
        return starting[0]
    close = difflib.get_close_matches(wanted, list(by_normal), n=1)
    return by_normal[close[0]] if close else None


class _Parser(argparse.ArgumentParser):
    """argparse's parser, naming the closest choice to a mistyped one.

    ``navkit run omni`` says "maybe you meant 'omni-apf'?", as Python 3.14's
    ``suggest_on_error`` does, on every Python version and for every choice
    (commands, scenarios, planners, maps, warm-up steps).
    """

    def _check_value(self, action: argparse.Action, value: Any) -> None:
        try:
            super()._check_value(action, value)
        except argparse.ArgumentError as exc:
            message = exc.message
            guess = (
                closest_choice(value, action.choices)
                if isinstance(value, str) and action.choices is not None
                else None
            )
            if guess is None or "maybe you meant" in message:  # argparse's own (3.15)
                raise
            hint = f", maybe you meant {guess!r}?"
            at = message.find(" (choose from ")
            message = message + hint if at < 0 else message[:at] + hint + message[at:]
            raise argparse.ArgumentError(action, message) from None


class _Formatter(argparse.HelpFormatter):
    """argparse's help, with the lines of a paragraph holding indented lines (examples) kept.

    Other paragraphs (blank-line separated) are filled to the terminal's width
    as argparse fills them.
    """

    def _fill_text(self, text: str, width: int, indent: str) -> str:
        paragraphs = []
        for paragraph in text.split("\n\n"):
            lines = paragraph.splitlines()
            if any(line.startswith("  ") for line in lines):
                paragraphs.append("\n".join(indent + line for line in lines))
            else:
                paragraphs.append(super()._fill_text(paragraph, width, indent))
        return "\n\n".join(paragraphs)


#: ``navkit --help``'s closing text: examples, then the exit codes (as navkit.cli.main's).
_EPILOG = """\
examples:
  navkit demo              # plan, track and localise (a real map, else a synthetic one)
  navkit list              # the papers' experiments
  navkit run omni-apf --trials 5 --plot omni.png --json omni.json
  navkit plan map.yaml --start -2,-0.5 --goal 2,0.5 --radius 0.1
  navkit warmup            # compile every kernel ahead (once per install)

Run navkit COMMAND --help for a command's options. Exit codes: 0 done; 1 a file, \
map, data set or plan failed (one line "navkit: error: ..."); 2 bad arguments (with \
the usage); 130 Ctrl-C (143 SIGTERM, 129 SIGHUP); 141 standard output closed \
early (navkit list | head -1, once the output outgrows the pipe)."""

_RUN_EPILOG = """\
examples:
  navkit run soccer        # the scenario's trials per case, on every core
  navkit run omni-apf --trials 2 --seed 7 --workers 1
  navkit run greedy --json greedy.json --plot greedy.png
  navkit run diff-astar --scheduler tcp://host:8786

--trials counts trials per case (navkit list gives each scenario's default). \
Tables go to standard output; the progress bar (on a terminal) and notices to \
standard error."""

_PLAN_EPILOG = """\
examples:
  navkit plan maps/turtlebot3_world/map.yaml --start -2,-0.5 --goal 2,0.5
  navkit plan office.yaml --start 1.5,2 --goal 12,8.25 --radius 0.2 \\
      --planner field_dstar --plot route.png
  navkit plan office.yaml --start "(1.5, 2)" --goal 12,8.25 --json route.json

Coordinates are world metres in the map's frame (its YAML's origin), not \
cells, as X,Y or (X, Y) (quoted for the shell), as the table prints them; a \
negative one may follow --start or --goal with a space."""


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


#: Numbers as C's ``strtod`` and other command-line programs read them, in ASCII:
#: Python's float() and int() also take ``1_0`` (10: a mistyped "1.0" or "1,0"?) and
#: digits of other scripts (``"١٢"``), which no user means on a command line.
_DECIMAL = re.compile(
    r"[+-]?(?:(?:\d+\.?\d*|\.\d+)(?:e[+-]?\d+)?|inf|infinity|nan)", re.IGNORECASE | re.ASCII
)
_INTEGER = re.compile(r"[+-]?\d+", re.ASCII)


def _float(text: str) -> float:
    """``text`` as a float, spaces around it allowed; ValueError unless a plain decimal number."""
    number = text.strip()
    if not _DECIMAL.fullmatch(number):
        raise ValueError(text)
    return float(number)


def _point(text: str) -> tuple[float, float]:
    """``"X,Y"`` (m) as two finite floats; ``"(X, Y)"``, as the tables print points, too."""
    inner = text.strip()
    if inner.startswith("(") and inner.endswith(")"):
        inner = inner[1:-1]
    parts = inner.split(",")
    try:
        if len(parts) != 2:
            raise ValueError
        x, y = _float(parts[0]), _float(parts[1])
    except ValueError:
        raise argparse.ArgumentTypeError(f"expected X,Y in metres, got {text!r}") from None
    if not (math.isfinite(x) and math.isfinite(y)):
        raise argparse.ArgumentTypeError(f"X,Y must be finite, got {text!r}")
    return x, y


def _count(low: int, high: int, *, shown: str | None = None) -> type[int]:
    """An integer argument in ``[low, high]`` (``shown``: the range as the help writes it)."""
    bounds = shown if shown is not None else f"[{low}, {high}]"

    def parse(text: str) -> int:
        number = text.strip()
        if not _INTEGER.fullmatch(number):
            raise argparse.ArgumentTypeError(f"expected an integer, got {text!r}")
        try:
            # The stripped text, as _float reads it: int() keeps some characters that
            # str.strip() takes for spaces ("\x1c"), and its ValueError then read as
            # "an integer of 1 characters".
            value = int(number)
        except ValueError:  # beyond int()'s digit limit
            raise argparse.ArgumentTypeError(
                f"must be in {bounds}, got an integer of {len(number)} characters"
            ) from None
        if not low <= value <= high:
            raise argparse.ArgumentTypeError(f"must be in {bounds}, got {value}")
        return value

    parse.__name__ = "integer"
    return parse  # type: ignore[return-value]


def _radius(text: str) -> float:
    try:
        value = _float(text)
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
        value = _float(text)
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
    parser.add_argument("--seed", type=_count(0, 2**64 - 1, shown="[0, 2**64)"), default=0,
                        metavar="S",
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
    parser = _Parser(
        prog="navkit",
        description="navkit's experiments, demo and planner on the command line.",
        epilog=_EPILOG,
        formatter_class=_Formatter,
    )
    parser.add_argument("--version", action=_Version, nargs=0, default=argparse.SUPPRESS,
                        help="show program's version number and exit")  # fmt: skip
    sub = parser.add_subparsers(dest="command", metavar="COMMAND", required=True)

    demo = sub.add_parser(
        "demo", help="plan, track and localise on a real office map (a synthetic office "
                     "when no data is found; a few seconds)",
        description="A robot plans (A*), tracks (regulated pure pursuit) and localises "
                    "(wheel encoders + IMU fusion) on a three-leg tour of the Willow Garage "
                    "office map (a synthetic office when the data is absent), then prints "
                    "a results table.",
        epilog="examples:\n  navkit demo\n  navkit demo --map office --plot demo.png",
        formatter_class=_Formatter,
    )  # fmt: skip
    _outputs(demo)
    demo.add_argument("--map", choices=("auto", "willow", "office"), default="auto",
                      help="the map (default auto: Willow Garage if found, else the synthetic "
                           "office)")  # fmt: skip

    sub.add_parser("list", help="list the experiments",
                   description="List the experiments: name, default trials per case, what "
                               "each runs.", formatter_class=_Formatter)  # fmt: skip

    run = sub.add_parser(
        "run", help="run an experiment and print its tables beside the paper's",
        description="Run one of the papers' experiments and print navkit's figures beside "
                    "the paper's.",
        epilog=_RUN_EPILOG,
        formatter_class=_Formatter,
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
        epilog=_PLAN_EPILOG,
        formatter_class=_Formatter,
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
    plan.add_argument("--json", metavar="FILE",
                      help="write the plan as JSON: its points (m), length, cost, "
                           "planner")  # fmt: skip
    plan.add_argument("--quiet", action="store_true", help="no compilation notice on stderr")

    warm = sub.add_parser(
        "warmup", help="compile navkit's kernels now, once per install (a minute)",
        description="Compile every numba kernel navkit uses (numba caches them on disk), "
                    "so that no later run waits for compilation; print what was compiled "
                    "and how long it took. Run it at install or image-build time.",
        epilog="examples:\n  navkit warmup\n  navkit warmup --only astar --only field_dstar "
               "--workers 1",
        formatter_class=_Formatter,
    )  # fmt: skip
    warm.add_argument("--workers", type=_count(1, 1024), metavar="N",
                      help="processes (default: every core; 1: this one)")  # fmt: skip
    _late_help(warm.add_argument("--only", action="append", choices=Choices(_warmup_steps),
                                 metavar="STEP"),
               "only this step (repeatable): %(choices)s")  # fmt: skip
    warm.add_argument("--quiet", action="store_true", help="no progress on stderr")
    return parser
