"""What an experiment is: trials, their results, tables of figures and a scene to draw.

A :class:`Scenario` describes one source paper's experiment. It splits into
independent :class:`Trial` s (a case and a seed each) so that
:func:`~navkit.sim.sweep` can run them anywhere — in this process, a process
pool or a Dask cluster — and get the same numbers; the scenario then folds the
:class:`TrialResult` s into a :class:`ScenarioResult` with the paper's figures
beside navkit's.
"""

from __future__ import annotations

import concurrent.futures
import json
import math
from abc import ABC, abstractmethod
from collections.abc import Callable, Iterable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from dataclasses import dataclass, field
from typing import Any, ClassVar, Protocol

import numpy as np

from navkit._shared.counts import counted
from navkit._shared.dunders import bounded_repr, record_eq, record_hash
from navkit._shared.frozen import frozen_setattr, read_only_view, restore_read_only
from navkit._shared.frozendict import FrozenDict
from navkit._shared.text import as_text
from navkit._shared.types import FloatArray
from navkit._shared.validation import (
    as_float_array,
    as_sequence,
    bounded_int,
    finite_float,
    is_ndarray,
)
from navkit.mapping import OccupancyGrid
from navkit.sim._trace import Trace
from navkit.sim._world import World

__all__ = [
    "Scenario",
    "ScenarioResult",
    "Scene",
    "Table",
    "Trial",
    "TrialResult",
    "trial_seed",
]

#: Most trials per case a run may ask for.
_MAX_TRIALS = 100_000
#: Most trials of a run over all its cases (the built-in scenarios ask for at most
#: 900001 at the per-case maximum).
_MAX_TOTAL_TRIALS = 1_000_000

Cell = str | int | float | np.integer | np.floating | None
"""One table cell: text, a number (NaN shown as ``-``) or nothing."""


def trial_seed(base: int, case_index: int, trial_index: int) -> int:
    """The seed of one trial, from the run's base seed and the trial's place.

    The seed depends only on ``(base, case_index, trial_index)``, never on the
    order trials run in or on which worker runs them, so a sweep gives the same
    numbers on one core, a process pool or a cluster. Different triples never
    give NumPy's ``SeedSequence`` the same entropy, whatever their size.

    Parameters
    ----------
    base : int
        The run's seed, in [0, 2**64).
    case_index, trial_index : int
        The trial's case (0-based, in the scenario's order) and its number
        within the case (0-based), each in [0, 2**63).

    Returns
    -------
    int
        A seed in [0, 2**63).

    Raises
    ------
    TypeError
        An argument that is not an integer.
    ValueError
        An argument outside its range (``base`` in ``[0, 2**64)``, the indices
        in ``[0, 2**63)``).

    Examples
    --------
    >>> trial_seed(0, 0, 1) == trial_seed(0, 0, 1) != trial_seed(0, 0, 2)
    True
    """
    values = [
        _int_in(base, "base", 2**64),
        _int_in(case_index, "case_index", 2**63),
        _int_in(trial_index, "trial_index", 2**63),
    ]
    words = values
    if max(values) >= 2**32:
        # SeedSequence cuts each int into as many 32-bit words as it needs and pads
        # the whole to four words with zeros, so (2**32, 0, k) and (0, 1, k) would
        # give it the same words: spell every value in two words, plus a marker
        # word that sets these seven words apart from any three small values.
        # (Values below 2**32 keep their single words: the seeds runs have had.)
        words = [w for v in values for w in (v & 0xFFFF_FFFF, v >> 32)] + [1]
    state = np.random.SeedSequence(words)
    return int(state.generate_state(2, dtype=np.uint64)[0] >> np.uint64(1))


def _int_in(value: object, name: str, upper: int) -> int:
    return bounded_int(value, name, 0, upper, exclusive=True)


def _cell(value: object, name: str) -> Cell:
    """A table cell as a Python object: NumPy scalars printed as ``np.float64(2.0)`` in reprs."""
    if value is None:
        return None
    if isinstance(value, str):
        return str.__str__(value)
    # Booleans before integers (a bool is an int): shown as yes/no, NumPy's as Python's.
    if isinstance(value, (bool, np.bool_)):
        return bool(value)
    if isinstance(value, (int, np.integer)):
        return int(value)
    if isinstance(value, (float, np.floating)):
        return float(value)
    raise TypeError(f"{name} must be text, a number or None, got {type(value).__name__}")


def _figures(value: object, name: str) -> FrozenDict[str, float]:
    """Named real figures as a new read-only mapping of floats (NaN: a figure that does not apply).

    Read-only, so that the frozen record holding it is (a plain dict could be
    changed in place, and a ``copy.copy`` of the record shared it).
    """
    if not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping of str to float, got {type(value).__name__}")
    out: dict[str, float] = {}
    for key, figure in value.items():
        if not isinstance(key, str):
            raise TypeError(f"{name} keys must be str, got {type(key).__name__}")
        # Plain str: an np.str_ key printed as np.str_('error') in the record's repr.
        key = as_text(key, f"{name} keys")
        if key in out:  # two subclass keys spelling the same text (their own hash differs)
            raise ValueError(f"{name} has the key {key!r} twice")
        # NumPy booleans too (``np.all(...)``): booleans are stored as 0.0/1.0.
        if not isinstance(figure, (int, float, np.integer, np.floating, np.bool_)):
            raise TypeError(f"{name}[{key!r}] must be a real number, got {type(figure).__name__}")
        number = float(figure)
        if math.isinf(number):
            raise ValueError(f"{name}[{key!r}] must be finite or NaN, got {number}")
        out[key] = number
    return FrozenDict.wrap(out)


def _restore_figures(record: Any, state: list[Any], name: str) -> None:
    """``__setstate__`` of a record with figures: fields from ``state``, ``name`` read-only.

    Pickles made before the figures became read-only hold a plain dict.
    """
    restore_read_only(record, state, ())
    figures = getattr(record, name)
    if type(figures) is dict or any(type(key) is not str for key in figures):
        # Older pickles may also hold np.str_ keys (before they were stored as plain str).
        plain = {as_text(key, name): figure for key, figure in figures.items()}
        object.__setattr__(record, name, FrozenDict.wrap(plain))


def _labelled(value: object, name: str, check: Callable[[Any, str], Any]) -> tuple[Any, ...]:
    out = []
    for k, item in enumerate(as_sequence(value, name)):
        pair = as_sequence(item, f"{name}[{k}]")
        if len(pair) != 2:
            raise ValueError(
                f"{name}[{k}] must be a (label, value) pair, got {counted(len(pair), 'item')}"
            )
        out.append((as_text(pair[0], f"{name}[{k}][0]"), check(pair[1], f"{name}[{k}][1]")))
    return tuple(out)


def _points(value: Any, name: str) -> FloatArray:
    """Points ``(n, 2)`` (one point ``(2,)`` becomes ``(1, 2)``) as a read-only copy."""
    arr: FloatArray = as_float_array(value, name).copy()
    if arr.shape == (2,):
        arr = arr.reshape(1, 2)
    if arr.ndim != 2 or arr.shape[1] != 2:
        raise ValueError(f"{name} must have shape (n, 2) or (2,), got {arr.shape}")
    arr.flags.writeable = False
    return arr


def _instance(cls: type, optional: bool) -> Callable[[Any, str], Any]:
    def check(value: Any, name: str) -> Any:
        if value is None and optional:
            return None
        if not isinstance(value, cls):
            raise TypeError(f"{name} must be a {cls.__name__}, got {type(value).__name__}")
        return value

    return check


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Trial:
    """One independent run of a scenario.

    Attributes
    ----------
    case : str
        What is run, for people (``"target (0, 3) m, obstacle"``); the scenario
        decodes its own cases from ``case_index``.
    case_index : int
        Position of the case in the scenario's list of cases, 0-based.
    index : int
        Trial number within the case, 0-based.
    seed : int
        The trial's own seed (see :func:`trial_seed`).

    Examples
    --------
    >>> Trial("target (0, 3) m", 0, 2, trial_seed(0, 0, 2)).index
    2
    """

    case: str
    case_index: int
    index: int
    seed: int

    def __post_init__(self) -> None:
        object.__setattr__(self, "case", as_text(self.case, "case"))
        object.__setattr__(self, "case_index", _int_in(self.case_index, "case_index", 2**63))
        object.__setattr__(self, "index", _int_in(self.index, "index", 2**63))
        object.__setattr__(self, "seed", _int_in(self.seed, "seed", 2**64))


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class TrialResult:
    """What one trial produced.

    Attributes
    ----------
    trial : Trial
        The trial that ran.
    values : Mapping[str, float]
        Named scalar outcomes in SI units (``"final_error": 0.021``); booleans
        as 0.0/1.0. Read-only (``dict(r.values)`` gives a dict to edit); equal
        to a dict with the same items.
    trace : Trace or None
        The simulated run, when the trial is one.
    wall_time : float
        Seconds of wall-clock time the trial took.

    Examples
    --------
    >>> r = TrialResult(Trial("a", 0, 0, 1), {"error": 0.02})
    >>> r.values["error"]
    0.02
    """

    trial: Trial
    values: Mapping[str, float]
    trace: Trace | None = None
    wall_time: float = 0.0

    def __post_init__(self) -> None:
        _instance(Trial, False)(self.trial, "trial")
        object.__setattr__(self, "values", _figures(self.values, "values"))
        _instance(Trace, True)(self.trace, "trace")
        wall = finite_float(self.wall_time, "wall_time")
        if wall < 0.0:
            raise ValueError(f"wall_time must be >= 0 s, got {wall}")
        object.__setattr__(self, "wall_time", wall)

    def __setstate__(self, state: list[Any]) -> None:
        _restore_figures(self, state, "values")


@frozen_setattr
@dataclass(frozen=True, slots=True)
class Table:
    """A table of figures: navkit's results, the paper's beside them.

    Attributes
    ----------
    title : str
        What the table shows.
    columns : tuple of str
        Column headings, units included (``"error (mm)"``).
    rows : tuple of tuple
        One tuple per row, as long as ``columns``: text, numbers or None,
        NumPy's stored as Python's (``str``, ``bool``, ``int``, ``float``).
    notes : tuple of str
        Sentences printed under the table (where the setup differs from the
        paper's, what the paper reports, ...).

    Examples
    --------
    >>> t = Table("errors", ("target", "navkit (mm)", "paper (mm)"), (("(0, 3)", 12.5, 31.0),))
    >>> print(t.render())
    errors
    target  navkit (mm)  paper (mm)
    ------  -----------  ----------
    (0, 3)         12.5          31
    """

    title: str
    columns: tuple[str, ...]
    rows: tuple[tuple[Cell, ...], ...]
    notes: tuple[str, ...] = ()

    # NaN cells ("no figure") equal in a table and its copy or rerun.
    def __eq__(self, other: object) -> bool:
        # A method, not ``__eq__ = record_eq``: type checkers then see object's signature.
        return record_eq(self, other)

    __hash__ = record_hash
    __repr__ = bounded_repr

    def __post_init__(self) -> None:
        object.__setattr__(self, "title", as_text(self.title, "title"))
        columns = tuple(
            as_text(c, f"columns[{i}]") for i, c in enumerate(as_sequence(self.columns, "columns"))
        )
        rows = []
        for i, row in enumerate(as_sequence(self.rows, "rows")):
            cells = as_sequence(row, f"rows[{i}]")
            if len(cells) != len(columns):
                raise ValueError(
                    f"rows[{i}] has {counted(len(cells), 'cell')} for "
                    f"{counted(len(columns), 'column')}"
                )
            rows.append(tuple(_cell(cell, f"rows[{i}][{j}]") for j, cell in enumerate(cells)))
        notes = tuple(
            as_text(n, f"notes[{i}]") for i, n in enumerate(as_sequence(self.notes, "notes"))
        )
        object.__setattr__(self, "columns", columns)
        object.__setattr__(self, "rows", tuple(rows))
        object.__setattr__(self, "notes", notes)

    def render(self, *, digits: int = 3) -> str:
        """The table as aligned plain text.

        Parameters
        ----------
        digits : int, optional
            Significant digits of floats, in [1, 17]. A float of magnitude at
            least ``10**digits`` once rounded to them prints whole, as an
            integer (``12346`` for 12345.6, ``1000`` for 999.6 at 3 digits),
            while below 1e17; from 1e17 on, where a float holds fewer
            significant digits than its integer part has, in exponent notation
            with ``digits`` significant digits.

        Returns
        -------
        str
            Title, header, rule, rows and notes, one per line.

        Raises
        ------
        TypeError
            ``digits`` not an integer (a bool is none).
        ValueError
            ``digits`` outside [1, 17].

        Examples
        --------
        >>> Table("t", ("a",), ((1.23456,),)).render(digits=2).splitlines()[-1]
        '1.2'
        >>> Table("t", ("a", "b"), ((12345.6, 1.23456789e20),)).render().splitlines()[-1]
        '12346  1.23e+20'
        """
        digits = bounded_int(digits, "digits", 1, 17)
        cells = [list(self.columns)] + [[_cell_text(c, digits) for c in row] for row in self.rows]
        widths = [max(len(r[i]) for r in cells) for i in range(len(self.columns))]

        def line(r: list[str], header: bool) -> str:
            out = []
            for i, text in enumerate(r):
                numeric = not header and i > 0 and _looks_numeric(text)
                out.append(text.rjust(widths[i]) if numeric else text.ljust(widths[i]))
            return "  ".join(out).rstrip()

        lines = [self.title, line(cells[0], True), "  ".join("-" * w for w in widths)]
        lines += [line(r, False) for r in cells[1:]]
        lines += list(self.notes)
        return "\n".join(lines)

    def to_dict(self) -> dict[str, Any]:
        """The table as JSON-ready data (NaN becomes None).

        Returns
        -------
        dict
            ``{"title", "columns", "rows", "notes"}``.

        Examples
        --------
        >>> Table("t", ("a",), ((float("nan"),),)).to_dict()["rows"]
        [[None]]
        """
        return {
            "title": self.title,
            "columns": list(self.columns),
            "rows": [[_json_cell(c) for c in row] for row in self.rows],
            "notes": list(self.notes),
        }

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> Table:
        """The table that :meth:`to_dict` gave ``data`` for (read back from JSON, say).

        Parameters
        ----------
        data : Mapping
            ``{"title", "columns", "rows", "notes"}`` as :meth:`to_dict` makes
            them (lists where it made lists; tuples are as good).

        Returns
        -------
        Table
            Equal to the table :meth:`to_dict` was called on, but that a NaN or
            infinite cell (None in ``data``) comes back as None, an empty cell:
            ``data`` cannot tell them apart.

        Raises
        ------
        TypeError
            ``data`` not a mapping, or a value of the wrong type.
        ValueError
            A key missing or unknown, a row of the wrong length.

        Examples
        --------
        >>> import json
        >>> t = Table("errors", ("case", "error (m)"), (("a", 0.25),), ("a note",))
        >>> Table.from_dict(json.loads(json.dumps(t.to_dict()))) == t
        True
        """
        return cls._from_data(data, "data")

    @classmethod
    def _from_data(cls, data: Mapping[str, Any], where: str) -> Table:
        """:meth:`from_dict`, its errors naming ``data`` as ``where`` (a result's table)."""
        fields = _record_fields(data, where, _TABLE_KEYS)
        with _naming(where):
            rows = tuple(
                as_sequence(row, f"rows[{i}]")
                for i, row in enumerate(as_sequence(fields["rows"], "rows"))
            )
            return cls(fields["title"], fields["columns"], rows, fields["notes"])


#: Floats print whole (as integers) only below this: from 1e17 on, fixed notation
#: shows digits beyond the float's 17 significant ones (1.23456789e20 as
#: 123456788999999995904), and 1e300 would print 301 digits.
_WHOLE_LIMIT = 1e17


def _cell_text(cell: Cell, digits: int) -> str:
    if cell is None:
        return ""
    if isinstance(cell, bool):
        return "yes" if cell else "no"
    if isinstance(cell, (float, np.floating)):
        if not math.isfinite(cell):
            return "-"
        value = float(cell)
        text = f"{value:.{digits}g}"
        # Exponent notation from 1 up means at least 10**digits once rounded
        # (999.6 at 3 digits too): whole, like 1000.0, while below the limit.
        if "e" in text and 1.0 <= abs(value) < _WHOLE_LIMIT:
            return f"{value:.0f}"
        return text
    return str(cell)


def _looks_numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return text == "-"
    return True


_TABLE_KEYS = ("title", "columns", "rows", "notes")
_RESULT_KEYS = ("scenario", "seed", "summary", "tables", "trials")
_TRIAL_KEYS = ("case", "case_index", "index", "seed", "values", "wall_time")


def _record_fields(data: object, name: str, keys: tuple[str, ...]) -> Mapping[str, Any]:
    """``data`` (what a ``to_dict`` made) checked to hold exactly ``keys``."""
    if not isinstance(data, Mapping):
        raise TypeError(
            f"{name} must be a mapping (what to_dict gives), got {type(data).__name__}"
        )
    expected = ", ".join(keys)
    for key in keys:
        if key not in data:
            raise ValueError(f"{name} has no {key!r} key (to_dict gives {expected})")
    for key in data:
        if key not in keys:
            raise ValueError(f"{name} has an unknown key {key!r} (to_dict gives {expected})")
    return data


def _json_figures(value: object) -> Any:
    """Figures as :func:`_json_cell` wrote them: None is NaN again (the rest checked later)."""
    if not isinstance(value, Mapping):
        return value  # refused by _figures, under the field's name
    return {key: math.nan if figure is None else figure for key, figure in value.items()}


@contextmanager
def _naming(where: str) -> Iterator[None]:
    """Errors of the records built inside prefixed with where their values came from."""
    try:
        yield
    except (TypeError, ValueError) as exc:
        raise type(exc)(f"{where}: {exc}") from None


def _json_cell(cell: Cell) -> Cell:
    if isinstance(cell, (float, np.floating)):
        return float(cell) if math.isfinite(cell) else None
    if isinstance(cell, np.integer):
        return int(cell)
    return cell


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class Scene:
    """What a picture of a scenario shows: the map, plans, driven traces, markers.

    Attributes
    ----------
    title : str
        Caption.
    grid : OccupancyGrid or None
        The map, drawn in ROS map orientation on world axes.
    world : World or None
        Shapes and circles of the simulated world (drawn over ``grid``).
    paths : tuple of (str, ndarray (n, 2))
        Labelled planned paths, world ``(x, y)`` in m (finite).
    traces : tuple of (str, Trace)
        Labelled runs: true poses solid, estimates dashed.
    points : tuple of (str, ndarray (n, 2))
        Labelled markers (starts, goals, targets), world ``(x, y)`` in m
        (finite; a single ``(2,)`` point is stored as ``(1, 2)``).

    Notes
    -----
    Every part is checked on construction (``TypeError``/``ValueError`` naming
    it, e.g. ``paths[0][1]``); arrays are stored as read-only copies.

    Examples
    --------
    >>> Scene("empty").paths
    ()
    """

    title: str
    grid: OccupancyGrid | None = None
    world: World | None = None
    paths: tuple[tuple[str, FloatArray], ...] = ()
    traces: tuple[tuple[str, Trace], ...] = ()
    points: tuple[tuple[str, FloatArray], ...] = ()

    __repr__ = bounded_repr

    def __post_init__(self) -> None:
        object.__setattr__(self, "title", as_text(self.title, "title"))
        _instance(OccupancyGrid, True)(self.grid, "grid")
        _instance(World, True)(self.world, "world")
        object.__setattr__(self, "paths", _labelled(self.paths, "paths", _points))
        traces = _labelled(self.traces, "traces", _instance(Trace, False))
        object.__setattr__(self, "traces", traces)
        object.__setattr__(self, "points", _labelled(self.points, "points", _points))

    def __setstate__(self, state: list[Any]) -> None:
        # Pickles and deep copies skip __post_init__: the labelled arrays (inside
        # tuples, which restore_read_only does not reach) are made read-only here.
        restore_read_only(self, state, ())
        self._freeze_nested()

    def _freeze_nested(self) -> None:
        # Also called after a user's subclass state is restored (which skips
        # __setstate__): see navkit._shared.frozen.rebuild_from_state. Views, so
        # that an array the state shares with someone else stays theirs.
        for name in ("paths", "points"):
            labelled = getattr(self, name, ())
            if any(xy.flags.writeable for _, xy in labelled):
                frozen = tuple((label, read_only_view(xy)) for label, xy in labelled)
                object.__setattr__(self, name, frozen)


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class ScenarioResult:
    """A scenario's outcome: every trial, the tables, and what to draw.

    Attributes
    ----------
    scenario : str
        The scenario's name (``"omni-apf"``).
    seed : int
        The base seed the trials' seeds came from.
    trials : tuple of TrialResult
        Every trial, in the scenario's order (case, then trial index) whatever
        order they ran in: the total over the cases, not the ``trials``
        argument of :meth:`Scenario.run` and :func:`~navkit.sim.sweep`, which
        is trials per case (as ``navkit run --trials``).
    tables : tuple of Table
        navkit's figures beside the paper's.
    summary : Mapping[str, float]
        The headline figures, named, SI units (what tests and sweeps compare).
        Read-only (``dict(r.summary)`` gives a dict to edit); equal to a dict
        with the same items.
    scene : Scene or None
        A representative picture of the run, for ``--plot``.

    Examples
    --------
    >>> r = ScenarioResult("x", 0, (), (Table("t", ("a",), ((1.0,),)),), {"a": 1.0})
    >>> r.to_dict()["summary"]
    {'a': 1.0}
    """

    scenario: str
    seed: int
    trials: tuple[TrialResult, ...]
    tables: tuple[Table, ...]
    summary: Mapping[str, float] = field(default_factory=dict)
    scene: Scene | None = None

    __repr__ = bounded_repr  # a trace per trial: print a few

    def __post_init__(self) -> None:
        object.__setattr__(self, "scenario", as_text(self.scenario, "scenario"))
        object.__setattr__(self, "seed", _int_in(self.seed, "seed", 2**64))
        trials = as_sequence(self.trials, "trials")
        for k, r in enumerate(trials):
            _instance(TrialResult, False)(r, f"trials[{k}]")
        tables = as_sequence(self.tables, "tables")
        for k, t in enumerate(tables):
            _instance(Table, False)(t, f"tables[{k}]")
        object.__setattr__(self, "trials", trials)
        object.__setattr__(self, "tables", tables)
        object.__setattr__(self, "summary", _figures(self.summary, "summary"))
        _instance(Scene, True)(self.scene, "scene")

    def __setstate__(self, state: list[Any]) -> None:
        _restore_figures(self, state, "summary")

    @property
    def traces(self) -> tuple[Trace, ...]:
        """Every trial's trace, in trial order (trials without one are skipped).

        Returns
        -------
        tuple of Trace
            The simulated runs.

        Examples
        --------
        >>> ScenarioResult("x", 0, (), ()).traces
        ()
        """
        return tuple(r.trace for r in self.trials if r.trace is not None)

    def table(self, *, digits: int = 3) -> str:
        """Every table as plain text, navkit's figures beside the paper's.

        Parameters
        ----------
        digits : int, optional
            Significant digits of floats, in [1, 17].

        Returns
        -------
        str
            The tables separated by blank lines.

        Raises
        ------
        TypeError
            ``digits`` not an integer (a bool is none).
        ValueError
            ``digits`` outside [1, 17].

        Examples
        --------
        >>> print(ScenarioResult("x", 0, (), (Table("t", ("a",), ((1.0,),)),)).table())
        t
        a
        -
        1
        """
        digits = _int_in(digits, "digits", 18)
        return "\n\n".join(t.render(digits=digits) for t in self.tables)

    def to_dict(self) -> dict[str, Any]:
        """The result as JSON-ready data (no traces; NaN becomes None).

        Returns
        -------
        dict
            ``{"scenario", "seed", "summary", "tables", "trials"}``; each trial
            as ``{"case", "case_index", "index", "seed", "values", "wall_time"}``.

        Examples
        --------
        >>> import json
        >>> json.dumps(ScenarioResult("x", 0, (), ()).to_dict())
        '{"scenario": "x", "seed": 0, "summary": {}, "tables": [], "trials": []}'
        """
        data = {
            "scenario": self.scenario,
            "seed": int(self.seed),
            "summary": {k: _json_cell(float(v)) for k, v in self.summary.items()},
            "tables": [t.to_dict() for t in self.tables],
            "trials": [
                {
                    "case": r.trial.case,
                    "case_index": r.trial.case_index,
                    "index": r.trial.index,
                    "seed": r.trial.seed,
                    "values": {k: _json_cell(float(v)) for k, v in r.values.items()},
                    "wall_time": float(r.wall_time),
                }
                for r in self.trials
            ],
        }
        json.dumps(data)  # fail here, not in the caller's writer, if something slipped in
        return data

    @classmethod
    def from_dict(cls, data: Mapping[str, Any]) -> ScenarioResult:
        """The result that :meth:`to_dict` gave ``data`` for (``navkit run --json``'s file, say).

        For comparing runs saved as JSON: the tables print as they did
        (:meth:`table`) but for NaN cells (printed ``-``, they come back empty:
        JSON has no NaN), and the trials' figures and the summary are there to
        compare. What :meth:`to_dict` leaves out is not restored: the traces
        and the scene are None.

        Parameters
        ----------
        data : Mapping
            ``{"scenario", "seed", "summary", "tables", "trials"}`` as
            :meth:`to_dict` makes them (lists where it made lists; tuples are
            as good).

        Returns
        -------
        ScenarioResult
            The scenario, seed, trials (without traces), tables and summary.
            A figure that was NaN (None in ``data``) is NaN again; a table cell
            that was NaN or infinite comes back as None (see
            :meth:`Table.from_dict`).

        Raises
        ------
        TypeError
            ``data`` not a mapping, or a value of the wrong type.
        ValueError
            A key missing or unknown, a value out of its range (a negative
            seed, an infinite figure).

        Examples
        --------
        >>> import json
        >>> trial = TrialResult(Trial("target (0, 3) m", 0, 0, 7), {"error": 0.02}, wall_time=0.5)
        >>> result = ScenarioResult("x", 0, (trial,), (), {"error": float("nan")})
        >>> back = ScenarioResult.from_dict(json.loads(json.dumps(result.to_dict())))
        >>> back.trials[0].values["error"], back.summary["error"]
        (0.02, nan)
        >>> back.to_dict() == result.to_dict()
        True
        """
        fields = _record_fields(data, "data", _RESULT_KEYS)
        trials = []
        for k, item in enumerate(as_sequence(fields["trials"], "data['trials']")):
            where = f"data['trials'][{k}]"
            trial = _record_fields(item, where, _TRIAL_KEYS)
            with _naming(where):
                trials.append(
                    TrialResult(
                        Trial(trial["case"], trial["case_index"], trial["index"], trial["seed"]),
                        _json_figures(trial["values"]),
                        wall_time=trial["wall_time"],
                    )
                )
        tables = tuple(
            Table._from_data(table, f"data['tables'][{k}]")
            for k, table in enumerate(as_sequence(fields["tables"], "data['tables']"))
        )
        with _naming("data"):
            return cls(
                fields["scenario"],
                fields["seed"],
                tuple(trials),
                tables,
                _json_figures(fields["summary"]),
            )


class DaskClient(Protocol):
    """What ``sweep`` takes of a ``dask.distributed.Client`` (dask is not imported).

    The run-time check is duck-typed (callable ``submit`` and ``gather``); ``cancel``
    is called when a trial fails. The parameters are positional-only and the rest
    ``Any``, so that the Client's own signatures (and any stand-in's) satisfy it.
    """

    def submit(self, func: Callable[..., Any], /, *args: Any, **kwargs: Any) -> Any:
        """Run ``func(*args)`` on the cluster; a future."""

    def gather(self, futures: Any, /) -> Any:
        """The results of futures."""

    def cancel(self, futures: Any, /) -> Any:
        """Stop futures not yet run."""


#: Where ``sweep`` and ``Scenario.run`` run trials, besides their own pool.
TrialExecutor = concurrent.futures.Executor | DaskClient


class Scenario(ABC):
    """One source paper's experiment, split into independent trials.

    Subclasses set the class attributes, take their options keyword-only in
    ``__init__`` (plain, picklable values: a scenario object travels to worker
    processes and cluster workers with each trial) and implement
    :meth:`cases`, :meth:`run_trial` and :meth:`summarize`. Heavy setup (maps,
    worlds, planners) is built lazily inside :meth:`run_trial` and cached per
    process, never stored on the scenario object.

    Attributes
    ----------
    name : str
        Command-line name (``"omni-apf"``).
    title : str
        One line for ``navkit list``.
    paper : str
        The source paper.
    default_trials : int
        Trials per case in the paper's setup.

    Examples
    --------
    >>> class Coin(Scenario):  # the whole contract: a seeded coin, flipped once per trial
    ...     name, title, paper, default_trials = "coin", "a fair coin", "none", 100
    ...     def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
    ...         return (("fair coin", trials),)
    ...     def run_trial(self, trial: Trial) -> TrialResult:
    ...         heads = np.random.default_rng(trial.seed).random() < 0.5
    ...         return TrialResult(trial, {"heads": float(heads)})
    ...     def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
    ...         share = float(np.mean([r.values["heads"] for r in results]))
    ...         table = Table("coin", ("case", "heads (share)"), (("fair coin", share),))
    ...         return ScenarioResult(self.name, seed, tuple(results), (table,), {"heads": share})
    >>> result = Coin().run(seed=1)  # default_trials trials of each case
    >>> len(result.trials), 0.35 < result.summary["heads"] < 0.65
    (100, True)
    >>> Coin().run(seed=1).summary == result.summary  # the same seed, the same figures
    True
    """

    name: ClassVar[str]
    title: ClassVar[str]
    paper: ClassVar[str]
    default_trials: ClassVar[int]

    @abstractmethod
    def cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """The cases to run and how many trials each gets.

        Parameters
        ----------
        trials : int
            Trials per case asked for (>= 1); deterministic cases may run once
            whatever it is.

        Returns
        -------
        tuple of (str, int)
            ``(case description, number of trials)`` in the scenario's order:
            each number in [0, 100000], 1000000 at most in all (a run refuses
            more with ``ValueError``).

        Examples
        --------
        >>> from navkit.sim.scenarios import Demo
        >>> [count for _, count in Demo(map="office").cases(2)]  # three legs, two trials each
        [2, 2, 2]
        """

    @abstractmethod
    def run_trial(self, trial: Trial) -> TrialResult:
        """Run one trial; must depend only on the scenario's options and ``trial``.

        Parameters
        ----------
        trial : Trial
            Which case, which trial, which seed.

        Returns
        -------
        TrialResult
            The trial's values (and trace, when it simulates a run).

        Examples
        --------
        >>> from navkit.sim.scenarios import Demo
        >>> demo = Demo(map="office", duration=0.2)  # 0.2 s of each leg: a cheap trial
        >>> r = demo.run_trial(demo.trials(1, seed=0)[1])
        >>> assert r.trace is not None  # Demo simulates every trial
        >>> r.trial.case_index, r.trace.metrics.duration, r.values["collisions"]  # s
        (1, 0.2, 0.0)
        >>> demo.run_trial(r.trial).values["distance"] == r.values["distance"]  # reproducible
        True
        """

    @abstractmethod
    def summarize(self, results: Sequence[TrialResult], *, seed: int) -> ScenarioResult:
        """Fold the trials into tables beside the paper's figures.

        Parameters
        ----------
        results : sequence of TrialResult
            Every trial of :meth:`trials`, in order.
        seed : int
            The base seed (recorded in the result).

        Returns
        -------
        ScenarioResult
            Tables, summary and scene.

        Examples
        --------
        >>> from navkit.sim.scenarios import Demo
        >>> demo = Demo(map="office", duration=0.2)
        >>> results = [demo.run_trial(t) for t in demo.trials(1, seed=3)]
        >>> result = demo.summarize(results, seed=3)
        >>> result.seed, len(result.trials), result.summary["legs"]
        (3, 3, 3.0)
        """

    def trials(self, trials: int | None = None, *, seed: int = 0) -> tuple[Trial, ...]:
        """Every trial of a run, in order, each with its own seed.

        Parameters
        ----------
        trials : int, optional
            Trials per case (default :attr:`default_trials`), in [1, 100000];
            at most 1000000 trials over all the cases (``ValueError``).
        seed : int, optional
            The base seed, in [0, 2**64).

        Returns
        -------
        tuple of Trial
            Case by case, trial by trial.

        Raises
        ------
        TypeError
            ``trials`` or ``seed`` not an integer (bools included); a
            subclass's :meth:`cases` not returning ``(description, count)``
            pairs.
        ValueError
            ``trials`` or ``seed`` out of range; the cases' counts out of range
            or summing to more than 1000000.

        Examples
        --------
        >>> from navkit.sim.scenarios import Demo
        >>> trials = Demo(map="office").trials(2, seed=5)  # three legs, two trials each
        >>> [(t.case_index, t.index) for t in trials][:3]
        [(0, 0), (0, 1), (1, 0)]
        >>> trials[3].seed == trial_seed(5, 1, 1) != trials[2].seed
        True
        """
        n = self._check_trials(self.default_trials if trials is None else trials)
        # Checked here, under the caller's name (trial_seed would call it ``base``).
        base = _int_in(seed, "seed", 2**64)
        out: list[Trial] = []
        for ci, (case, count) in enumerate(self._checked_cases(n)):
            out.extend(Trial(case, ci, k, trial_seed(base, ci, k)) for k in range(count))
        return tuple(out)

    def run(
        self,
        trials: int | None = None,
        *,
        seed: int = 0,
        workers: int | None = 1,
        executor: TrialExecutor | None = None,
        progress: Callable[[int, int], object] | None = None,
        keep_traces: bool = True,
    ) -> ScenarioResult:
        """Run every trial and summarize: :func:`~navkit.sim.sweep` on this scenario.

        Parameters
        ----------
        trials : int, optional
            Trials per case (default :attr:`default_trials`), in [1, 100000];
            at most 1000000 trials over all the cases (``ValueError``).
        seed : int, optional
            The base seed, in [0, 2**64); the same seed gives the same result.
        workers : int or None, optional
            Processes to use, as for :func:`~navkit.sim.sweep`: 1 (the default
            here) runs in this process, None uses every core this process may
            use (its CPU affinity; the default of ``sweep``, ``warmup`` and
            ``navkit run``). Not used when ``executor`` is given (still checked).
        executor : concurrent.futures.Executor or dask.distributed.Client, optional
            Where to run the trials.
        progress : callable, optional
            Called as ``progress(done, total)`` after each trial.
        keep_traces : bool, optional
            Keep each trial's trace (the default). False drops it where the
            trial ran, once its values are computed: the trials' ``trace``
            is None and the scene draws no driven runs; the tables, summary
            and ``to_dict()`` are the same (up to wall-clock measurements).

        Returns
        -------
        ScenarioResult
            Tables beside the paper's, summary, trials and scene. By default
            it keeps every trial's trace, so memory grows with the number of
            trials: 80 bytes a recorded step, about 127 kB a trial for
            ``Greedy``; ``keep_traces=False`` keeps the values alone (see
            :func:`~navkit.sim.sweep`).

        Raises
        ------
        TypeError
            ``trials``, ``seed`` or ``workers`` not an integer (bools
            included), ``keep_traces`` not a bool, ``progress`` not callable,
            or as :meth:`trials`.
        ValueError
            ``trials``, ``seed`` or ``workers`` out of range, or as
            :meth:`trials`.

        Examples
        --------
        >>> from navkit.sim.scenarios import Demo
        >>> demo = Demo(map="office", duration=0.2)
        >>> done: list[tuple[int, int]] = []
        >>> result = demo.run(trials=1, seed=3, progress=lambda k, n: done.append((k, n)))
        >>> done, [r.trial.case_index for r in result.trials]
        ([(1, 3), (2, 3), (3, 3)], [0, 1, 2])
        >>> by_hand = demo.summarize([demo.run_trial(t) for t in demo.trials(1, seed=3)], seed=3)
        >>> result.summary["travel_time"] == by_hand.summary["travel_time"]
        True
        >>> lean = demo.run(trials=1, seed=3, keep_traces=False)  # values only, same figures
        >>> lean.traces, lean.summary["travel_time"] == result.summary["travel_time"]
        ((), True)
        """
        from navkit.sim._sweep import sweep  # _sweep imports this module

        # Checked here, under the caller's name (sweep would call it ``seeds``); a 0-d
        # array is one seed, as sweep takes it.
        value: object = seed
        if is_ndarray(value) and value.ndim == 0:
            value = value[()]
        base = _int_in(value, "seed", 2**64)
        return sweep(
            self,
            trials=trials,
            seeds=base,
            workers=workers,
            executor=executor,
            progress=progress,
            keep_traces=keep_traces,
        )

    # Argument checks every scenario shares (protected: for subclasses).

    @staticmethod
    def _check_trials(trials: object) -> int:
        """``trials`` per case (the argument of :meth:`cases`) as an int in [1, 100000].

        Raises TypeError for a non-integer (bools included), ValueError out of range.
        """
        return bounded_int(trials, "trials", 1, _MAX_TRIALS)

    def _checked_cases(self, trials: int) -> tuple[tuple[str, int], ...]:
        """:meth:`cases` of ``trials``, checked: ``(description, count)`` pairs.

        A subclass's slip is named here rather than run: a negative or boolean
        count would run no trial (or one) of its case without a word, and a
        count beyond the ``trials`` limit (100000), or counts adding up to more
        than 1000000 (10^5 cases of 10^5 trials), would build that many trials.
        """
        where = f"{type(self).__name__}.cases({trials})"
        cases: object = self.cases(trials)
        if isinstance(cases, (str, bytes, Mapping, set, frozenset)) or not isinstance(
            cases, Iterable
        ):
            raise TypeError(
                f"{where} must return a sequence of (description, count) pairs, "
                f"got {type(cases).__name__}"
            )
        out = []
        total = 0
        for k, item in enumerate(cases):
            if isinstance(item, (str, bytes)) or not isinstance(item, Sequence):
                raise TypeError(
                    f"{where}[{k}] must be a (description, count) pair, got {type(item).__name__}"
                )
            if len(item) != 2:
                raise TypeError(
                    f"{where}[{k}] must be a (description, count) pair, "
                    f"got a {type(item).__name__} of {len(item)}"
                )
            case, count = item
            if not isinstance(case, str):
                raise TypeError(
                    f"{where}[{k}]: the description must be a str, got {type(case).__name__}"
                )
            try:
                checked = bounded_int(count, "the count", 0, _MAX_TRIALS)
            except (TypeError, ValueError) as exc:
                raise type(exc)(f"{where}[{k}]: {exc}") from None
            total += checked
            if total > _MAX_TOTAL_TRIALS:
                # Said at the first case past the limit, before any more of the cases run.
                raise ValueError(
                    f"{where}: cases 0..{k} ask for {total} trials; a run may have at most "
                    f"{_MAX_TOTAL_TRIALS} over all its cases (lower trials)"
                )
            out.append((case, checked))
        return tuple(out)

    def _case_count(self) -> int:
        """How many cases the scenario has (of :meth:`cases` of 1, checked)."""
        return len(self._checked_cases(1))

    def _case_of(self, trial: object) -> int:
        """The case index of ``trial`` (the argument of :meth:`run_trial`), checked.

        Raises TypeError when ``trial`` is not a :class:`Trial`, ValueError when
        its ``case_index`` is not one of :meth:`cases`.
        """
        if not isinstance(trial, Trial):
            raise TypeError(f"trial must be a Trial, got {type(trial).__name__}")
        count = self._case_count()
        if trial.case_index >= count:
            raise ValueError(f"trial.case_index must be in [0, {count}), got {trial.case_index}")
        return trial.case_index

    def _results_by_case(
        self,
        results: object,
        seed: object,
        *,
        keys: Callable[[int], Iterable[str]] | None = None,
    ) -> tuple[tuple[TrialResult, ...], dict[int, list[TrialResult]], int]:
        """The checked arguments of :meth:`summarize`, and the results by case index.

        Parameters
        ----------
        results : iterable of TrialResult
            Any ordered iterable (not a str, bytes, mapping or set) of
            TrialResults whose ``trial.case_index`` is one of :meth:`cases`.
        seed : int
            The base seed, in [0, 2**64).
        keys : callable, optional
            ``keys(case_index)``: the value names every result of that case must
            hold (ValueError naming the missing ones otherwise).

        Returns
        -------
        tuple
            ``(results as a tuple in the given order, {case_index: [results in
            order]} (keys in order of first appearance), seed as an int)``.
        """
        if isinstance(results, (Mapping, str, bytes, set, frozenset)) or not isinstance(
            results, Iterable
        ):
            raise TypeError(
                f"results must be a sequence of TrialResult, got {type(results).__name__}"
            )
        out = tuple(results)
        base = _int_in(seed, "seed", 2**64)
        count = self._case_count()
        by_case: dict[int, list[TrialResult]] = {}
        for k, r in enumerate(out):
            if not isinstance(r, TrialResult):
                raise TypeError(f"results[{k}] must be a TrialResult, got {type(r).__name__}")
            index = r.trial.case_index
            if index >= count:
                raise ValueError(
                    f"results[{k}].trial.case_index must be in [0, {count}), got {index}"
                )
            if keys is not None:
                missing = [key for key in keys(index) if key not in r.values]
                if missing:
                    raise ValueError(f"results[{k}].values lack {', '.join(missing)}")
            by_case.setdefault(index, []).append(r)
        return out, by_case, base
