"""The ASCII error handler writes every undecodable file-name byte back (review 42, MUTANT13).

A mutation review of ``navkit.cli._encoding`` found each bound of the
``surrogateescape`` range (U+DC80..U+DCFF, the bytes 0x80..0xFF) movable by one
without a failing test: the only test wrote one byte back (``ü`` in UTF-8, 0xC3
0xBC), inside both bounds. Here every byte of the range, and the surrogates just
outside it (no byte of a file name: a stand-in, not an error), are written.
"""

from __future__ import annotations

import pytest

from navkit.cli._encoding import ERRORS


def test_every_byte_surrogateescape_could_not_decode_is_written_back() -> None:
    for byte in range(0x80, 0x100):
        text = f"karte_{bytes([byte]).decode('ascii', 'surrogateescape')}.yaml"
        assert text.encode("ascii", ERRORS) == b"karte_" + bytes([byte]) + b".yaml"
    every = bytes(range(0x80, 0x100))
    assert every.decode("utf-8", "surrogateescape").encode("ascii", ERRORS) == every


@pytest.mark.parametrize("code", [0xDC7F, 0xDD00, 0xDBFF, 0xDFFF])
def test_a_surrogate_outside_the_escaped_bytes_gets_a_stand_in(code: int) -> None:
    assert f"a{chr(code)}b".encode("ascii", ERRORS) == b"a?b"
