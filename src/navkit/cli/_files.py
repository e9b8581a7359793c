"""Writing the command's output files atomically."""

from __future__ import annotations

import json
import os
from pathlib import Path
from typing import Any

from navkit._shared.files import atomic_path

__all__ = ["write_json"]


def write_json(data: Any, path: str | os.PathLike[str]) -> Path:
    """Write ``data`` as JSON to ``path`` atomically.

    The text goes to a temporary file in the same folder, which then replaces
    ``path`` (``os.replace``): readers see the old file or the whole new one,
    and a failure leaves no partial file behind. A ``path`` that exists but is
    not a regular file (``/dev/null``, ``/dev/stdout``, a named pipe) is
    written into directly instead: renaming a file over it would replace the
    device or pipe itself. The text is UTF-8 with LF line ends on every system
    (Windows' text mode would write CRLF): the same result, the same bytes.

    Parameters
    ----------
    data : JSON-ready object
        What to write (``ScenarioResult.to_dict()``).
    path : str or path-like
        The file; its folder must exist.

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    OSError
        The folder does not exist or cannot be written; ``path`` is a folder.
    TypeError, ValueError
        ``data`` is not JSON-serialisable (nothing is written).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = write_json({"a": 1.5}, Path(folder) / "out.json")
    ...     target.read_text()
    '{\\n  "a": 1.5\\n}\\n'
    """
    target = Path(path)
    text = json.dumps(data, indent=2, allow_nan=False) + "\n"
    if target.is_dir():
        raise IsADirectoryError(f"{target} is a folder, not a file")
    if target.exists() and not target.is_file():
        with open(target, "w", encoding="utf-8", newline="\n") as stream:
            stream.write(text)
        return target
    folder = target.parent
    if not folder.is_dir():
        raise FileNotFoundError(f"folder {folder} does not exist")
    with atomic_path(target) as temporary:
        temporary.write_text(text, encoding="utf-8", newline="\n")  # LF on Windows too
    return target
