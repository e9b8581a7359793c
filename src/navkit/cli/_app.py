"""The ``navkit`` command: parse, dispatch, and turn expected failures into one line."""

from __future__ import annotations

import argparse
import contextlib
import os
import sys
from collections.abc import Sequence
from typing import TextIO, cast

from navkit.cli._encoding import tolerant_output
from navkit.cli._parser import build_parser, join_negative_points, parse_command_line
from navkit.cli._signals import Terminated, handled_signals
from navkit.errors import KernelCacheWarning, NavkitError

__all__ = ["main"]

#: Failures of the user's input or environment (files, data, maps, missing
#: extras, unreachable plans): reported in one line with exit code 1. Under
#: ``-W error`` a :class:`~navkit.errors.KernelCacheWarning` (no writable cache
#: folder) is raised rather than shown: one line too, not a traceback.
EXPECTED = (NavkitError, OSError, ValueError, ImportError, KernelCacheWarning)


def one_line(exc: BaseException) -> str:
    """An exception's message (and notes) on one line.

    The operating system's own errors (``[Errno 13] Permission denied:
    'map.yaml'``) read as the system's commands write them: file, then reason.

    Examples
    --------
    >>> one_line(ValueError("bad\\n  map"))
    'bad map'
    >>> one_line(PermissionError(13, "Permission denied", "maps/map.yaml"))
    'maps/map.yaml: Permission denied'
    """
    text = " ".join(_os_error_text(exc).split()) or type(exc).__name__
    notes = [" ".join(str(n).split()) for n in getattr(exc, "__notes__", ())]
    return "; ".join([text, *notes])


def _os_error_text(exc: BaseException) -> str:
    """``str(exc)``, or ``"file: reason"`` for an OSError in Python's default form."""
    text = str(exc)
    if not (isinstance(exc, OSError) and exc.strerror and text.startswith("[Errno ")):
        return text  # navkit's own messages (FileNotFoundError("map YAML file ... does not exist"))
    names = [
        os.fsdecode(name)
        for name in (exc.filename, exc.filename2)
        if isinstance(name, (str, bytes, os.PathLike))
    ]
    return f"{' -> '.join(names)}: {exc.strerror}" if names else exc.strerror


def main(argv: Sequence[str] | None = None) -> int:
    """The ``navkit`` command: :func:`navkit.cli.main` once its modules are loaded.

    Parameters
    ----------
    argv : sequence of str, optional
        The arguments after the program name (default ``sys.argv[1:]``).

    Returns
    -------
    int
        The exit code (see :func:`navkit.cli.main`).

    Examples
    --------
    >>> main(["--version"]) == 0  # doctest: +ELLIPSIS
    navkit ...
    True
    """
    if argv is not None and (
        isinstance(argv, (str, bytes)) or not isinstance(argv, Sequence)
        or not all(isinstance(a, str) for a in argv)
    ):  # fmt: skip
        raise TypeError(f"argv must be a sequence of str or None, got {argv!r:.60}")
    # Under a locale without "×" or "±" (LC_ALL=C), ASCII stand-ins rather than a
    # UnicodeEncodeError ending the command.
    with contextlib.ExitStack() as closing, tolerant_output(), handled_signals():
        # A closed standard output or error (`navkit warmup >&-`) is None in Python:
        # the command still runs, its text discarded.
        streams: list[TextIO] = []
        for stream in (sys.stdout, sys.stderr):
            if stream is None:
                stream = closing.enter_context(open(os.devnull, "w", encoding="utf-8"))
            streams.append(stream)
        if sys.stdout is None:  # argparse's --help would go to standard error instead
            closing.enter_context(contextlib.redirect_stdout(streams[0]))
        out = cast(TextIO, _NamedOutput(streams[0], "standard output"))
        return _main(argv, out, streams[1])


class _NamedOutput:
    """A text stream whose write errors name it (``standard output: No space left on device``).

    The system reports a failed write to an open stream without a file name
    (``navkit plan ... > /dev/full``: "No space left on device" alone), which
    would leave the user guessing among the command's files. A closed pipe
    (``BrokenPipeError``) passes unchanged: the command ends quietly with 141.
    """

    def __init__(self, stream: TextIO, name: str) -> None:
        self._stream = stream
        self._name = name

    def _name_in(self, exc: OSError) -> None:
        if exc.filename is None and not isinstance(exc, BrokenPipeError):
            exc.filename = self._name

    def write(self, text: str) -> int:
        try:
            return self._stream.write(text)
        except OSError as exc:
            self._name_in(exc)
            raise

    def flush(self) -> None:
        try:
            self._stream.flush()
        except OSError as exc:
            self._name_in(exc)
            raise

    def __getattr__(self, name: str) -> object:  # fileno, isatty, encoding, ...
        return getattr(self._stream, name)


def _main(argv: Sequence[str] | None, out: TextIO, err: TextIO) -> int:
    try:
        parser = build_parser()
        # An embedding interpreter may leave sys.argv unset: no arguments, then.
        given = getattr(sys, "argv", [])[1:] if argv is None else list(argv)
        args = parse_command_line(parser, join_negative_points(given, parser=parser))
    except SystemExit as exc:  # --help, --version (0) and bad arguments (2)
        return exc.code if isinstance(exc.code, int) else (0 if exc.code is None else 2)
    except KeyboardInterrupt as exc:  # while the parser is made or a name checked (imports)
        return _interrupted(exc, err)
    try:
        code = _dispatch(args, out, err)
        out.flush()  # a closed pipe fails here, not in the interpreter's last flush
        return code
    except BrokenPipeError:
        # The reader went away (a pipe into head): stop quietly as other commands
        # do, and send what is left in the buffer to /dev/null so that the flush
        # at exit does not fail again ("Exception ignored ...", exit code 120).
        with contextlib.suppress(OSError, ValueError, AttributeError):
            # The standard output's descriptor first: a stream without one opens nothing.
            fileno = sys.stdout.fileno()
            devnull = os.open(os.devnull, os.O_WRONLY)
            try:
                os.dup2(devnull, fileno)
            finally:
                # dup2 made its own copy: this one would stay open until the process ends
                # (main() may be called many times in one process, in tests and embedders).
                os.close(devnull)
        return 141  # 128 + SIGPIPE: what a shell reports for a command the pipe ended
    except EXPECTED as exc:
        err.write(f"navkit: error: {one_line(exc)}\n")
        return 1
    except KeyboardInterrupt as exc:
        return _interrupted(exc, err)


def _interrupted(exc: KeyboardInterrupt, err: TextIO) -> int:
    """One line for Ctrl-C (exit code 130) or a termination signal (128 + signal)."""
    if isinstance(exc, Terminated):
        err.write(f"navkit: terminated ({exc.name})\n")
        return exc.exit_code
    err.write("navkit: interrupted\n")
    return 130


def _dispatch(args: argparse.Namespace, out: TextIO, err: TextIO) -> int:
    """Run the command ``args`` names; its exit code.

    Each command's module is imported here, when the command runs: ``navkit
    --help`` needs none of them, ``navkit plan`` no scenario (issue 17).
    """
    if args.command == "list":
        from navkit.cli._scenarios import list_scenarios

        return list_scenarios(out)
    if args.command == "plan":
        from navkit.cli._plan import plan_command

        return plan_command(args, out, err)
    if args.command == "warmup":
        from navkit.cli._warmup import warmup_command

        return warmup_command(args, out, err)
    from navkit.cli._scenarios import run_scenario

    if args.command == "demo":
        return run_scenario(args, out, err, name="demo", workers=1)
    return run_scenario(args, out, err, name=args.scenario, workers=args.workers)
