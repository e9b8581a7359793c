"""What an experiment is: trials, their results, tables of figures and a scene to draw.

A :class:`Scenario` describes one source paper's experiment. It splits into
independent :class:`Trial` s (a case and a seed each) so that
:func:`~navkit.sim.sweep` can run them anywhere — in this process, a process
pool or a Dask cluster — and get the same numbers; the scenario then folds the
:class:`TrialResult` s into a :class:`ScenarioResult` with the paper's figures
beside navkit's.
"""

from __future__ import annotations

import json
import math
from abc import ABC, abstractmethod
from collections.abc import Callable, Mapping, Sequence
from dataclasses import dataclass, field
from typing import Any, ClassVar

import numpy as np

from navkit._shared.types import FloatArray
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

Cell = str | int | float | np.integer | np.floating | None
"""One table cell: text, a number (NaN shown as ``-``) or nothing."""


def trial_seed(base: int, case_index: int, trial_index: int) -> int:
    """The seed of one trial, from the run's base seed and the trial's place.

    The seed depends only on ``(base, case_index, trial_index)``, never on the
    order trials run in or on which worker runs them, so a sweep gives the same
    numbers on one core, a process pool or a cluster.

    Parameters
    ----------
    base : int
        The run's seed, >= 0.
    case_index, trial_index : int
        The trial's case (0-based, in the scenario's order) and its number
        within the case (0-based).

    Returns
    -------
    int
        A seed in [0, 2**63).

    Examples
    --------
    >>> trial_seed(0, 0, 1) == trial_seed(0, 0, 1) != trial_seed(0, 0, 2)
    True
    """
    for name, value in (("base", base), ("case_index", case_index), ("trial_index", trial_index)):
        if isinstance(value, bool) or not isinstance(value, (int, np.integer)):
            raise TypeError(f"{name} must be an integer, got {type(value).__name__}")
        if not 0 <= value < 2**64:
            raise ValueError(f"{name} must be in [0, 2**64), got {value}")
    state = np.random.SeedSequence([int(base), int(case_index), int(trial_index)])
    return int(state.generate_state(2, dtype=np.uint64)[0] >> np.uint64(1))


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


@dataclass(frozen=True, slots=True, eq=False)
class TrialResult:
    """What one trial produced.

    Attributes
    ----------
    trial : Trial
        The trial that ran.
    values : Mapping[str, float]
        Named scalar outcomes in SI units (``"final_error": 0.021``); booleans
        as 0.0/1.0. JSON-ready.
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
        One tuple per row, as long as ``columns``: text, numbers or None.
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

    def __post_init__(self) -> None:
        for row in self.rows:
            if len(row) != len(self.columns):
                raise ValueError(
                    f"rows: a row has {len(row)} cells for {len(self.columns)} columns"
                )

    def render(self, *, digits: int = 3) -> str:
        """The table as aligned plain text.

        Parameters
        ----------
        digits : int, optional
            Significant digits of floats.

        Returns
        -------
        str
            Title, header, rule, rows and notes, one per line.

        Examples
        --------
        >>> Table("t", ("a",), ((1.23456,),)).render(digits=2).splitlines()[-1]
        '1.2'
        """
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


def _cell_text(cell: Cell, digits: int) -> str:
    if cell is None:
        return ""
    if isinstance(cell, bool):
        return "yes" if cell else "no"
    if isinstance(cell, (float, np.floating)):
        if not math.isfinite(cell):
            return "-"
        return f"{float(cell):.{digits}g}" if abs(cell) < 10**digits else f"{float(cell):.0f}"
    return str(cell)


def _looks_numeric(text: str) -> bool:
    try:
        float(text)
    except ValueError:
        return text == "-"
    return True


def _json_cell(cell: Cell) -> Cell:
    if isinstance(cell, (float, np.floating)):
        return float(cell) if math.isfinite(cell) else None
    if isinstance(cell, np.integer):
        return int(cell)
    return cell


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
        Labelled planned paths, world ``(x, y)`` in m.
    traces : tuple of (str, Trace)
        Labelled runs: true poses solid, estimates dashed.
    points : tuple of (str, ndarray (n, 2))
        Labelled markers (starts, goals, targets), world ``(x, y)`` in m.

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
        order they ran in.
    tables : tuple of Table
        navkit's figures beside the paper's.
    summary : Mapping[str, float]
        The headline figures, named, SI units (what tests and sweeps compare).
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
            Significant digits of floats.

        Returns
        -------
        str
            The tables separated by blank lines.

        Examples
        --------
        >>> print(ScenarioResult("x", 0, (), (Table("t", ("a",), ((1.0,),)),)).table())
        t
        a
        -
        1
        """
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
            ``(case description, number of trials)`` in the scenario's order.
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
        """

    def trials(self, trials: int | None = None, *, seed: int = 0) -> tuple[Trial, ...]:
        """Every trial of a run, in order, each with its own seed.

        Parameters
        ----------
        trials : int, optional
            Trials per case (default :attr:`default_trials`).
        seed : int, optional
            The base seed, >= 0.

        Returns
        -------
        tuple of Trial
            Case by case, trial by trial.
        """
        n = self.default_trials if trials is None else trials
        if isinstance(n, bool) or not isinstance(n, (int, np.integer)):
            raise TypeError(f"trials must be an integer, got {type(n).__name__}")
        if not 1 <= n <= 100_000:
            raise ValueError(f"trials must be in [1, 100000], got {n}")
        out: list[Trial] = []
        for ci, (case, count) in enumerate(self.cases(int(n))):
            out.extend(Trial(case, ci, k, trial_seed(seed, ci, k)) for k in range(count))
        return tuple(out)

    def run(
        self,
        trials: int | None = None,
        *,
        seed: int = 0,
        workers: int | None = 1,
        executor: Any = None,
        progress: Callable[[int, int], None] | None = None,
    ) -> ScenarioResult:
        """Run every trial and summarize: :func:`~navkit.sim.sweep` on this scenario.

        Parameters
        ----------
        trials : int, optional
            Trials per case (default :attr:`default_trials`).
        seed : int, optional
            The base seed, >= 0; the same seed gives the same result.
        workers : int or None, optional
            Processes to use; 1 (default) runs in this process, None uses
            every core. Ignored when ``executor`` is given.
        executor : concurrent.futures.Executor or dask.distributed.Client, optional
            Where to run the trials.
        progress : callable, optional
            Called as ``progress(done, total)`` after each trial.

        Returns
        -------
        ScenarioResult
            Tables beside the paper's, summary, trials and scene.
        """
        from navkit.sim._sweep import sweep  # _sweep imports this module

        return sweep(
            self, trials=trials, seeds=seed, workers=workers, executor=executor, progress=progress
        )
