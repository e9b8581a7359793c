"""A Ctrl-C while ``--json``/``--plot``'s folder is probed leaves no probe file (review 26).

``check_output`` creates a file in the output folder and removes it, to know
that the run's results can be written there. A ``SIGINT`` arriving as the
probe file had been made (``tempfile.mkstemp`` returning) raised
``KeyboardInterrupt`` before its removal, leaving ``.navkit-*.tmp`` in the
user's folder (found by review 26's warnings-and-resources lens). The interrupt
now waits until the probe is gone, and is then raised.
"""

from __future__ import annotations

import signal
import tempfile
import threading
from pathlib import Path
from typing import Any

import pytest

from navkit.cli import _outputs

pytestmark = pytest.mark.skipif(
    threading.current_thread() is not threading.main_thread(), reason="signals: main thread"
)


def test_a_ctrl_c_as_the_probe_is_made_leaves_no_file(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    real = tempfile.mkstemp

    def mkstemp_then_ctrl_c(*args: Any, **kwargs: Any) -> tuple[int, str]:
        made = real(*args, **kwargs)
        signal.raise_signal(signal.SIGINT)  # Python runs the handler as this returns
        return made

    monkeypatch.setattr(_outputs.tempfile, "mkstemp", mkstemp_then_ctrl_c)
    with pytest.raises(KeyboardInterrupt):
        _outputs.check_output(str(tmp_path / "result.json"), ".json", "--json")
    assert list(tmp_path.iterdir()) == []


def test_the_probe_still_refuses_a_folder_it_cannot_write(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    def refused(*args: Any, **kwargs: Any) -> tuple[int, str]:
        raise PermissionError(13, "Permission denied")

    monkeypatch.setattr(_outputs.tempfile, "mkstemp", refused)
    with pytest.raises(OSError, match=r"--json: cannot write in folder .* \(Permission denied\)"):
        _outputs.check_output(str(tmp_path / "result.json"), ".json", "--json")
    assert signal.getsignal(signal.SIGINT) is signal.default_int_handler
