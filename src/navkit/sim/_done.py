"""The truth value of a controller's or tracker's ``done`` flag, checked."""

from __future__ import annotations

from typing import Any

__all__ = ["done_flag"]


def done_flag(done: Any, name: str) -> bool:
    """``bool(done)``, or a ``TypeError`` naming ``name`` where that would mislead or fail.

    ``name`` is what the message calls the flag ("tracker.done", "the
    controller's done"). A method ``done()`` written without ``@property`` is
    refused: a bound method is true, and the run would end at its first step
    without a word. A value without a truth value (NumPy's "truth value ... is
    ambiguous" for an array of several flags) is refused naming ``name``.
    """
    if callable(done):
        raise TypeError(
            f"{name} must be true or false (a property or an attribute), got a "
            f"{type(done).__name__}: a method done() needs @property"
        )
    try:
        return bool(done)
    except Exception as exc:
        raise TypeError(f"{name} must be true or false, got {type(done).__name__} ({exc})") from exc
