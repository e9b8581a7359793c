"""Private text of counted things ("1 cell", "2 cells"), for messages and reports.

One place for the plural, so that no message reads "expanded 1 cells".
"""

from __future__ import annotations

__all__ = ["counted"]


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
