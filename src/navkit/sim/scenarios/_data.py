"""Where the real data sets are: ``data_dir=``, ``$NAVKIT_DATA``, or ``shared/data`` nearby."""

from __future__ import annotations

import os
from pathlib import Path

from navkit.errors import DataNotFoundError

__all__ = ["find_data"]

#: Environment variable naming the data folder (the one holding ``ros-map-server-maps``, ...).
ENV_VAR = "NAVKIT_DATA"


def _named_folder(folder: Path, named_by: str, hint: str = "") -> Path:
    """``folder``, refused unless it is an existing folder.

    A folder the user named (``data_dir=``, ``$NAVKIT_DATA``) that does not
    exist is a mistake to report, not a reason to look elsewhere: falling back
    to another ``shared/data`` would run on data the user did not choose. So it
    is a ``ValueError``, not the ``DataNotFoundError`` of a data set missing
    from a real folder, which the experiments' "auto" modes answer with their
    synthetic maps.
    """
    if not folder.is_dir():
        state = "is not a folder" if folder.exists() else "does not exist"
        where = str(folder) if folder.is_absolute() else f"{folder} ({folder.absolute()})"
        raise ValueError(
            f"{named_by} names the data folder {where}, which {state}; it must be the "
            f"folder holding ros-map-server-maps, carmen-logs, ...{hint}"
        )
    return folder


def _candidates(data_dir: str | os.PathLike[str] | None) -> list[Path]:
    if data_dir is not None:
        return [_named_folder(Path(data_dir), "data_dir")]
    found: list[Path] = []
    env = os.environ.get(ENV_VAR)
    if env:  # set but empty counts as unset, as for most variables
        found.append(
            # expanduser: a "~" that no shell expanded (quoted, or set from PowerShell)
            _named_folder(
                Path(env).expanduser(),
                f"${ENV_VAR}",
                " (or unset it to look in shared/data nearby)",
            )
        )
    here = Path.cwd().resolve()
    bases = [here, *list(here.parents)[:3]]
    # A checkout (src layout) keeps the data beside its root: <root>/../shared/data.
    # An installed navkit (<venv>/lib/python3.X/site-packages/navkit) has no such
    # root, and "<venv>/lib/shared/data" in the error would send users astray.
    source = Path(__file__).resolve().parents
    if len(source) > 5 and source[3].name == "src" and (source[4] / "pyproject.toml").is_file():
        bases.append(source[5])
    found.extend(base / "shared" / "data" for base in bases)
    return found


def find_data(relative: str, *, data_dir: str | os.PathLike[str] | None = None) -> Path:
    """The path of a file or folder of the real data sets.

    Parameters
    ----------
    relative : str
        Path inside the data folder, e.g.
        ``"ros-map-server-maps/turtlebot3_world/map.yaml"``.
    data_dir : str or path-like, optional
        The data folder; the only place looked in. Default: ``$NAVKIT_DATA``
        when it is set (and not empty), then the first ``shared/data`` found
        in the working directory, its parents (up to three levels) or beside
        the navkit checkout.

    Returns
    -------
    Path
        An existing path.

    Raises
    ------
    DataNotFoundError
        When no candidate folder holds ``relative``.
    TypeError, ValueError
        A ``relative`` that is not a non-empty str; a ``data_dir`` that is not
        a path, or an empty one; ``data_dir``, or else ``$NAVKIT_DATA``,
        naming a folder that does not exist (or a file): a misspelt folder is
        reported, not replaced by another ``shared/data`` (nor, in the
        experiments' "auto" modes, by their synthetic maps).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as empty:
    ...     try:
    ...         find_data("no-such-set/x.yaml", data_dir=empty)
    ...     except DataNotFoundError:
    ...         print("not found")
    not found
    """
    if not isinstance(relative, str) or not relative:
        raise TypeError(f"relative must be a non-empty str, got {relative!r}")
    if data_dir is not None and not isinstance(data_dir, (str, os.PathLike)):
        raise TypeError(f"data_dir must be a path, got {type(data_dir).__name__}")
    if data_dir is not None and os.fspath(data_dir) == "":
        # Path("") is the working directory: not a data folder anyone means.
        raise ValueError("data_dir must not be empty (None looks in the default places)")
    looked = _candidates(data_dir)
    for base in looked:
        path = base / relative
        if path.exists():
            return path
    where = ", ".join(str(p) for p in dict.fromkeys(looked))
    # Told to "pass data_dir=" after passing it, a user was left guessing; the usual
    # slip is a folder one level off (a data set's own folder, or its parent).
    advice = (
        f"set {ENV_VAR} or pass data_dir= (--data on the command line): the folder holding"
        if data_dir is None
        else f"data_dir= (--data on the command line) is the only folder looked in (not "
        f"{ENV_VAR}, not shared/data nearby): it must be the one that itself holds"
    )
    raise DataNotFoundError(
        f"{relative} not found in {where}; {advice} ros-map-server-maps, carmen-logs, ... "
        "(where to download them: the 'Data sets' page of navkit's documentation, docs/data.md)"
    )
