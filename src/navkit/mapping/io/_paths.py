"""File-path arguments of the readers and writers (private).

Examples
--------
>>> as_path("map.yaml", "path").name
'map.yaml'
>>> as_path(3, "path")
Traceback (most recent call last):
...
TypeError: path must be a str or an os.PathLike, got int
"""

from __future__ import annotations

import os
from pathlib import Path
from typing import Any

__all__ = ["as_path"]


def as_path(value: Any, name: str) -> Path:
    """``value`` (a ``str`` or ``os.PathLike`` of ``str``) as a Path: not empty, no NUL."""
    if not isinstance(value, (str, os.PathLike)):
        raise TypeError(f"{name} must be a str or an os.PathLike, got {type(value).__name__}")
    text = os.fspath(value)
    if not isinstance(text, str):
        raise TypeError(f"{name} must be a str path, got {type(text).__name__}")
    if not text:  # Path("") would be the working directory
        raise ValueError(f"{name} must not be empty")
    if "\x00" in text:
        raise ValueError(f"{name} must not contain a NUL character, got {text!r}")
    return Path(text)
