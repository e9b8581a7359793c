"""The command's output on terminals that cannot show every character (``LC_ALL=C``).

navkit's tables and notes use a few non-ASCII characters (``×``, ``±``, ``°``,
``≈``, ``σ``, ...). Under a locale whose encoding lacks them (the C locale
without Python's UTF-8 mode, ``PYTHONIOENCODING=ascii``) writing them raised
``UnicodeEncodeError`` and ended the command. :func:`tolerant_output` makes
standard output and error write an ASCII stand-in for each such character
instead (``x``, ``+/-``, ``deg``, ``~``, ``sigma``, else ``?``), and writes
bytes of a file name that Python could not decode (``surrogateescape``, as
in ``karte_ü`` under the C locale) back as they were. A stream whose errors
are ``"strict"`` gets the same handler whatever its encoding: a UTF-8 one
(``PYTHONIOENCODING=utf-8``) has every character but not those bytes.
"""

from __future__ import annotations

import codecs
import contextlib
import sys
import unicodedata
from collections.abc import Iterator

__all__ = ["ERRORS", "tolerant_output"]

#: The name of the error handler :func:`tolerant_output` installs.
ERRORS = "navkit.ascii"

# What the command prints: tables, notes, errors, the library's messages.
_STAND_INS = {
    "×": "x", "±": "+/-", "°": " deg", "→": "->", "←": "<-", "–": "-", "—": "--",
    "−": "-", "≈": "~", "·": "*", "≤": "<=", "≥": ">=", "½": "1/2", "µ": "u", "μ": "u",
    "π": "pi", "σ": "sigma", "θ": "theta", "ω": "omega", "α": "alpha", "β": "beta",
    "δ": "delta", "Δ": "Delta", "ρ": "rho", "κ": "kappa", "ξ": "xi", "Σ": "Sigma",
    "‖": "||", "…": "...", "ᵀ": "^T", "⁻": "^-", "²": "^2", "³": "^3", "√": "sqrt",
    "∞": "inf", "∇": "grad", "∂": "d", "‘": "'", "’": "'", "“": '"', "”": '"',
}  # fmt: skip

#: Characters that show whether a stream needs the stand-ins.
_PROBE = "×±°→≈σ"


def _stand_in(exc: UnicodeError) -> tuple[str | bytes, int]:
    """Codec error handler: one unencodable character as ASCII (or its original byte)."""
    if not isinstance(exc, UnicodeEncodeError):
        raise exc
    char = exc.object[exc.start]
    code = ord(char)
    if 0xDC80 <= code <= 0xDCFF:  # a byte that surrogateescape decoding could not map
        return bytes([code - 0xDC00]), exc.start + 1
    text = _STAND_INS.get(char)
    if text is None:
        # Accents dropped (ü -> u), compatibility forms spelled out (ⁱ -> i).
        decomposed = unicodedata.normalize("NFKD", char)
        text = decomposed.encode("ascii", "ignore").decode("ascii") or "?"
    return text, exc.start + 1


codecs.register_error(ERRORS, _stand_in)


def _needs_stand_ins(stream: object) -> bool:
    encoding = getattr(stream, "encoding", None)
    if not isinstance(encoding, str) or not hasattr(stream, "reconfigure"):
        return False
    if getattr(stream, "errors", None) == "strict":
        # Even UTF-8 cannot encode a file name's undecodable bytes (U+DC80..U+DCFF):
        # a strict UTF-8 output (PYTHONIOENCODING=utf-8, a UTF-8 locale other than
        # C.UTF-8) ended `navkit plan` after its files were written.
        return True
    try:
        _PROBE.encode(encoding)
    except UnicodeEncodeError:
        return True
    except LookupError:  # pragma: no cover - an encoding Python does not know
        return False
    return False


@contextlib.contextmanager
def tolerant_output() -> Iterator[None]:
    """Within the block, ``sys.stdout`` and ``sys.stderr`` write stand-ins for what their
    encoding lacks; their error handlers are restored afterwards.

    A stream is changed only when it has ``reconfigure`` (a
    :class:`~io.TextIOWrapper`) and an encoding, and either lacks one of
    ``×±°→≈σ`` or is strict; one that cannot be reconfigured (closed, its
    flush failing) is left as it is.

    Examples
    --------
    >>> "14.4 × 12 m, ±2 m, ü".encode("ascii", ERRORS)
    b'14.4 x 12 m, +/-2 m, u'
    """
    changed: list[tuple[object, str]] = []
    for stream in (sys.stdout, sys.stderr):
        if _needs_stand_ins(stream):
            with contextlib.suppress(OSError, ValueError):
                errors = str(getattr(stream, "errors", "strict"))
                stream.reconfigure(errors=ERRORS)  # type: ignore[union-attr]
                changed.append((stream, errors))
    try:
        yield
    finally:
        for stream, errors in changed:
            with contextlib.suppress(OSError, ValueError):
                stream.reconfigure(errors=errors)  # type: ignore[attr-defined]
