"""What a file reader makes of given bytes: its content, or a refusal naming the file.

Review 46's CARMEN and MovingAI reader tests cut, damage and vary files and ask
each reader whether it reads them or refuses them with a ``ValueError`` that
names the path (never another error); each wrote this again (review 47).
"""

from __future__ import annotations

from collections.abc import Callable
from pathlib import Path
from typing import Any


def outcome(
    read: Callable[[Path], Any], content: Callable[[Any], Any], path: Path, data: bytes
) -> Any:
    """``content`` of what ``read`` gives of ``data`` written at ``path``.

    None when ``read`` refuses it with a ValueError, which must name the path.
    """
    path.write_bytes(data)
    try:
        return content(read(path))
    except ValueError as exc:
        assert str(path) in str(exc), exc
        return None
