"""Writing the command's output files atomically."""

from __future__ import annotations

import contextlib
import json
import os
from collections.abc import Iterator
from pathlib import Path
from typing import Any

from navkit._shared.files import atomic_path, check_folder

__all__ = ["json_text", "named_write_errors", "write_json"]


def write_json(
    data: Any, path: str | os.PathLike[str], *, number_lists_on_one_line: bool = False
) -> Path:
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
    number_lists_on_one_line : bool, default False
        Write each list of numbers (``null`` among them) on one line, ``[x, y]``
        (``navkit plan``'s points), instead of one number a line; the content
        is the same (see :func:`json_text`).

    Returns
    -------
    Path
        The file written.

    Raises
    ------
    FileNotFoundError
        The folder of ``path`` does not exist, or is (or lies below) a loop of
        symbolic links: ``"path: folder {folder} does not exist"``, the loop
        named after it. Nothing is written.
    NotADirectoryError
        A file stands where a folder of ``path`` should be:
        ``"path: {file} is a file, not a folder"``. Nothing is written.
    OSError
        The folder cannot be written; ``path`` is a folder.
    TypeError, ValueError
        ``data`` is not JSON-serialisable (nothing is written).
    ValueError
        ``path`` is a loop of symbolic links (nothing is written).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     target = write_json({"a": 1.5}, Path(folder) / "out.json")
    ...     target.read_text()
    '{\\n  "a": 1.5\\n}\\n'
    """
    target = Path(path)
    text = json_text(data, number_lists_on_one_line=number_lists_on_one_line) + "\n"
    if target.is_dir():
        raise IsADirectoryError(f"{target} is a folder, not a file")
    with named_write_errors(target):
        if target.exists() and not target.is_file():
            with open(target, "w", encoding="utf-8", newline="\n") as stream:
                stream.write(text)
            return target
        check_folder(target, "path")
        with atomic_path(target) as temporary:
            temporary.write_text(text, encoding="utf-8", newline="\n")  # LF on Windows too
    return target


@contextlib.contextmanager
def named_write_errors(target: Path) -> Iterator[None]:
    """Give ``target`` as the file name of an ``OSError`` raised without one.

    The system reports a failed write or flush (a full disk, ``/dev/full``, a
    file-size limit) without a file name: ``navkit: error: No space left on
    device`` alone would leave the user guessing which output failed. An error
    that names its file already (the folder's, the temporary file's) keeps it.

    Parameters
    ----------
    target : Path
        The output file being written.

    Yields
    ------
    None
        Once; the block writes ``target``.

    Examples
    --------
    >>> try:
    ...     with named_write_errors(Path("out.json")):
    ...         raise OSError(28, "No space left on device")
    ... except OSError as exc:
    ...     print(exc)
    [Errno 28] No space left on device: 'out.json'
    """
    try:
        yield
    except OSError as exc:
        if exc.filename is None and exc.strerror:
            exc.filename = os.fspath(target)
        raise


def json_text(data: Any, *, number_lists_on_one_line: bool = False) -> str:
    """``data`` as JSON indented by 2, as ``json.dumps(data, indent=2, allow_nan=False)``.

    With ``number_lists_on_one_line``, a list holding only numbers (and
    ``null``) is written on one line, ``[0.55, 0.55]``: a path of 400 points
    is 400 lines, not 1,600. The data read back is the same either way.

    Raises
    ------
    TypeError, ValueError
        ``data`` is not JSON-serialisable (NaN and infinities included).

    Examples
    --------
    >>> print(json_text({"points": [[0.5, 1], [2, -3.25]]}, number_lists_on_one_line=True))
    {
      "points": [
        [0.5, 1],
        [2, -3.25]
      ]
    }
    """
    text = json.dumps(data, indent=2, allow_nan=False)
    if not number_lists_on_one_line:
        return text
    # Laid out again from the data json.dumps accepted, read back: keys as strings,
    # tuples as lists, floats exact (repr round-trips), as json.dumps wrote them.
    return _laid_out(json.loads(text), 0)


def _laid_out(value: Any, depth: int) -> str:
    """JSON of plain data (json.loads' types), indented by 2, number lists on one line."""
    inner, outer = "  " * (depth + 1), "  " * depth
    if isinstance(value, dict) and value:
        items = (f"{inner}{json.dumps(k)}: {_laid_out(v, depth + 1)}" for k, v in value.items())
        return "{\n" + ",\n".join(items) + f"\n{outer}}}"
    if isinstance(value, list) and value:
        if all(v is None or (isinstance(v, (int, float)) and not isinstance(v, bool))
               for v in value):  # fmt: skip
            return json.dumps(value)
        items = (f"{inner}{_laid_out(v, depth + 1)}" for v in value)
        return "[\n" + ",\n".join(items) + f"\n{outer}]"
    return json.dumps(value)
