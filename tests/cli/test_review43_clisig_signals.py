"""``handled_signals`` where the mutation review of review 43 found it untested (CLISIG).

Four changes to ``navkit.cli._signals`` left every test passing (MUTANT14):

* a process forked in the block (a pool's worker) ending with exit code 1
  instead of ``128 + signal`` (S1), or raising the command's own
  ``KeyboardInterrupt``/``Terminated`` there, a traceback on standard error,
  instead of ending quietly (S3): the command's own tests meet only the pool's
  workers, which ignore ``SIGINT`` and are killed as the command stops;
* ``SIGHUP`` (a closed terminal) not handled at all (S5): the test that raised
  it skipped wherever the test runner ignores ``SIGHUP`` (``nohup``);
* the handlers put back without holding the signals meanwhile (S8): no test
  sent a signal between two of the restores;
* the main-thread guard dropped (S2): no test ran a command outside the main
  thread, where ``signal.signal`` raises ``ValueError``.
"""

from __future__ import annotations

import os
import signal
import sys
import threading
from collections.abc import Callable
from typing import Any

import pytest

from navkit.cli import main
from navkit.cli._signals import handled_signals
from subprocess_probe import probe_outcome

_POSIX = hasattr(os, "fork") and hasattr(signal, "SIGHUP") and sys.platform != "win32"
_SIGNALS = ("SIGINT", "SIGTERM", "SIGHUP")

# A worker forked in the block waits for work (as a pool's idle worker does) and is
# sent the signal: what it raised, its exit code and what it wrote to standard error.
# The dispositions are set as a shell leaves them, whatever the test runner's own
# (``nohup`` ignores SIGHUP, and handled_signals leaves a handler it did not expect).
_WORKER_PROBE = """
import json, multiprocessing, os, signal, sys, tempfile

signum = signal.Signals[sys.argv[1]]
signal.signal(signal.SIGINT, signal.default_int_handler)
signal.signal(signal.SIGTERM, signal.SIG_DFL)
signal.signal(signal.SIGHUP, signal.SIG_DFL)

from navkit.cli._signals import handled_signals

def wait_for_work(conn):
    try:  # (the signal may land as "ready" is sent)
        conn.send("ready")
        conn.recv()  # work that never comes
    except BaseException as exc:
        conn.send([type(exc).__name__, getattr(exc, "code", None)])
        raise

context = multiprocessing.get_context("fork")
ours, theirs = context.Pipe()
raised = None
with tempfile.TemporaryFile("w+") as err:
    sys.stderr = err  # the worker's traceback, if any, lands here
    with handled_signals():
        worker = context.Process(target=wait_for_work, args=(theirs,))
        worker.start()
        theirs.close()  # the worker's end: its death reads as the end of the pipe
        assert ours.recv() == "ready"
        os.kill(worker.pid, signum)
        try:
            if ours.poll(120):  # a bound against a hang, not a timing
                raised = ours.recv()
        except EOFError:  # died without raising anything
            pass
        worker.join(120)
        if worker.exitcode is None:
            worker.kill()
            worker.join()
    sys.stderr = sys.__stderr__
    err.seek(0)
    said = err.read()
print(json.dumps({"raised": raised, "exitcode": worker.exitcode, "said": said}))
"""


@pytest.mark.skipif(not _POSIX, reason="POSIX signals and os.fork")
@pytest.mark.parametrize("name", _SIGNALS)
def test_a_worker_forked_in_the_block_ends_quietly_with_128_plus_the_signal(name: str) -> None:
    code = 128 + signal.Signals[name]
    out = probe_outcome(_WORKER_PROBE, name)
    assert out == {"raised": ["WorkerStopped", code], "exitcode": code, "said": ""}


def _handlers() -> dict[int, Any]:
    signums = [signal.SIGINT, signal.SIGTERM, *([signal.SIGHUP] if _POSIX else [])]
    return {s: signal.getsignal(s) for s in signums}


def _in_a_thread(call: Callable[[], Any]) -> dict[str, Any]:
    """What ``call`` returned (``"value"``) or raised (``"error"``), run in a new thread."""
    outcome: dict[str, Any] = {}

    def run() -> None:
        try:
            outcome["value"] = call()
        except BaseException as exc:  # a failure to report, whatever it is
            outcome["error"] = exc

    thread = threading.Thread(target=run)
    thread.start()
    thread.join()
    return outcome


def test_a_command_run_outside_the_main_thread_leaves_the_signals_alone(
    capsys: pytest.CaptureFixture[str],
) -> None:
    # An embedding program's worker thread (a GUI, a notebook's background job):
    # signal.signal raises ValueError there, which ended the command.
    before = _handlers()
    assert _in_a_thread(lambda: main(["--version"])) == {"value": 0}
    assert capsys.readouterr().out.startswith("navkit ")
    assert _handlers() == before

    def block() -> dict[int, Any]:
        with handled_signals():
            return _handlers()

    assert _in_a_thread(block) == {"value": before}


@pytest.mark.skipif(
    not hasattr(signal, "pthread_sigmask")
    or threading.current_thread() is not threading.main_thread(),
    reason="needs POSIX signal masks in the main thread",
)
def test_a_ctrl_c_as_the_handlers_are_put_back_meets_the_restored_ones(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Ctrl-C lands as SIGINT's handler is about to be put back: held until every
    # handler is back, it raises KeyboardInterrupt from Python's own handler. Not
    # held, navkit's handler raised it out of the restoring loop, which left
    # navkit's handlers in place for good.
    if signal.getsignal(signal.SIGINT) is not signal.default_int_handler:
        pytest.skip("the test runner handles SIGINT itself")
    before = _handlers()
    real = signal.signal
    sent: list[int] = []

    def put_back(signum: int, handler: Any) -> Any:
        if signum == signal.SIGINT and not sent:
            sent.append(signum)
            signal.raise_signal(signal.SIGINT)
        return real(signum, handler)

    try:
        with pytest.raises(KeyboardInterrupt), handled_signals():
            monkeypatch.setattr(signal, "signal", put_back)  # the restores only
        monkeypatch.undo()
        assert sent == [signal.SIGINT]
        assert _handlers() == before
        assert signal.SIGINT not in signal.pthread_sigmask(signal.SIG_BLOCK, [])
    finally:
        monkeypatch.undo()
        for signum, handler in before.items():  # whatever a failure left
            real(signum, handler)
