"""``navkit list``, ``navkit run SCENARIO`` and ``navkit demo``."""

from __future__ import annotations

import argparse
import contextlib
import inspect
import time
from collections.abc import Iterator
from pathlib import Path
from typing import Any, TextIO

from navkit._shared.cores import usable_cores
from navkit._shared.counts import counted
from navkit._shared.relative_paths import relative_to_cwd
from navkit.cli._kernels import announce_compilation, check_cache
from navkit.cli._outputs import (
    check_distinct,
    check_output,
    save_animation,
    save_json,
    save_picture,
)
from navkit.cli._progress import ProgressBar
from navkit.sim import Scenario, ScenarioResult, Table, sweep
from navkit.sim.scenarios import get_scenario

__all__ = ["list_scenarios", "run_scenario"]


def list_scenarios(out: TextIO) -> int:
    """Print every experiment: name, default trials per case, what it runs."""
    # Here, not at the top: SCENARIOS imports every scenario's module, `navkit run` only its own.
    from navkit.sim.scenarios import SCENARIOS

    rows = tuple((name, cls.default_trials, cls.title) for name, cls in sorted(SCENARIOS.items()))
    table = Table(
        "navkit's experiments (navkit run SCENARIO)", ("scenario", "trials", "what it runs"), rows
    )
    print(table.render(), file=out)
    return 0


def _construct(name: str, args: argparse.Namespace) -> Scenario:
    """The scenario with the command line's options (those its constructor takes)."""
    cls = get_scenario(name)
    accepted = inspect.signature(cls).parameters
    options: dict[str, Any] = {}
    if getattr(args, "data", None) is not None and "data_dir" in accepted:
        options["data_dir"] = args.data
    if getattr(args, "map", None) is not None and "map" in accepted:
        options["map"] = args.map
    return cls(**options)


@contextlib.contextmanager
def _dask_client(address: str | None) -> Iterator[Any]:
    """A ``dask.distributed.Client`` connected to ``address`` (None: no client)."""
    if address is None:
        yield None
        return
    try:
        from dask.distributed import Client
    except ImportError as exc:
        raise ImportError(
            "--scheduler needs Dask's distributed scheduler: pip install 'navkit[distributed]'"
        ) from exc
    connect: Any = Client  # untyped
    try:
        client = connect(address, timeout="10s")
    except (OSError, ValueError) as exc:
        # Dask's message ("missing port number in address 'x'", "Timed out trying
        # to connect ...") names the address but not the option the user gave it in.
        error = OSError if isinstance(exc, OSError) else ValueError
        raise error(f"--scheduler: {exc}") from exc
    try:
        yield client
    finally:
        client.close()


def run_scenario(
    args: argparse.Namespace, out: TextIO, err: TextIO, *, name: str, workers: int | None
) -> int:
    """Run a scenario as the options say; print its tables; write the files asked for."""
    check_output(args.plot, ".png", "--plot")
    check_output(args.animate, ".gif", "--animate")
    check_output(args.json, "", "--json")
    check_distinct({"--plot": args.plot, "--animate": args.animate, "--json": args.json})
    address = getattr(args, "scheduler", None)
    if args.data == "":
        # Path("") is the working directory: taken as the data folder by the check
        # below, and refused by the scenarios in their keyword's words (data_dir).
        raise ValueError(
            "--data must not be empty: leave it out to look in $NAVKIT_DATA, then "
            "shared/data nearby"
        )
    if args.data is not None and address is None and not Path(args.data).is_dir():
        # Scenarios fall back to other places or to built-in maps when the data is
        # absent: a mistyped --data would go unnoticed. (With --scheduler the
        # folder is the workers', which need not exist here.)
        raise FileNotFoundError(f"--data: {args.data} is not a folder{relative_to_cwd(args.data)}")
    # (A Dask cluster's workers compile, and cache, on their own machines.) Checked
    # before the scenario is made: making one may run a kernel (greedy's A* route),
    # and an unusable cache was then reported as the library's two-line warning.
    problem = check_cache(err) if address is None else None
    scenario = _construct(name, args)
    total = len(scenario.trials(args.trials, seed=args.seed))
    if address is None and not args.quiet:
        processes = _processes(workers, total)
        announce_compilation("simulation", err, problem=problem, processes=processes)
    began = time.perf_counter()
    with (
        _dask_client(address) as client,
        ProgressBar(err, enabled=not args.quiet, description=scenario.name) as bar,
    ):
        bar.start(total)
        # Only a picture draws the traces: without one a long run holds the values
        # alone (a Greedy trial's trace is ~127 kB; the tables and JSON never use it).
        drawn = args.plot is not None or args.animate is not None
        result: ScenarioResult = sweep(
            scenario, trials=args.trials, seeds=args.seed, workers=workers, executor=client,
            progress=bar, keep_traces=drawn,
        )  # fmt: skip
        where = _where(address, workers, total)
    elapsed = time.perf_counter() - began
    print(result.table(), file=out)
    print(f"\n{counted(total, 'trial')} in {elapsed:.1f} s ({where}), seed {args.seed}", file=out)
    if args.json is not None:
        print(f"wrote {save_json(result, args.json)}", file=out)
    if args.plot is not None or args.animate is not None:
        if result.scene is None:
            raise ValueError(f"{scenario.name} has no scene to draw")
        if args.plot is not None:
            print(f"wrote {save_picture(result.scene, args.plot)}", file=out)
        if args.animate is not None:
            print(f"wrote {save_animation(result.scene, args.animate)}", file=out)
    return 0


def _processes(workers: int | None, total: int) -> int:
    """How many local processes sweep runs ``total`` trials on (1: this one)."""
    # sweep's rule: min(workers or the usable cores, trials) processes; 1 is this process.
    return max(1, min(workers if workers is not None else usable_cores(), total))


def _where(address: str | None, workers: int | None, total: int) -> str:
    if address is not None:
        return f"Dask scheduler {address}"
    n = _processes(workers, total)
    return "this process" if n <= 1 else f"{n} local processes"
