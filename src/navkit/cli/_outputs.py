"""The files ``--plot``, ``--animate`` and ``--json`` write (checked before a run starts)."""

from __future__ import annotations

from pathlib import Path
from typing import Any

from navkit.cli._files import write_json
from navkit.sim import ScenarioResult, Scene

__all__ = ["check_output", "save_animation", "save_json", "save_picture"]


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
    ValueError
        A wrong extension, or a folder given for a file.
    FileNotFoundError
        The folder does not exist.

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
    target = Path(path)
    if suffix and target.suffix.lower() != suffix:
        raise ValueError(f"{option}: the file must end in {suffix}, got {path}")
    if target.is_dir():
        raise ValueError(f"{option}: {path} is a folder, not a file")
    folder = target.parent
    if not folder.is_dir():
        raise FileNotFoundError(f"{option}: folder {folder} does not exist")


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
    written: Path = plot.save_figure(ax, path)
    return written


def save_animation(scene: Scene, path: str) -> Path:
    """Write a GIF of a scene's runs (robot, scans, plan)."""
    written: Path = _plot().animate_trace(scene, path)
    return written


def save_json(result: ScenarioResult, path: str) -> Path:
    """Write a result's ``to_dict()`` as JSON, atomically."""
    return write_json(result.to_dict(), path)
