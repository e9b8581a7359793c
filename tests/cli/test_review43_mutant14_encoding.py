"""``tolerant_output``'s choice of streams and its clean-up (review 43, MUTANT14).

A mutation review of ``navkit.cli._encoding`` left these changes without a
failing test: dropping the check for ``reconfigure`` (an ASCII stream without
it, an embedder's own, raised AttributeError), the handler's re-raise of a
decoding error, the restoration of each stream's error handler, the probe's
characters beyond Latin-1, the ``OSError``/``ValueError`` guards, standard
error's own handler. And it found a defect: a strict UTF-8 standard output
(``PYTHONIOENCODING=utf-8``, or any UTF-8 locale but C.UTF-8) was left strict,
so a file name with bytes that are not UTF-8 (``karte_\\xff``) ended ``navkit
plan`` with "'utf-8' codec can't encode character '\\udcff'", exit code 1,
after its files were written.
"""

from __future__ import annotations

import contextlib
import io
import os
import sys
from pathlib import Path

import numpy as np
import pytest

from navkit.cli import main
from navkit.cli._encoding import ERRORS, tolerant_output
from navkit.mapping import OccupancyGrid
from navkit.mapping.io import write_map


def _stream(encoding: str, errors: str = "strict") -> io.TextIOWrapper:
    return io.TextIOWrapper(io.BytesIO(), encoding=encoding, errors=errors, write_through=True)


def _written(stream: io.TextIOWrapper) -> bytes:
    buffer = stream.buffer
    assert isinstance(buffer, io.BytesIO)
    return buffer.getvalue()


class _AsciiWithoutReconfigure:
    """An embedder's stream: an encoding, but no ``reconfigure`` (not a TextIOWrapper)."""

    encoding = "ascii"
    errors = "strict"

    def __init__(self) -> None:
        self.parts: list[str] = []

    def write(self, text: str) -> int:
        self.parts.append(text)
        return len(text)

    def flush(self) -> None:
        pass


def test_a_stream_without_reconfigure_is_left_as_it_is(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    out, err = _AsciiWithoutReconfigure(), _AsciiWithoutReconfigure()
    monkeypatch.setattr(sys, "stdout", out)
    monkeypatch.setattr(sys, "stderr", err)
    with tolerant_output():
        print("14.4 × 12 m")
    assert main(["list"]) == 0
    assert out.parts[0] == "14.4 × 12 m" and "demo" in "".join(out.parts)


def test_a_stream_whose_encoding_is_not_a_name_is_left_as_it_is(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    class NoEncoding(_AsciiWithoutReconfigure):
        encoding = None  # type: ignore[assignment]

        def reconfigure(self, **kwargs: str) -> None:
            raise AssertionError(f"reconfigured with {kwargs}")

    monkeypatch.setattr(sys, "stdout", NoEncoding())
    with tolerant_output():
        pass


def test_decoding_errors_are_not_handled() -> None:
    with pytest.raises(UnicodeDecodeError):
        b"karte_\xff".decode("ascii", ERRORS)


@pytest.mark.parametrize("fails", [False, True])
def test_each_streams_own_handler_is_back_afterwards(
    monkeypatch: pytest.MonkeyPatch, fails: bool
) -> None:
    # C locale's standard output and error: ASCII, surrogateescape and backslashreplace.
    out, err = _stream("ascii", "surrogateescape"), _stream("ascii", "backslashreplace")
    monkeypatch.setattr(sys, "stdout", out)
    monkeypatch.setattr(sys, "stderr", err)
    with pytest.raises(KeyError) if fails else contextlib.nullcontext(), tolerant_output():
        assert (out.errors, err.errors) == (ERRORS, ERRORS)
        print("± 2 m, 45°", file=out)
        print("σ ≈ 0.1", file=err)
        if fails:
            raise KeyError("the block's own error")
    assert (out.errors, err.errors) == ("surrogateescape", "backslashreplace")
    assert _written(out) == b"+/- 2 m, 45 deg\n" and _written(err) == b"sigma ~ 0.1\n"


def test_a_stream_beyond_latin_1_gets_stand_ins_for_what_it_lacks(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    # Latin-1 has "×", "±" and "°", not "→", "≈" or "σ" (not strict: a strict
    # stream gets the handler whatever its encoding).
    out = _stream("latin-1", "surrogateescape")
    monkeypatch.setattr(sys, "stdout", out)
    with tolerant_output():
        print("a → b, 2 × 3, σ ≈ 0.1")
    assert _written(out) == "a -> b, 2 × 3, sigma ~ 0.1\n".encode("latin-1")


def test_a_closed_stream_is_passed_over(monkeypatch: pytest.MonkeyPatch) -> None:
    # reconfigure() raises ValueError on a closed stream; the block still runs.
    closed, out = _stream("ascii"), _stream("ascii")
    closed.close()
    monkeypatch.setattr(sys, "stdout", closed)
    monkeypatch.setattr(sys, "stderr", out)
    ran = False
    with tolerant_output():
        ran = True
        out.close()  # closed within the block: its handler cannot be restored
    assert ran


def test_a_stream_that_cannot_flush_is_passed_over(monkeypatch: pytest.MonkeyPatch) -> None:
    class Full(io.TextIOWrapper):
        def reconfigure(self, **kwargs: object) -> None:
            raise OSError(28, "No space left on device")  # reconfigure flushes first

    out = Full(io.BytesIO(), encoding="ascii")
    monkeypatch.setattr(sys, "stdout", out)
    with tolerant_output():
        pass
    assert out.errors == "strict"


def test_a_handler_that_does_not_fail_is_kept_on_utf_8(monkeypatch: pytest.MonkeyPatch) -> None:
    # UTF-8 has every character; backslashreplace (standard error) writes any name.
    err = _stream("utf-8", "backslashreplace")
    monkeypatch.setattr(sys, "stderr", err)
    with tolerant_output():
        assert err.errors == "backslashreplace"
        print("karte_\udcff", file=err)
    assert _written(err) == b"karte_\\udcff\n"


@pytest.mark.skipif(sys.platform == "win32", reason="POSIX file names are bytes")
def test_a_strict_utf_8_output_writes_a_file_names_bytes_back(
    monkeypatch: pytest.MonkeyPatch, tmp_path: Path
) -> None:
    # `PYTHONIOENCODING=utf-8 navkit plan karte_$'\xff'/m.yaml ...`: exit code 1,
    # "navkit: error: 'utf-8' codec can't encode character '\udcff' ...".
    folder = Path(os.fsdecode(os.fsencode(tmp_path) + b"/karte_\xff"))
    folder.mkdir()
    occupied = np.zeros((10, 12), dtype=bool)
    occupied[:6, 6] = True
    write_map(OccupancyGrid.from_occupancy(occupied, resolution=0.1), folder / "m\xfc.yaml")
    out, err = _stream("utf-8"), _stream("utf-8", "backslashreplace")
    monkeypatch.setattr(sys, "stdout", out)
    monkeypatch.setattr(sys, "stderr", err)
    argv = ["plan", str(folder / "m\xfc.yaml"), "--start", "0.15,0.15", "--goal", "1.05,0.15"]
    code = main([*argv, "--json", str(folder / "p.json"), "--quiet"])
    assert code == 0, _written(err)
    assert b"wrote " + os.fsencode(folder / "p.json") + b"\n" in _written(out)
    assert "m\xfc.yaml".encode() in _written(out)  # the map's name, UTF-8 as given
    assert out.errors == "strict"
