"""A MovingAI map whose rows are followed by many blanks reads as its rows (review 46, HYPO7).

``read_movingai_map`` ignores spaces or tabs after a row, as HOG2's
``fscanf`` does, but read the rows in one block of ``height * (width + 2) +
4096`` bytes: blanks beyond that (100 rows of 10 padded to 60, a map padded
to a fixed width) pushed the last rows out of the block, and a valid file
was refused as having "more than the 100 rows of the header's height". The
rows past the block are now read on in chunks, each line kept without its
blanks. Property: blanks appended to rows change nothing, valid file or
damaged: the same terrain, or the same message, with any line end and with
chunk boundaries anywhere (the chunk made small).
"""

from __future__ import annotations

import tempfile
from pathlib import Path
from typing import Any

import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import navkit.mapping.io._movingai as movingai
from navkit.mapping.io import read_movingai_map
from navkit.mapping.io._movingai import TERRAIN

_HEADER = b"type octile\nheight %d\nwidth %d\nmap\n"


def _outcome(data: bytes, chunk: int | None = None) -> tuple[str, Any]:
    with tempfile.TemporaryDirectory() as name, pytest.MonkeyPatch.context() as mp:
        if chunk is not None:
            mp.setattr(movingai, "_CHUNK", chunk)
        path = Path(name, "m.map")
        path.write_bytes(data)
        try:
            return "read", read_movingai_map(path).terrain.tobytes()
        except ValueError as exc:
            return "refused", str(exc).replace(str(path), "FILE")


@pytest.mark.parametrize("end", [b"\n", b"\r\n", b"\r"])
@pytest.mark.parametrize("pad", [50, 5000, 3 << 20])
def test_rows_padded_with_blanks_read_as_the_rows(end: bytes, pad: int) -> None:
    rows = [(b".@TG" * 3)[:10] for _ in range(100)]
    plain = (_HEADER % (100, 10) + b"\n".join(rows) + b"\n").replace(b"\n", end)
    padded = _HEADER % (100, 10) + b"\n".join(r + b" " * pad for r in rows[:3]) + b"\n"
    padded += b"\n".join(r + b" \t" * 25 for r in rows[3:]) + b"\n"
    kind, terrain = _outcome(padded.replace(b"\n", end))
    assert kind == "read", terrain
    assert (kind, terrain) == _outcome(plain)


@pytest.mark.parametrize("chunk", [1, 2, 3, 4, 5, 1 << 20])
def test_blanks_inside_rows_past_the_first_read_are_kept_across_chunks(chunk: int) -> None:
    head = _HEADER % (4, 6) + b"." * 6 + b" " * 6000 + b"\n"
    for rows in (
        [b"..\t ..", b"......", b"......"],  # six characters, a tab among them
        [b"..  \t ..", b"......", b"......"],  # eight characters
        [b"......", b".  ", b"......"],  # blanks after a short row: three characters
        [b"......", b"...   " + b"\t" * 30 + b".", b"......"],  # 37 characters
    ):
        data = head + b"\n".join(rows) + b"\n"
        plain = _HEADER % (4, 6) + b"." * 6 + b"\n" + b"\n".join(rows) + b"\n"
        assert _outcome(data, chunk) == _outcome(plain), rows


def test_messages_past_the_first_read_name_the_row_and_its_length() -> None:
    head = _HEADER % (3, 10) + b"." * 10 + b" " * 6000 + b"\n"
    assert _outcome(head + b"." * 10 + b"\t" * 9000 + b"@\n" + b"." * 10 + b"\n") == (
        "refused",
        "FILE:6: a row of 9011 characters, the header's width is 10",
    )
    assert _outcome(head + b"." * 9 + b"\n" + b"." * 10 + b"\n") == (
        "refused",
        "FILE:6: a row of 9 characters, the header's width is 10",
    )
    assert _outcome(head + b"." * 10 + b"\n") == (
        "refused",
        "FILE: 2 rows after the 'map' line, the header's height is 3",
    )
    assert _outcome(head + (b"." * 10 + b"\n") * 3) == (
        "refused",
        "FILE: more than the 3 rows of the header's height after the 'map' line",
    )
    assert _outcome(head + b"....\t.....\n" + b"." * 10 + b"\n\n \n") == (
        "refused",
        "FILE:6: byte 0x09 at column 4 is not a MovingAI terrain character (one of '.G@OTSW')",
    )


_NOISE = st.sampled_from([*b".@TGx \t", 0x0C])


@st.composite
def _maps(draw: st.DrawFn) -> tuple[list[bytes], int, int]:
    """Rows of a map (some damaged), and the header's height and width."""
    height, width = draw(st.integers(1, 6)), draw(st.integers(1, 6))
    rows = [
        bytes(draw(st.lists(st.sampled_from(TERRAIN.encode()), min_size=width, max_size=width)))
        for _ in range(height)
    ]
    for _ in range(draw(st.integers(0, 2))):
        i = draw(st.integers(0, len(rows) - 1))
        at = draw(st.integers(0, len(rows[i])))
        kind = draw(
            st.sampled_from(["set", "insert", "blanks", "cut", "row out", "row twice", "blank row"])
        )
        if kind == "set" and rows[i]:
            at = min(at, len(rows[i]) - 1)
            rows[i] = rows[i][:at] + bytes([draw(_NOISE)]) + rows[i][at + 1 :]
        elif kind == "insert":
            rows[i] = rows[i][:at] + bytes([draw(_NOISE)]) * draw(st.integers(1, 3)) + rows[i][at:]
        elif kind == "blanks":  # inside the row: split by a chunk's edge, kept as they are
            run = draw(st.sampled_from([b" ", b"\t", b" \t", b"  \t "]))
            rows[i] = rows[i][:at] + run + rows[i][at:]
        elif kind == "cut":
            rows[i] = rows[i][:at]
        elif kind == "row out" and len(rows) > 1:
            del rows[i]
        elif kind == "row twice":
            rows.insert(i, rows[i])
        elif kind == "blank row":
            rows.insert(i, b"")
    return rows, height, width


@settings(max_examples=150, deadline=None)
@given(
    case=_maps(),
    data=st.data(),
    end=st.sampled_from([b"\n", b"\r\n", b"\r"]),
    last_end=st.booleans(),
    chunk=st.sampled_from([1, 1, 2, 3, 5, 7, 64, 1 << 20]),
)
def test_blanks_after_rows_change_nothing(
    case: tuple[list[bytes], int, int],
    data: st.DataObject,
    end: bytes,
    last_end: bool,
    chunk: int,
) -> None:
    rows, height, width = case
    blank = st.sampled_from([b" ", b"\t", b" \t"])
    # Most rows a few blanks, some far more than the first read's 4096 spare bytes.
    pads = [data.draw(blank) * data.draw(st.sampled_from([0, 0, 1, 3, 700, 2100])) for _ in rows]
    tail = data.draw(st.sampled_from([b"", b"\n", b"\n \n\t\n"]))

    def file(padded: list[bytes]) -> bytes:
        text = _HEADER % (height, width) + b"\n".join(padded) + (b"\n" if last_end else b"")
        return (text + (tail if last_end else b"")).replace(b"\n", end)

    want = _outcome(file(rows))
    got = _outcome(file([r + p for r, p in zip(rows, pads, strict=True)]), chunk)
    assert got == want, (rows, [len(p) for p in pads])
