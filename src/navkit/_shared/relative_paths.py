"""Where a relative path was looked up: for "does not exist" messages."""

from __future__ import annotations

import os
from pathlib import Path

__all__ = ["relative_to_cwd"]


def relative_to_cwd(path: str | os.PathLike[str]) -> str:
    """`` (relative to the working directory ...)`` for a relative ``path``, else ``""``.

    The documentation's examples name ``../shared/data/...`` from the
    repository's root: run from another folder, "does not exist" alone left
    the reader to guess where the path had been looked up.

    Examples
    --------
    >>> relative_to_cwd(Path.cwd() / "map.yaml")
    ''
    >>> relative_to_cwd("map.yaml").startswith(" (relative to the working directory ")
    True
    """
    if Path(path).is_absolute():
        return ""
    try:
        cwd = os.getcwd()
    except OSError:  # the working directory was removed
        return ""
    return f" (relative to the working directory {cwd})"
