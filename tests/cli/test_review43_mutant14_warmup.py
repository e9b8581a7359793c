"""``navkit warmup``'s progress line and table (review 43, MUTANT14).

A mutation review of ``navkit.cli._warmup`` left these changes without a
failing test: the progress line not ended after its last step (the table
then began on the progress line), and not flushed after each step (nothing
shown until the end, on a buffered terminal); the table's title for two
processes, and its total row's columns swapped (compiled with loaded, wall
with CPU seconds).
"""

from __future__ import annotations

import io

import pytest

from navkit.cli._warmup import _StepProgress, report_table
from navkit.sim import WarmupReport, WarmupStep


class _Terminal(io.StringIO):
    """A terminal that records what it has shown at each flush."""

    def __init__(self) -> None:
        super().__init__()
        self.shown: list[str] = []

    def isatty(self) -> bool:
        return True

    def flush(self) -> None:
        self.shown.append(self.getvalue())


def test_each_step_is_shown_at_once_and_the_last_ends_the_line() -> None:
    terminal = _Terminal()
    progress = _StepProgress(terminal, enabled=True)
    for done in (1, 2, 3):
        progress(done, 3)
    line = "\rnavkit: compiling navkit's kernels: {}/3 steps"
    assert terminal.shown == [
        line.format(1),
        line.format(1) + line.format(2),
        line.format(1) + line.format(2) + line.format(3) + "\n",
    ]


@pytest.mark.parametrize(("workers", "processes"), [(1, "this process"), (2, "2 processes")])
def test_the_tables_total_row_and_title(workers: int, processes: str) -> None:
    # Distinct counts and times: a column swapped with its neighbour shows.
    a, b, c = "navkit.m.a", "navkit.m.b", "navkit.m.c"
    steps = (
        WarmupStep("astar", (a, b), (c,), 1.5, 1.25),
        WarmupStep("geometry", (a,), (), 0.5, 0.125),
    )
    report = WarmupReport(steps, 2.75, workers)
    table = report_table(report)
    assert table.title == f"navkit warmup ({processes})"
    assert table.rows[0] == ("astar", 2, 1, 1.5, 1.25)
    assert table.rows[-1] == ("total", 2, 1, 2.75, 1.375)
