"""Progress of a sweep on standard error: a tqdm bar, on terminals only."""

from __future__ import annotations

import os
import shutil
from types import TracebackType
from typing import Any, TextIO

__all__ = ["DELAY", "ProgressBar"]

#: Seconds a run must last before its bar appears (shorter runs print nothing).
DELAY = 2.0


def _size(stream: TextIO) -> dict[str, Any]:
    """tqdm's size options for a terminal ``stream``: its width as it changes, or a fixed one.

    A terminal reporting no size (0 x 0: ``script``, ``docker run -t`` without
    a terminal on the client's side) made tqdm draw nothing at all (it took
    the bar's line for one below the screen's last row); the bar then gets
    ``$COLUMNS``/``$LINES`` or 80 x 24.
    """
    try:
        columns, lines = os.get_terminal_size(stream.fileno())
    except (AttributeError, OSError, ValueError):  # no descriptor: tqdm finds none either
        return {"dynamic_ncols": True}
    if columns > 0 and lines > 0:
        return {"dynamic_ncols": True}
    fallback = shutil.get_terminal_size((80, 24))
    return {"ncols": columns or fallback.columns or 80, "nrows": lines or fallback.lines or 24}


class ProgressBar:
    """``progress(done, total)`` for :func:`navkit.sim.sweep`, drawn with tqdm.

    The bar (trials done / total, rate, ETA) is drawn on ``stream`` only when
    that stream is a terminal and ``enabled``, and only once the run has lasted
    :data:`DELAY` seconds; otherwise calls do nothing. Use it as a context
    manager so the bar is closed (and its line kept) at the end.

    Parameters
    ----------
    stream : text stream
        Standard error.
    enabled : bool
        False for ``--quiet``.
    description : str
        Shown left of the bar.

    Examples
    --------
    >>> import io
    >>> with ProgressBar(io.StringIO(), enabled=True, description="demo") as bar:
    ...     bar(1, 2)
    ...     bar(2, 2)
    >>> bar.shown
    False
    """

    __slots__ = ("_bar", "_description", "_enabled", "_stream")

    def __init__(self, stream: TextIO, *, enabled: bool, description: str) -> None:
        isatty = getattr(stream, "isatty", None)
        self._enabled = bool(enabled and isatty is not None and isatty())
        self._stream = stream
        self._description = description
        self._bar: Any = None

    @property
    def shown(self) -> bool:
        """Whether a bar is being drawn (a terminal, not quiet)."""
        return self._bar is not None

    def __call__(self, done: int, total: int) -> None:
        if not self._enabled:
            return
        if self._bar is None:
            try:
                from tqdm import tqdm
            except ImportError:  # a dependency missing: a bar is not worth failing the run
                self._enabled = False
                return

            # No monitor thread: sweeps may fork worker processes while the bar is up.
            tqdm.monitor_interval = 0
            self._bar = tqdm(
                total=total, desc=self._description, unit="trial", file=self._stream,
                delay=DELAY, leave=True, **_size(self._stream),
            )  # fmt: skip
        self._bar.update(done - self._bar.n)

    def start(self, total: int) -> None:
        """Start the clock before the first trial ends (the bar's rate and ETA)."""
        self(0, total)

    def __enter__(self) -> ProgressBar:
        return self

    def __exit__(
        self,
        kind: type[BaseException] | None,
        error: BaseException | None,
        traceback: TracebackType | None,
    ) -> None:
        if self._bar is not None:
            self._bar.close()
            self._bar = None
