"""A ``SIGTERM`` or ``SIGHUP`` while ``--json``/``--plot``'s folder is probed leaves no file.

Review 26 made a Ctrl-C wait until ``check_output``'s probe file is gone
(``interrupts_deferred``), but the command line turns ``SIGTERM`` and ``SIGHUP``
into :class:`~navkit.cli._signals.Terminated` too (``timeout``, a CI job
cancelled, a closed terminal), and those were not held back: one landing as
``tempfile.mkstemp`` returned still left ``.navkit-*.tmp`` in the user's folder
(review 27, a fresh-eyes review of review 26).
"""

from __future__ import annotations

import signal
import tempfile
import threading
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import _outputs
from navkit.cli._signals import Terminated, handled_signals

_SIGNALS = [signal.SIGTERM, *([signal.SIGHUP] if hasattr(signal, "SIGHUP") else [])]


@pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signals: main thread"
)
@pytest.mark.parametrize("signum", _SIGNALS)
def test_a_termination_as_the_probe_is_made_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, signum: int
) -> None:
    if signal.getsignal(signum) is not signal.SIG_DFL:
        pytest.skip("the signal is handled by the test runner")  # handled_signals leaves it
    real = tempfile.mkstemp

    def mkstemp_then_signal(*args: Any, **kwargs: Any) -> tuple[int, str]:
        made = real(*args, **kwargs)
        signal.raise_signal(signum)  # Python runs the handler as this returns
        return made

    monkeypatch.setattr(_outputs.tempfile, "mkstemp", mkstemp_then_signal)
    with pytest.raises(Terminated), handled_signals():
        _outputs.check_output(str(tmp_path / "result.json"), ".json", "--json")
    assert list(tmp_path.iterdir()) == []
    assert signal.getsignal(signum) is signal.SIG_DFL
