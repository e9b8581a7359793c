"""The first signal decides how the command ends (review 44).

A ``SIGTERM`` as ``--json``'s output probe was made, then a Ctrl-C while the
probe was removed (held back until the removal was done, then delivered),
ended ``navkit`` with ``interrupted`` and 130: the Ctrl-C's exception replaced
the ``Terminated`` being handled, as Python's exceptions do. A command that
dies of a signal reports that one, and programs that clean up on signals (GNU
``sort``, ``csplit``) hold the others back while they clean up and then die of
the first: ``handled_signals`` now raises every later signal as the first.
"""

from __future__ import annotations

import signal
import sys
import tempfile
import threading
from pathlib import Path
from typing import Any

import numpy as np
import pytest
from hypothesis import example, given, settings
from hypothesis import strategies as st

from navkit.cli import main
from navkit.cli._signals import Terminated, handled_signals
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map

pytestmark = [
    pytest.mark.skipif(sys.platform == "win32", reason="SIGHUP, signals raised in the process"),
    pytest.mark.skipif(
        threading.current_thread() is not threading.main_thread(), reason="signals: main thread"
    ),
]


def _handled_by_navkit() -> None:
    """Skip unless ``handled_signals`` takes the three signals (the runner handles none)."""
    defaults = {signal.SIGINT: signal.default_int_handler, signal.SIGTERM: signal.SIG_DFL,
                signal.SIGHUP: signal.SIG_DFL}  # fmt: skip
    if any(signal.getsignal(s) is not d for s, d in defaults.items()):
        pytest.skip("the test runner handles these signals itself")


def _terminated_then_ctrl_c(monkeypatch: pytest.MonkeyPatch) -> list[str]:
    """``SIGTERM`` as the probe is made, Ctrl-C as it is removed; the files removed."""
    real_mkstemp, real_unlink = tempfile.mkstemp, Path.unlink
    removed: list[str] = []

    def mkstemp_then_terminated(*args: Any, **kwargs: Any) -> tuple[int, str]:
        made = real_mkstemp(*args, **kwargs)
        signal.raise_signal(signal.SIGTERM)
        return made

    def unlink_after_ctrl_c(self: Path, missing_ok: bool = False) -> None:
        if self.name.startswith(".navkit-") and not removed:
            removed.append(self.name)
            signal.raise_signal(signal.SIGINT)  # held back until the removal is done
        real_unlink(self, missing_ok=missing_ok)

    monkeypatch.setattr("navkit.cli._outputs.tempfile.mkstemp", mkstemp_then_terminated)
    monkeypatch.setattr(Path, "unlink", unlink_after_ctrl_c)
    return removed


def test_a_ctrl_c_in_the_clean_up_after_sigterm_exits_as_terminated(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, capsys: pytest.CaptureFixture[str]
) -> None:
    _handled_by_navkit()
    occupied = np.zeros((10, 12), dtype=bool)
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), tmp_path / "m.yaml")
    out = tmp_path / "out"
    out.mkdir()
    removed = _terminated_then_ctrl_c(monkeypatch)
    code = main(["plan", str(tmp_path / "m.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15",
                 "--json", str(out / "p.json")])  # fmt: skip
    monkeypatch.undo()
    captured = capsys.readouterr()
    assert len(removed) == 1  # the Ctrl-C came, in the clean-up
    assert (code, captured.err, captured.out) == (143, "navkit: terminated (SIGTERM)\n", "")
    assert list(out.iterdir()) == []
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
    assert signal.getsignal(signal.SIGTERM) is signal.SIG_DFL


_NAMES = ("SIGINT", "SIGTERM", "SIGHUP")


def _raise_in_clean_ups(names: list[str]) -> None:
    """Raise the first signal, each next one in the clean-up (``finally``) of the one before."""
    try:
        signal.raise_signal(signal.Signals[names[0]])
    finally:
        if names[1:]:
            _raise_in_clean_ups(names[1:])


@settings(max_examples=30, deadline=None)
@given(st.lists(st.sampled_from(_NAMES), min_size=1, max_size=4))
@example(["SIGTERM", "SIGINT"])
@example(["SIGINT", "SIGTERM"])
@example(["SIGHUP", "SIGTERM", "SIGINT"])
def test_the_first_signal_decides_whatever_follows(names: list[str]) -> None:
    _handled_by_navkit()
    with pytest.raises(KeyboardInterrupt) as caught, handled_signals():
        _raise_in_clean_ups(names)
    first = signal.Signals[names[0]]
    if first == signal.SIGINT:
        assert type(caught.value) is KeyboardInterrupt
    else:
        assert isinstance(caught.value, Terminated) and caught.value.signum == first
    # Each later signal did raise (a waiting clean-up can be cut short): the chain
    # of exceptions holds one per signal.
    chain, exc = 0, caught.value
    while exc is not None:
        chain, exc = chain + 1, exc.__context__
    assert chain == len(names)


def test_a_new_command_starts_afresh(tmp_path: Path) -> None:
    # The first signal is the first of one handled_signals block, not of the process
    # (main() runs many times in one process: tests, embedders).
    _handled_by_navkit()
    with pytest.raises(Terminated), handled_signals():
        signal.raise_signal(signal.SIGTERM)
    with pytest.raises(KeyboardInterrupt) as caught, handled_signals():
        signal.raise_signal(signal.SIGINT)
    assert type(caught.value) is KeyboardInterrupt
