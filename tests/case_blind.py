"""A ``str`` subclass equal to any text that differs from it in case alone (review 33).

A user's key or label type, say: it shows whether navkit checks text as the
plain ``str`` it stores or with the subclass's own ``==`` and ``hash``.
"""

from __future__ import annotations


class CaseBlind(str):
    """Text equal to, and hashed as, any text that differs from it in case alone."""

    def __eq__(self, other: object) -> bool:
        return isinstance(other, str) and self.lower() == other.lower()

    def __ne__(self, other: object) -> bool:
        return not self == other

    def __hash__(self) -> int:
        return hash(self.lower())
