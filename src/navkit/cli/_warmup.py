"""``navkit warmup``: compile every kernel now, print what was compiled and how long it took."""

from __future__ import annotations

import argparse
import warnings
from typing import TextIO

from navkit._shared.counts import counted
from navkit._shared.jit import cache_problem, jit_disabled
from navkit.errors import KernelCacheWarning
from navkit.sim import Table, WarmupReport, warmup

__all__ = ["report_table", "warmup_command"]


class _StepProgress:
    """``progress(done, total)`` drawn as one self-rewriting line, on terminals only."""

    __slots__ = ("_enabled", "_stream")

    def __init__(self, stream: TextIO, *, enabled: bool) -> None:
        isatty = getattr(stream, "isatty", None)
        self._enabled = bool(enabled and isatty is not None and isatty())
        self._stream = stream

    def __call__(self, done: int, total: int) -> None:
        if not self._enabled:
            return
        end = "\n" if done == total else ""
        self._stream.write(f"\rnavkit: compiling navkit's kernels: {done}/{total} steps{end}")
        self._stream.flush()


def report_table(report: WarmupReport) -> Table:
    """The warm-up's steps as a table: kernels compiled and loaded, wall and CPU seconds.

    Examples
    --------
    >>> from navkit.sim import WarmupStep
    >>> step = WarmupStep("astar", ("k1", "k2"), (), 1.5, 1.25)
    >>> table = report_table(WarmupReport((step,), 1.5, 1))
    >>> table.rows[0][:3], table.rows[-1][0]
    (('astar', 2, 0), 'total')
    """
    rows = [
        (s.name, len(s.compiled), len(s.loaded), s.seconds, s.cpu_seconds) for s in report.steps
    ]
    rows.append(
        ("total", len(report.compiled), len(report.loaded), report.seconds, report.cpu_seconds)
    )
    processes = "this process" if report.workers == 1 else f"{report.workers} processes"
    return Table(
        f"navkit warmup ({processes})",
        ("step", "kernels compiled", "loaded from cache", "wall (s)", "CPU (s)"),
        tuple(rows),
    )


def warmup_command(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Compile (or load) every kernel and print the report table; exit code 0.

    Raises
    ------
    OSError
        numba has nowhere to cache the kernels (a read-only installation and
        no ``NUMBA_CACHE_DIR``): compiling them now would be lost.
    """
    if jit_disabled():
        print("numba's JIT is disabled (NUMBA_DISABLE_JIT=1): nothing to compile; navkit's "
              "kernels run as Python.", file=out)  # fmt: skip
        return 0
    with warnings.catch_warnings():  # said once, below, as the command's error
        warnings.simplefilter("ignore", KernelCacheWarning)
        problem = cache_problem()
    if problem is not None:
        raise OSError(f"{problem}; nothing was compiled")
    progress = _StepProgress(err, enabled=not args.quiet)
    report = warmup(workers=args.workers, progress=progress, only=args.only)
    print(report_table(report).render(digits=3), file=out)
    if report.compiled:
        print(f"{counted(len(report.compiled), 'kernel')} compiled and cached: later runs "
              "load them.",
              file=out)  # fmt: skip
    else:
        print("Every kernel was already cached: nothing to compile.", file=out)
    return 0
