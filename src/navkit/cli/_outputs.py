"""The files ``--plot``, ``--animate`` and ``--json`` write (checked before a run starts)."""

from __future__ import annotations

import contextlib
import os
import secrets
import tempfile
from collections.abc import Mapping
from pathlib import Path
from typing import Any

from navkit._shared.files import check_folder, link_loop
from navkit._shared.interrupts import interrupts_deferred
from navkit.cli._files import named_write_errors, write_json
from navkit.sim import ScenarioResult, Scene

__all__ = ["check_distinct", "check_output", "save_animation", "save_json", "save_picture"]


def check_output(path: str | None, suffix: str, option: str) -> None:
    """Fail early, before a long run, on an output file that cannot be written.

    Parameters
    ----------
    path : str or None
        The option's value (None: not asked for).
    suffix : str
        The extension it needs (``".png"``, ``".gif"``), or "" for any.
    option : str
        The option's name, for the message.

    Raises
    ------
    ImportError
        A picture (``.png``, ``.gif``) without matplotlib (the ``plot`` extra).
    ValueError
        An empty name, ``"-"`` (standard output), a wrong extension, a folder
        given for a file, a loop of symbolic links, or a picture (a
        ``suffix``) to be written over something that is not a regular file
        (a device, a pipe).
    FileNotFoundError
        The folder does not exist, or is (or lies below) a loop of symbolic
        links: ``"{option}: folder {folder} does not exist"``, the loop named
        after it.
    NotADirectoryError
        A file stands where a folder of the path should be:
        ``"{option}: {file} is a file, not a folder"``.
    OSError
        No file can be created in the folder (read-only, no permission).

    Examples
    --------
    >>> check_output("out.png", ".png", "--plot")
    >>> try:
    ...     check_output("out.jpg", ".png", "--plot")
    ... except ValueError as exc:
    ...     print(exc)
    --plot: the file must end in .png, got out.jpg
    """
    if path is None:
        return
    if not path:
        # Path("") is ".", the current folder: "is a folder" would puzzle.
        raise ValueError(f"{option}: the file name is empty")
    if path == "-":
        # The usual spelling of standard output, which carries the command's tables:
        # not a file named "-" made in the current folder without a word.
        raise ValueError(
            f"{option}: '-' (standard output) is not supported, as the tables go there; "
            "give a file name (./- for a file named '-')"
        )
    if suffix in (".png", ".gif"):
        _check_matplotlib(option)
    target = Path(path)
    if suffix and target.suffix.lower() != suffix:
        raise ValueError(f"{option}: the file must end in {suffix}, got {path}")
    if target.is_dir():
        raise ValueError(f"{option}: {path} is a folder, not a file")
    check_folder(target, option)  # (a looped folder too: the path's loop is the folder's)
    if link_loop(target):
        # exists() and is_dir() say False for it: found only when written, after the run.
        raise ValueError(f"{option}: {path} is a loop of symbolic links")
    if target.exists() and not target.is_file():
        if suffix:  # pictures are written atomically, which would replace the device itself
            raise ValueError(f"{option}: {path} is not a regular file (a device or a pipe?)")
        return  # written into directly (write_json), whatever its folder allows
    folder = target.parent
    # Create a file there and remove it: permissions, read-only file systems and
    # root's exemptions make any cheaper test (os.access) unreliable. A Ctrl-C waits
    # until it is gone: landing in between, it left the probe file in the user's folder.
    # SIGTERM and SIGHUP (Terminated) are not held back: the probe's own prefix finds
    # it, made by mkstemp but its name not yet returned, for removal (review 27).
    prefix = f".navkit-{secrets.token_hex(4)}-"
    with interrupts_deferred():
        try:
            try:
                fd, probe = tempfile.mkstemp(dir=folder, prefix=prefix, suffix=".tmp")
            except OSError as exc:
                reason = exc.strerror or type(exc).__name__
                raise OSError(f"{option}: cannot write in folder {folder} ({reason})") from exc
            os.close(fd)
            os.unlink(probe)
        except BaseException:
            with contextlib.suppress(OSError):  # the error raised is the one to report
                for left in folder.glob(f"{prefix}*.tmp"):
                    left.unlink(missing_ok=True)
            raise


def _check_matplotlib(option: str) -> None:
    """An ImportError naming the ``plot`` extra, before the run rather than at its end.

    (matplotlib imports Pillow, which the GIFs need, itself.)
    """
    try:
        # The top-level package first: a submodule alone is found in sys.modules
        # even when its package is hidden (sys.modules["matplotlib"] = None).
        import matplotlib
        import matplotlib.figure  # noqa: F401
    except ImportError:
        raise ImportError(
            f"{option} needs matplotlib, which is not installed: pip install 'navkit[plot]'"
        ) from None


def check_distinct(paths: Mapping[str, str | None]) -> None:
    """Fail early when two options name the same file (the second would overwrite the first).

    Parameters
    ----------
    paths : mapping of str to (str or None)
        Option name to its value (None: not asked for).

    Raises
    ------
    ValueError
        Two options name the same file.

    Examples
    --------
    >>> try:
    ...     check_distinct({"--plot": "out.png", "--json": "./out.png", "--animate": None})
    ... except ValueError as exc:
    ...     print(exc)
    --json and --plot name the same file ./out.png; give each its own
    """
    seen: dict[Path, str] = {}
    for option, path in paths.items():
        if path is None:
            continue
        # "out.png", "./out.png" and a symlink to it are one file. os.path.realpath, not
        # Path.resolve(), which before Python 3.13 raised RuntimeError ("Symlink loop")
        # for a loop of symbolic links: a traceback.
        key = Path(os.path.realpath(path))
        if key in seen:
            raise ValueError(
                f"{option} and {seen[key]} name the same file {path}; give each its own"
            )
        seen[key] = option


def _plot() -> Any:
    """navkit.plot, or an ImportError naming the ``plot`` extra."""
    try:
        import navkit.plot as plot
    except ImportError as exc:  # pragma: no cover - matplotlib is a test dependency
        raise ImportError(f"plotting needs matplotlib: pip install 'navkit[plot]' ({exc})") from exc
    return plot


def save_picture(scene: Scene, path: str) -> Path:
    """Write a PNG of a scene (map, plans, driven traces, obstacles, markers)."""
    plot = _plot()
    ax = plot.plot_scene(scene)
    with named_write_errors(Path(path)):
        written: Path = plot.save_figure(ax, path)
    return written


def save_animation(scene: Scene, path: str) -> Path:
    """Write a GIF of a scene's runs (robot, scans, plan)."""
    with named_write_errors(Path(path)):
        written: Path = _plot().animate_trace(scene, path)
    return written


def save_json(result: ScenarioResult, path: str) -> Path:
    """Write a result's ``to_dict()`` as JSON, atomically."""
    return write_json(result.to_dict(), path)
