"""Private text of counted things ("1 cell", "2 cells") and sizes, for messages and reports.

One place for the plural, so that no message reads "expanded 1 cells".
"""

from __future__ import annotations

import math

__all__ = ["bytes_text", "counted"]

_UNITS = ("B", "KiB", "MiB", "GiB", "TiB", "PiB", "EiB", "ZiB", "YiB")


def counted(n: int, noun: str, plural: str | None = None) -> str:
    """``"{n} {noun}"``, the noun in the plural unless ``n`` is 1.

    Parameters
    ----------
    n : int
        The count.
    noun : str
        The noun in the singular (``"cell"``, ``"jump point"``).
    plural : str, optional
        Its plural; by default ``noun + "s"``.

    Examples
    --------
    >>> counted(1, "cell"), counted(0, "cell"), counted(2, "jump point")
    ('1 cell', '0 cells', '2 jump points')
    >>> counted(1, "entry", "entries"), counted(3, "entry", "entries")
    ('1 entry', '3 entries')
    """
    return f"{n} {noun if n == 1 else (plural or noun + 's')}"


def bytes_text(n: float) -> str:
    """A size in bytes as binary units to 3 significant digits, for messages.

    Parameters
    ----------
    n : float
        Bytes, >= 0; infinite for a size beyond counting.

    Returns
    -------
    str
        ``"512 B"``, ``"1.5 KiB"``, ... ``"YiB"``.

    Examples
    --------
    >>> bytes_text(512), bytes_text(1536), bytes_text(4.0 * 2**28)
    ('512 B', '1.5 KiB', '1 GiB')
    >>> bytes_text(float("inf"))
    'more bytes than exist'
    """
    if not math.isfinite(n):
        return "more bytes than exist"
    k = 0
    while n >= 1024.0 and k < len(_UNITS) - 1:
        n /= 1024.0
        k += 1
    return f"{n:.3g} {_UNITS[k]}" if k else f"{n:.0f} B"
