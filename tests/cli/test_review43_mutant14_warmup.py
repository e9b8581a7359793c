"""``navkit warmup``'s progress line and table (review 43, MUTANT14).

A mutation review of ``navkit.cli._warmup`` left these changes without a
failing test: the progress line not ended after its last step (the table
then began on the progress line), and not flushed after each step (nothing
shown until the end, on a buffered terminal); the table's title for two
processes, and its total row's columns swapped (compiled with loaded, wall
with CPU seconds); the workers given to ``sim.warmup``, the closing
sentence for a warm cache, the table's digits.
"""

from __future__ import annotations

import io

import pytest

from navkit.cli import _warmup
from navkit.cli._parser import build_parser
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


@pytest.mark.parametrize("compiled", [True, False])
def test_the_command_passes_its_options_on_and_says_what_it_compiled(
    monkeypatch: pytest.MonkeyPatch, compiled: bool
) -> None:
    # sim.warmup itself is tested in tests/sim; here what the command gives it and prints.
    kernels = ("navkit.m.a", "navkit.m.b")
    step = WarmupStep("geometry", kernels if compiled else (), () if compiled else kernels,
                      1.23456, 1.11111)  # fmt: skip
    report = WarmupReport((step,), 1.23456, 2)
    calls: list[dict[str, object]] = []

    def fake_warmup(**kwargs: object) -> WarmupReport:
        calls.append(kwargs)
        return report

    monkeypatch.setattr(_warmup, "warmup", fake_warmup)
    args = build_parser(["demo"]).parse_args(
        ["warmup", "--workers", "2", "--only", "geometry", "--quiet"]
    )
    out, err = io.StringIO(), io.StringIO()
    assert _warmup.warmup_command(args, out, err) == 0
    assert [(c["workers"], c["only"]) for c in calls] == [(2, ["geometry"])]
    table = report_table(report).render(digits=3)
    assert "1.23 " in table and "1.2346" not in table
    said = ("2 kernels compiled and cached: later runs load them." if compiled
            else "Every kernel was already cached: nothing to compile.")  # fmt: skip
    assert out.getvalue() == f"{table}\n{said}\n" and err.getvalue() == ""
