"""A Ctrl-C during the output probe's clean-up still removes the probe (review 43, CLISIG).

``check_output`` removes its probe file by its prefix when making or removing it
fails (a ``SIGTERM`` as ``mkstemp`` returns, an ``OSError`` from ``close``). A
Ctrl-C landing in that clean-up waits until it is done (``interrupts_deferred``
around the whole probe): raised there, it left ``.navkit-*.tmp`` in the user's
folder. Dropping the deferral left every test passing (MUTANT14's mutant O11):
the tests of review 26 and 27 interrupt only the making of the probe, which the
clean-up then removes.
"""

from __future__ import annotations

import errno
import os
import signal
import tempfile
import threading
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import _outputs
from navkit.cli._signals import handled_signals

pytestmark = pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signals: main thread"
)


def _fail_as_the_probe_is_made(monkeypatch: pytest.MonkeyPatch, how: str) -> None:
    """Make the probe's own steps fail ``how``, after the probe file exists."""
    if how == "SIGTERM":
        if signal.getsignal(signal.SIGTERM) is not signal.SIG_DFL:
            pytest.skip("the signal is handled by the test runner")  # handled_signals leaves it
        real_mkstemp = tempfile.mkstemp

        def mkstemp_then_terminated(*args: Any, **kwargs: Any) -> tuple[int, str]:
            made = real_mkstemp(*args, **kwargs)
            signal.raise_signal(signal.SIGTERM)  # Terminated, not held back
            return made

        monkeypatch.setattr("navkit.cli._outputs.tempfile.mkstemp", mkstemp_then_terminated)
    else:
        real_close = os.close
        failed: list[int] = []

        def close_failing(fd: int) -> None:
            real_close(fd)
            if not failed:  # the probe's (os.close is everyone's)
                failed.append(fd)
                raise OSError(errno.EIO, os.strerror(errno.EIO))  # a network file system's

        monkeypatch.setattr("navkit.cli._outputs.os.close", close_failing)


@pytest.mark.parametrize("how", ["SIGTERM", "OSError"])
def test_a_ctrl_c_during_the_probes_clean_up_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, how: str
) -> None:
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("the test runner handles SIGINT itself")
    _fail_as_the_probe_is_made(monkeypatch, how)
    real_unlink = Path.unlink
    removing: list[str] = []

    def unlink_after_ctrl_c(self: Path, missing_ok: bool = False) -> None:
        if self.name.startswith(".navkit-") and not removing:
            removing.append(self.name)
            signal.raise_signal(signal.SIGINT)  # Python runs the handler as this returns
        real_unlink(self, missing_ok=missing_ok)

    monkeypatch.setattr(Path, "unlink", unlink_after_ctrl_c)
    with pytest.raises(KeyboardInterrupt), handled_signals():
        _outputs.check_output(str(tmp_path / "result.json"), ".json", "--json")
    monkeypatch.undo()
    assert len(removing) == 1  # the clean-up ran, and was interrupted
    assert list(tmp_path.iterdir()) == []
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler


def test_the_clean_up_reports_the_failure_it_cleans_up_after(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Without a Ctrl-C, the clean-up removes the probe and the probe's own error is
    # the one raised.
    _fail_as_the_probe_is_made(monkeypatch, "OSError")
    with pytest.raises(OSError, match="Input/output error"):
        _outputs.check_output(str(tmp_path / "result.json"), ".json", "--json")
    assert list(tmp_path.iterdir()) == []
