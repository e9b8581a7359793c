"""navkit.cli._signals as on Windows, simulated on Linux (the portability review).

Windows has no ``SIGHUP`` and no ``pthread_sigmask``; its console's Ctrl-Break
is ``SIGBREAK``, whose default ends the process at once (no clean-up of
temporary files, no pool shut down). ``SIGUSR1`` stands in for ``SIGBREAK``.
"""

from __future__ import annotations

import signal
import threading

import pytest

from navkit.cli._signals import Terminated, handled_signals

pytestmark = pytest.mark.skipif(
    not hasattr(signal, "SIGUSR1") or threading.current_thread() is not threading.main_thread(),
    reason="needs SIGUSR1 (the stand-in) in the main thread",
)


@pytest.fixture
def windows_signals(monkeypatch: pytest.MonkeyPatch) -> int:
    monkeypatch.delattr(signal, "SIGHUP", raising=False)
    monkeypatch.delattr(signal, "pthread_sigmask", raising=False)
    monkeypatch.setattr(signal, "SIGBREAK", signal.SIGUSR1, raising=False)
    assert signal.getsignal(signal.SIGUSR1) is signal.SIG_DFL
    return int(signal.SIGUSR1)


def test_ctrl_break_ends_the_command_as_ctrl_c(windows_signals: int) -> None:
    with pytest.raises(Terminated) as ended, handled_signals():
        # Checked before raising it: with the default handler the signal would end pytest.
        assert callable(signal.getsignal(windows_signals))
        signal.raise_signal(windows_signals)
    assert ended.value.signum == windows_signals
    assert ended.value.exit_code == 128 + windows_signals
    assert isinstance(ended.value, KeyboardInterrupt)  # the library's Ctrl-C clean-up runs
    assert signal.getsignal(windows_signals) is signal.SIG_DFL


def test_handlers_come_back_without_signal_masks(windows_signals: int) -> None:
    before = {s: signal.getsignal(s) for s in (signal.SIGINT, signal.SIGTERM, windows_signals)}
    with pytest.raises(KeyboardInterrupt), handled_signals():
        signal.raise_signal(signal.SIGINT)
    assert {s: signal.getsignal(s) for s in before} == before


def test_an_embedding_programs_ctrl_break_handler_is_left_alone(windows_signals: int) -> None:
    seen: list[int] = []

    def own(signum: int, frame: object) -> None:
        seen.append(signum)

    previous = signal.signal(windows_signals, own)
    try:
        with handled_signals():
            assert signal.getsignal(windows_signals) is own
            signal.raise_signal(windows_signals)
        assert seen == [windows_signals]
    finally:
        signal.signal(windows_signals, previous)
