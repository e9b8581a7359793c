"""ROS map_server map files: the map YAML, PGM images and (with Pillow) other images.

The YAML is read with PyYAML's safe loader (every key map_server knows is
understood; other keys are ignored). Images: PGM (P5, P2) is read and written
with numpy; other formats are read, and scale-mode PNGs written, with Pillow.
Every malformed file raises a
``ValueError`` that names the file and the problem; an image's size is checked
from its header, before anything is decoded, against
``OccupancyGrid.MAX_CELLS`` (``2**28`` pixels) and, for images read with
Pillow, against Pillow's own decompression-bomb limit too
(``2 * PIL.Image.MAX_IMAGE_PIXELS``, 178,956,970 pixels in Pillow 13).
"""

from __future__ import annotations

import codecs
import contextlib
import errno
import functools
import io
import math
import os
import re
import reprlib
import stat
import struct
import unicodedata
import warnings
import zlib
from bisect import bisect_left
from collections.abc import Callable, Iterator
from dataclasses import dataclass
from pathlib import Path, PureWindowsPath
from typing import Any, BinaryIO, NamedTuple, cast

import numpy as np
import yaml
from numpy.typing import NDArray

from navkit._shared.counts import counted
from navkit._shared.files import RENAME_LOCK, atomic_paths
from navkit._shared.frozen import frozen_setattr
from navkit._shared.locks import ForkSafeLock
from navkit._shared.text import as_text
from navkit.geometry import Pose2D
from navkit.mapping import MapMode, OccupancyGrid
from navkit.mapping.io._paths import as_path, open_regular
from navkit.mapping.io._step_tables import (
    LOOK_UP_BLOCK,
    StepLookUp,
    StepTable,
    row_probability,
    step_table,
)

__all__ = [
    "MapMetadata",
    "map_image_path",
    "map_yaml_text",
    "pgm_bytes",
    "pixel_occupancy",
    "png_bytes",
    "read_image",
    "read_map",
    "read_map_yaml",
    "read_pgm",
    "write_map",
]

_MODES = ("trinary", "scale", "raw")
_WRITE_MODES = ("trinary", "scale")
#: The image format of each mode: map_saver's defaults (Nav2's map_io.cpp). Scale
#: maps need the alpha channel of PNG: map_server reads every pixel of a scale map
#: that is not fully opaque as unknown, and every opaque one as a value.
_IMAGE_FORMAT = {"trinary": "pgm", "scale": "png"}
_REQUIRED = ("image", "resolution", "origin", "negate", "occupied_thresh", "free_thresh")
#: The errors ``Path.exists`` reads as "no such file" (a missing file, a path through
#: a non-directory, a symlink loop) and, on Windows, the ``winerror`` codes it reads
#: so too (a drive not ready, an invalid name such as one with ``?``, a name that
#: cannot be resolved), whose ``errno`` is another.
_MISSING_ERRNOS = (errno.ENOENT, errno.ENOTDIR, errno.EBADF, errno.ELOOP)
_MISSING_WINERRORS = (21, 123, 1921)
_KEYS = frozenset((*_REQUIRED, "mode"))
#: A map YAML is a few hundred bytes; anything over 1 MiB is the wrong file.
YAML_MAX_BYTES = 1 << 20
#: A PGM header (magic, comments, width, height, maxval) must fit in 64 KiB.
_PGM_HEADER_MAX = 1 << 16
# Bytes of a P2 raster split into tokens at a time, and the whitespace that
# bytes.split() splits on (ASCII's six).
_P2_BLOCK_BYTES = 1 << 16
# Pixels of a band of image rows read_map converts at a time: its float64
# temporaries (grey, alpha, probabilities and the grid's) about 10 MiB.
_READ_BLOCK_PIXELS = 1 << 18
_WHITESPACE = re.compile(rb"[ \t\n\r\x0b\x0c]")
# File signatures of images, to say so when one is passed as the YAML.
_IMAGE_MAGIC = {
    b"P5": "a PGM image",
    b"P2": "a PGM image",
    b"\x89PNG": "a PNG image",
    b"\xff\xd8\xff": "a JPEG image",
    b"GIF8": "a GIF image",
    b"BM": "a BMP image",
    b"II*\x00": "a TIFF image",
    b"MM\x00*": "a TIFF image",
}
#: An integer as YAML 1.2 (yaml-cpp) and YAML 1.1 (PyYAML) read it alike.
_DECIMAL = re.compile(r"[-+]?(?:0|[1-9][0-9]*)")
#: Suffixes of image files: a YAML path ending in one would write over an image.
_IMAGE_SUFFIXES = frozenset(
    {".pgm", ".pbm", ".ppm", ".pnm", ".png", ".jpg", ".jpeg", ".bmp", ".gif", ".tif", ".tiff"}
    | {".webp"}
)


# PyYAML's pure-Python safe loader, not the libyaml one (CSafeLoader): the C
# loader's composer recurses on the C stack and crashes the interpreter
# (segmentation fault) on deeply nested input such as 100000 "[", where the
# Python one raises RecursionError. Map YAMLs are a few hundred bytes.
class _Loader(yaml.SafeLoader):
    """PyYAML's safe loader refusing duplicates of the keys map_server reads.

    PyYAML keeps a duplicate key's last value, yaml-cpp (map_server's parser)
    its first: a map YAML naming ``image`` twice means different maps to the
    two. Other keys are ignored anyway, so their duplicates are let through.

    Numbers spelled as only YAML 1.1 reads them (sexagesimal ``1:20`` = 80,
    ``1_000``, ``0b101``, octal ``010`` = 8) are kept as their text, which
    :func:`_as_float` reads as yaml-cpp (YAML 1.2) does: ``010`` is 10, the
    others are refused instead of read as another number.
    """

    def construct_yaml_int(self, node: Any) -> Any:
        text = self.construct_scalar(node)
        if isinstance(text, str) and not _DECIMAL.fullmatch(text):
            return text
        return super().construct_yaml_int(node)

    def construct_yaml_float(self, node: Any) -> Any:
        text = self.construct_scalar(node)
        if isinstance(text, str) and ("_" in text or ":" in text):
            return text
        return super().construct_yaml_float(node)

    def construct_mapping(self, node: Any, deep: bool = False) -> Any:
        if isinstance(node, yaml.MappingNode):
            seen: set[Any] = set()
            for key_node, _ in node.value:
                if key_node.tag == "tag:yaml.org,2002:merge":
                    continue  # "<<: *base" then "key: x" overrides on purpose
                key = self.construct_object(key_node, deep=True)
                if isinstance(key, str) and key in _KEYS:
                    if key in seen:
                        raise yaml.constructor.ConstructorError(
                            None, None, f"duplicate key {key!r}", key_node.start_mark
                        )
                    seen.add(key)
        mapping = super().construct_mapping(node, deep=deep)
        if isinstance(node, yaml.MappingNode) and "image" in mapping:
            _image_as_text(self, node, mapping)
        return mapping


def _image_as_text(loader: _Loader, node: yaml.MappingNode, mapping: dict[Any, Any]) -> None:
    """``mapping``'s ``image`` as its scalar's text, whatever YAML 1.1 resolves it to.

    map_server reads the image name with yaml-cpp's ``as<std::string>()``: a
    scalar's text (``image: yes``, ``on``, ``1.50``, ``2001-12-14``, ``15``
    name those files), where PyYAML's YAML 1.1 makes them True, 1.5, a date,
    an int, and they were refused as "image must be a file name" (review 53).
    A null (``image:``, ``~``) stays None, refused: yaml-cpp up to 0.6 refuses
    it too (later ones read the file ``null``). ``node.value`` holds the merged
    keys first (PyYAML flattened it), so its last ``image`` is the mapping's.
    """
    if isinstance(mapping["image"], str):
        return
    for key_node, value_node in reversed(node.value):
        if isinstance(key_node, yaml.ScalarNode) and loader.construct_object(key_node) == "image":
            if isinstance(value_node, yaml.ScalarNode) and value_node.tag != _NULL_TAG:
                mapping["image"] = value_node.value
            return


#: The tag PyYAML resolves a null (``~``, ``null``, an empty value) to.
_NULL_TAG = "tag:yaml.org,2002:null"

_Loader.add_constructor("tag:yaml.org,2002:int", _Loader.construct_yaml_int)
_Loader.add_constructor("tag:yaml.org,2002:float", _Loader.construct_yaml_float)


@frozen_setattr
@dataclass(frozen=True, slots=True)
class MapMetadata:
    """Content of a map_server YAML file (``image`` resolved against the YAML's folder).

    Examples
    --------
    >>> MapMetadata(Path("map.pgm"), 0.05, (0.0, 0.0, 0.0), False, 0.65, 0.196, "trinary").mode
    'trinary'
    """

    image: Path
    resolution: float
    origin: tuple[float, float, float]
    negate: bool
    occupied_thresh: float
    free_thresh: float
    mode: str


def _bounded_repr() -> reprlib.Repr:
    limits = reprlib.Repr()
    limits.maxlevel = 3
    limits.maxlist = limits.maxtuple = limits.maxdict = limits.maxset = 6
    limits.maxstring = limits.maxother = limits.maxlong = 80
    return limits


# YAML aliases make a value of a few hundred bytes a list of 9**10 elements
# ("billion laughs": it shares its parts); repr() would walk all of them.
_REPR = _bounded_repr()


def _short(value: Any) -> str:
    text = _REPR.repr(value)
    return text if len(text) <= 80 else text[:77] + "..."


def _as_float(value: Any, key: str, path: Path) -> float:
    # YAML 1.1 reads "1e-3" (no dot) as a string: numbers in text are accepted too.
    if isinstance(value, bool) or not isinstance(value, (int, float, str)):
        raise ValueError(f"{path}: {key} must be a number, got {_short(value)}")
    if isinstance(value, str) and ("_" in value or not value.isascii()):
        # Python's float() reads "1_0" and non-ASCII digits; yaml-cpp does not.
        raise ValueError(f"{path}: {key} must be a number, got {_short(value)}")
    try:
        out = float(value)
    except (ValueError, OverflowError):
        raise ValueError(f"{path}: {key} must be a finite number, got {_short(value)}") from None
    if not math.isfinite(out):
        raise ValueError(f"{path}: {key} must be finite, got {value!r}")
    return out


#: An integer as C's stream extraction reads it with the base left to the text, as
#: yaml-cpp (map_server's reader) converts a scalar to ``int``: 0x hexadecimal, a
#: leading 0 octal, else decimal; the whole text, an optional sign first.
_C_INTEGER = re.compile(r"([+-]?)(?:0[xX]([0-9a-fA-F]{1,8})|(0[0-7]{0,11})|([1-9][0-9]{0,9}))")


def _c_int(value: Any) -> int | None:
    """``value`` as yaml-cpp reads an ``int`` from it (a C ``int``), or None where it fails."""
    if not isinstance(value, (int, str)):
        return None
    text = str(value)
    sign = text[0] if text.startswith(("+", "-")) else ""
    body = text[len(sign) :]
    # Leading zeros, any number of them, add nothing (C reads 0x000000001 and
    # 0000000000001 as 1): dropped before the match, whose digit counts are those
    # of an int's range (review 54; by hand, not in the pattern, which would then
    # backtrack over them: seconds for a long run of zeros ending in a bad digit).
    if body[:2] in ("0x", "0X"):
        digits = body[2:]
        body = body[:2] + (digits.lstrip("0") or digits[:1])
    elif body.startswith("0"):
        body = "0" + body.lstrip("0")
    found = _C_INTEGER.fullmatch(sign + body)
    if found is None:
        return None
    sign, hexadecimal, octal, decimal = found.groups()
    if hexadecimal is not None:
        number = int(hexadecimal, 16)
    else:
        number = int(octal, 8) if octal is not None else int(decimal)
    number = -number if sign == "-" else number
    return number if -(2**31) <= number < 2**31 else None


def _as_negate(value: Any, path: Path) -> bool:
    if isinstance(value, bool):
        return value
    if isinstance(value, int) and value in (0, 1):
        return bool(value)
    if isinstance(value, str) and value.lower() in ("0", "1", "true", "false"):
        return value.lower() in ("1", "true")
    # Refused rather than read as map_server reads it (an integer spelt as C spells
    # it, any non-zero one negating): 0 and 1 are the values its documentation
    # gives, and "010" (8 to yaml-cpp) is not a reading a user would guess. The
    # message says what map_server made of it, for a map written for it.
    number = _c_int(value)
    hint = ""
    if number is not None:
        hint = (
            f" (map_server reads it as the integer {number}: "
            f"{'negated' if number else 'not negated'}; write {int(number != 0)})"
        )
    raise ValueError(f"{path}: negate must be 0 or 1, got {_short(value)}{hint}")


def _yaml_text(path: Path) -> tuple[str, str | None]:
    """The YAML file's text, refusing images, binary files, huge files and non-files.

    Returns the text and, for bytes that are not UTF-8, the refusal naming the
    first (the text then holds them as ``surrogateescape`` gives them: see
    :func:`_yaml_entries`), else None.
    """
    with open_regular(path, "map YAML file") as fh:
        size = os.fstat(fh.fileno()).st_size
        if size <= YAML_MAX_BYTES:
            data = fh.read(YAML_MAX_BYTES + 1)
            size = len(data)  # the file may have grown since
    if size > YAML_MAX_BYTES:
        raise ValueError(
            f"{path}: {size} bytes is too large for a map YAML (at most {YAML_MAX_BYTES} "
            "bytes); is it the image? Pass the map's YAML file"
        )
    for magic, kind in _IMAGE_MAGIC.items():
        if data.startswith(magic):
            raise ValueError(
                f"{path}: this is {kind}, not a map YAML; pass the map's YAML file "
                "(the one that names the image)"
            )
    # UTF-8 (a byte-order mark, as Windows Notepad wrote, is skipped by the YAML
    # reader); or UTF-16 / UTF-32 with their byte-order mark, as YAML allows and
    # map_server's yaml-cpp reads: Windows PowerShell 5's ">" writes UTF-16.
    encoding = "utf-8"
    if data.startswith((codecs.BOM_UTF32_LE, codecs.BOM_UTF32_BE)):
        encoding = "utf-32"
    elif data.startswith((codecs.BOM_UTF16_LE, codecs.BOM_UTF16_BE)):
        encoding = "utf-16"
    elif b"\x00" in data[:4] and (bits := _unmarked_unicode(data[:64])):
        # No YAML text holds a NUL (the YAML reader would report a "special
        # character #x0000"): ASCII in UTF-16 or UTF-32 without a byte-order mark
        # has one in every code unit (YAML's own detection, spec 1.2 section 5.2).
        raise ValueError(
            f"{path}: not a map YAML: UTF-{bits} text without a byte-order mark; "
            "save it as UTF-8, or with its byte-order mark"
        )
    try:
        return data.decode(encoding), None
    except UnicodeDecodeError as exc:
        what = "UTF-8" if encoding == "utf-8" else encoding.upper()
        refusal = (
            f"{path}: not a map YAML: not {what} text (byte 0x{data[exc.start]:02x} at "
            f"offset {exc.start})"
        )
        if encoding != "utf-8":
            raise ValueError(refusal) from None
        return data.decode(encoding, "surrogateescape"), refusal


#: ``surrogateescape``'s stand-ins for bytes 0x80..0xff that are not UTF-8, and the
#: private-use characters PyYAML reads in their place (it refuses lone surrogates).
_ESCAPED = {0xDC00 + byte: 0xF700 + byte for byte in range(0x80, 0x100)}
_UNESCAPED = {v: k for k, v in _ESCAPED.items()}
_PRIVATE_STAND_INS = re.compile("[\uf780-\uf7ff]")
#: The stand-ins as the bytes they are, in messages.
_SHOWN_BYTES = {0xF700 + byte: f"\\x{byte:02x}" for byte in range(0x80, 0x100)}
_ESCAPED_BYTES = re.compile("[\udc80-\udcff]")


def _printable(text: str) -> str:
    """``text`` with the bytes that were not UTF-8 (surrogate escapes) shown as escapes.

    A message naming a file whose name is not UTF-8 (a Latin-1 image name in the
    YAML, kept as surrogate escapes by :func:`_yaml_entries`) must still print
    and log: ``str(exc).encode("utf-8")`` raised UnicodeEncodeError on them.

    Examples
    --------
    >>> _printable(b"dir\\xfc".decode("utf-8", "surrogateescape"))
    'dir\\\\udcfc'
    """
    return text.encode("utf-8", "backslashreplace").decode("utf-8")


@contextlib.contextmanager
def _printable_errors() -> Iterator[None]:
    """Let the ValueError or OSError raised inside show its message with :func:`_printable`.

    A map YAML in a folder whose name is not UTF-8 (Latin-1 bytes, from
    ``os.listdir`` or ``sys.argv`` on Linux, surrogate escapes in a str) is named
    in most of read_map's messages, which then raised UnicodeEncodeError in a
    strict UTF-8 log handler (review 53, FRESH). The exception keeps its type,
    attributes and traceback; only a message holding surrogate escapes changes.

    Examples
    --------
    >>> with _printable_errors():
    ...     raise ValueError(b"dir\\xfc: bad".decode("utf-8", "surrogateescape"))
    Traceback (most recent call last):
    ...
    ValueError: dir\\udcfc: bad
    """
    try:
        yield
    except (ValueError, OSError) as exc:
        first = exc.args[0] if exc.args else None
        if isinstance(first, str) and _ESCAPED_BYTES.search(first):
            exc.args = (_printable(first), *exc.args[1:])
        raise


def _yaml_entries(path: Path) -> dict[str, Any]:
    """The keys and values of the map YAML ``path``, read as map_server reads its bytes.

    map_server's yaml-cpp takes text that is not UTF-8 byte for byte (it checks
    no encoding), as a YAML hand-edited in a Windows "ANSI" editor is: a
    Latin-1 or Windows-1252 comment (``# Karte Büro``) is skipped, and an image name's bytes
    are the file name looked up. Those bytes are read the same way here; in a
    value map_server parses as a number, list or mode they are refused, naming
    the value's first such byte (the file's first may be in a comment or the
    image name, both read).
    """
    text, refusal = _yaml_text(path)
    if refusal is None:
        return _load_yaml(text, path)
    if _PRIVATE_STAND_INS.search(text):
        raise ValueError(refusal)
    readable = text.translate(_ESCAPED)
    try:
        entries = _load_yaml(readable, path)
    except ValueError as exc:
        # PyYAML reads the stand-ins as any letter: this is an error of the YAML
        # itself, told as for a UTF-8 file (the bytes shown as such). Blaming the
        # bytes named a Latin-1 comment for a list left open lines below (review 51).
        raise ValueError(str(exc).translate(_SHOWN_BYTES)) from None
    for key in _KEYS - {"image"}:
        value = entries.get(key)
        for item in value if isinstance(value, list) else [value]:
            if isinstance(item, str) and _PRIVATE_STAND_INS.search(item):
                raise ValueError(_refused_value_byte(path, text, readable) or refusal)
    image = entries.get("image")
    if isinstance(image, str):
        entries["image"] = image.translate(_UNESCAPED)
    return entries


def _refused_value_byte(path: Path, text: str, readable: str) -> str | None:
    """The refusal naming the first byte that is not UTF-8 in a value read as a number,
    list or mode, at its offset in the file; None where the YAML's nodes cannot tell.

    ``text`` is the file's text with ``surrogateescape``'s stand-ins, ``readable``
    the same with :data:`_ESCAPED`'s (one character for one, so that the nodes'
    character positions hold in both). The file's first such byte may be one
    that is read (in a comment or the image name): naming it sent the user to
    the wrong line (review 51, FRESH).
    """
    try:
        root = yaml.compose(readable, Loader=_Loader)
    except (yaml.YAMLError, RecursionError):  # tabs between tokens, say: read otherwise
        return None
    if not isinstance(root, yaml.MappingNode):
        return None
    first: int | None = None
    for key, value in root.value:
        if not isinstance(key, yaml.ScalarNode) or key.value not in _KEYS - {"image"}:
            continue
        found = _PRIVATE_STAND_INS.search(readable, value.start_mark.index, value.end_mark.index)
        if found is not None and (first is None or found.start() < first):
            first = found.start()
    if first is None:
        return None
    offset = len(text[:first].encode("utf-8", "surrogateescape"))
    byte = ord(readable[first]) - 0xF700
    return f"{path}: not a map YAML: not UTF-8 text (byte 0x{byte:02x} at offset {offset})"


def _unmarked_unicode(head: bytes) -> int:
    """32 or 16 if ``head`` reads as UTF-32 or UTF-16 text without a byte-order mark, else 0."""
    for width in (4, 2):
        units = [head[i : i + width] for i in range(0, len(head) - width + 1, width)]
        for order in ("little", "big"):
            codes = [int.from_bytes(unit, order) for unit in units]
            # A printable ASCII first character (YAML's detection looks no further),
            # then no NUL and, in UTF-32, no code beyond Unicode's.
            first = codes[0] if codes else 0
            if (0x20 <= first < 0x7F or first in (0x09, 0x0A, 0x0D)) and all(
                0 < code <= 0x10FFFF for code in codes
            ):
                return 8 * width
    return 0


#: A quoted YAML scalar on one line: its tabs are its own. A double-quoted one not
#: closed on its line matches to the line's end (``closed`` unset): see _spaced.
_QUOTED = re.compile(r"""("(?:[^"\\\n]|\\.)*+(?:(?P<closed>")|\\?$)|'(?:[^'\n]|'')*')""")
#: A single-quoted scalar on one line.
_SINGLE_QUOTED = re.compile(r"""('(?:[^'\n]|'')*')""")


def _untabbed(text: str, blank: str = " ") -> str:
    """``text`` with tabs outside quoted scalars, after a line's indent, as ``blank``.

    YAML 1.2 and map_server's reader (yaml-cpp) take a tab as a blank between
    tokens (``resolution:<TAB>0.05``, a tab before a comment), as hand-edited
    map YAMLs have; PyYAML refuses it ("found character '\\t' that cannot start
    any token"). A tab in an indent stays: YAML refuses that everywhere (a tab
    leading a line inside a flow collection is no indent:
    :func:`_flow_lines_spaced`). A tab inside a plain scalar (``image:
    my<TAB>map.pgm``) is the value's own: this changes it, which
    :func:`_load_tabbed` detects.
    """
    lines = []
    for line in text.split("\n"):
        body = line.lstrip(" \t")
        lines.append(line[: len(line) - len(body)] + _spaced(body, blank))
    return "\n".join(lines)


#: The blanks that make up a line, or that come before a whole-line comment: the
#: tabs among them are no indent (one attempt a line: linear in the text).
_BLANK_LINE = re.compile(r"^[ \t]+(?=[#\r]|$)", re.MULTILINE)


def _blank_lines_spaced(text: str) -> str:
    """``text`` with the tabs of its blank and comment-only lines as spaces.

    YAML 1.2 reads such a line as a comment line (``l-comment``), whose tabs
    are separation, not indentation, and map_server's yaml-cpp eats them: a
    hand edit's tab-only line between keys is a blank line. PyYAML refuses it
    ("found character '\\t' that cannot start any token"), as it refuses a tab
    indenting a key, which YAML and yaml-cpp refuse too and which stays
    refused (:func:`_untabbed` keeps a line's indent).
    """
    return _BLANK_LINE.sub(lambda blanks: blanks.group().replace("\t", " "), text)


#: A line's leading blanks holding a tab (one attempt a line: linear in the text).
_TABBED_LEAD = re.compile(r"^ *\t[ \t]*", re.MULTILINE)
_FLOW_OPEN = (yaml.FlowSequenceStartToken, yaml.FlowMappingStartToken)
_FLOW_CLOSE = (yaml.FlowSequenceEndToken, yaml.FlowMappingEndToken)


def _flow_lines_spaced(text: str) -> str:
    """``text`` with the tabs leading a line that starts inside a flow collection as spaces.

    Inside ``[...]`` or ``{...}`` a line's leading blanks are separation, not
    indentation: YAML 1.2 takes tabs among them (after the one space of
    indent a top-level key's value needs), ruamel.yaml and map_server's
    yaml-cpp (which eats tabs wherever it skips blanks) read ``origin: [0.0,``
    continued on a line ``<TAB>0.0, 0.0]``; PyYAML refused it ("found
    character '\\t' that cannot start any token"). Where such a line starts is
    found from the flow collections' brackets among the tokens of the text
    with every line's leading tabs as spaces (the brackets are the same
    tokens either way: indentation moves no bracket of a flow collection,
    and no block scalar lies inside one); a line starting outside every flow
    collection keeps its tabs, an indent that YAML and PyYAML refuse. One for
    one, so that a character keeps its index (:func:`_tab_in_scalar`).
    """
    leads = list(_TABBED_LEAD.finditer(text))
    if not leads:
        return text
    spaced = _TABBED_LEAD.sub(lambda lead: lead.group().replace("\t", " "), text)
    changes: list[int] = []  # the index of each bracket opening (+) or closing (-) one
    try:
        for token in yaml.scan(_untabbed(spaced), Loader=_Loader):
            if isinstance(token, _FLOW_OPEN):
                changes.append(token.start_mark.index + 1)
            elif isinstance(token, _FLOW_CLOSE):
                changes.append(-token.start_mark.index - 1)
    except (yaml.YAMLError, RecursionError):
        return text  # refused as it stands, naming its first tab or problem
    opened = sorted(i for i in changes if i > 0)
    closed = sorted(-i for i in changes if i < 0)
    out = []
    end = 0
    for lead in leads:
        start = lead.start()
        if bisect_left(opened, start + 1) > bisect_left(closed, start + 1):
            out.append(text[end:start])
            out.append(lead.group().replace("\t", " "))
            end = lead.end()
    out.append(text[end:])
    return "".join(out)


def _load_tabbed(text: str, path: Path) -> object:
    """``text``, which PyYAML refused for a tab, loaded with its tabs between tokens as blanks.

    Loaded twice, the tabs as one space and as two: a tab between tokens is a
    blank either way, one inside a value (a plain scalar's, or a block scalar's)
    changes the value. That is refused, naming the key, rather than read as
    another value (``image: my<TAB>map.pgm`` read as ``my map.pgm``, another
    file). Where the second load fails (a tab after a block indicator, whose
    width moves what follows), the first stands unless one of its tabs lies
    inside a scalar of the document (:func:`_tab_in_scalar`).
    """
    text = _flow_lines_spaced(_blank_lines_spaced(text))
    narrow = _untabbed(text)
    doc = yaml.load(narrow, Loader=_Loader)
    try:
        wide = yaml.load(_untabbed(text, "  "), Loader=_Loader)
    except yaml.YAMLError:
        # A tab's width moved a structure, so the loads cannot be compared: the
        # tabs are checked by where they lie instead (unchecked, image: my<TAB>map.pgm
        # elsewhere in such a file was read as "my map.pgm").
        found = _tab_in_scalar(text, narrow)
        if found is None:
            return doc
        raise _TabInValue(
            f"{path}: a tab inside {found}, which PyYAML cannot read: "
            "quote it or replace the tab with a space"
        ) from None
    seen: set[tuple[int, int]] = set()
    if _same_doc(doc, wide, seen):
        return doc
    where = "a key or value"
    if isinstance(doc, dict) and isinstance(wide, dict):
        if list(doc) != list(wide):
            where = "a key"
        else:
            changed = [key for key in doc if not _same_doc(doc[key], wide[key], set())]
            where = f"the value of {_short(changed[0])}"
    raise _TabInValue(
        f"{path}: a tab inside {where}, which PyYAML cannot read: "
        "quote it or replace the tab with a space"
    )


def _tab_in_scalar(text: str, narrow: str) -> str | None:
    """Where a tab of ``text`` lies inside a plain or block scalar of ``narrow``, or None.

    ``narrow`` is ``text`` with its tabs outside quotes and indents as one
    space each, so a character keeps its index. A scalar's span runs from its
    first character to just past its last (a plain scalar's trailing blanks
    are outside it), so a tab between tokens is outside every span. A tab at
    the end of an inner line of a multi-line plain scalar, which folding
    drops, counts as inside too: refused, not guessed. Returns "a key", "the
    value of 'key'" or "a key or value", as :func:`_load_tabbed` words them.
    """
    tabs = [i for i, (a, b) in enumerate(zip(text, narrow, strict=True)) if a != b]
    root = yaml.compose(narrow, Loader=_Loader)

    def holds(node: yaml.Node, seen: set[int]) -> bool:
        # Each node once: aliases share nodes ("billion laughs" stays linear).
        if id(node) in seen:
            return False
        seen.add(id(node))
        if isinstance(node, yaml.ScalarNode):
            if node.style not in (None, "|", ">"):
                return False  # quoted: its tabs were never replaced
            # The first tab at or after the scalar's start: inside it if before its end.
            k = bisect_left(tabs, node.start_mark.index)
            return k < len(tabs) and tabs[k] < node.end_mark.index
        if isinstance(node, yaml.MappingNode):
            return any(holds(k, seen) or holds(v, seen) for k, v in node.value)
        if isinstance(node, yaml.SequenceNode):
            return any(holds(item, seen) for item in node.value)
        return False

    if root is None:
        return None
    if isinstance(root, yaml.MappingNode):
        seen: set[int] = set()
        for key, value in root.value:
            if holds(key, seen):
                return "a key"
            if holds(value, seen):
                name = key.value if isinstance(key, yaml.ScalarNode) else "?"
                return f"the value of {_short(name)}"
        return None
    return "a key or value" if holds(root, set()) else None


def _same_doc(a: object, b: object, seen: set[tuple[int, int]]) -> bool:
    """Whether two loads of a YAML document hold the same values (NaN equal to NaN).

    Each pair of nodes is compared once (``seen``): a document's aliases share
    nodes, and comparing their expansions (as ``==`` or ``repr`` would) takes
    time exponential in the nesting of a "billion laughs" document.
    """
    if type(a) is not type(b):
        return False
    if isinstance(a, (list, dict)) and isinstance(b, (list, dict)):
        pair = (id(a), id(b))
        if pair in seen:
            return True
        seen.add(pair)
        if isinstance(a, dict) and isinstance(b, dict):
            return list(a) == list(b) and all(_same_doc(a[k], b[k], seen) for k in a)
        return len(a) == len(b) and all(_same_doc(u, v, seen) for u, v in zip(a, b, strict=True))
    if isinstance(a, float) and a != a:  # NaN (.nan): equal to NaN only
        return b != b
    return a == b


class _TabInValue(Exception):
    """:func:`_load_tabbed`'s refusal, its message whole (not an "unreadable YAML value")."""


def _spaced(body: str, blank: str = " ") -> str:
    """One line's ``body`` with its tabs outside quoted scalars as ``blank``; linear time.

    A ``"`` not closed on its line is plain text, and so is every later ``"``
    of the line (each is inside the first one's escapes, read the same way
    from there); single-quoted scalars after it still count. Splitting on one
    pattern that tried each such ``"`` anew took time quadratic in the line
    (6.6 s for a 32 KB line of ``\\"``; hours for the 1 MiB a map YAML may have).
    """
    out = []
    end = 0
    for match in _QUOTED.finditer(body):
        out.append(body[end : match.start()].replace("\t", blank))
        token = match.group()
        if token[0] == '"' and match.group("closed") is None:
            parts = _SINGLE_QUOTED.split(body[match.start() + 1 :])
            out.append('"')
            out.extend(p if i % 2 else p.replace("\t", blank) for i, p in enumerate(parts))
            return "".join(out)
        out.append(token)
        end = match.end()
    out.append(body[end:].replace("\t", blank))
    return "".join(out)


def _load_yaml(text: str, path: Path) -> dict[str, Any]:
    try:
        try:
            doc = yaml.load(text, Loader=_Loader)  # _Loader is a safe loader
        except yaml.scanner.ScannerError as exc:
            if "'\\t'" not in (exc.problem or ""):
                raise
            doc = _load_tabbed(text, path)
    except yaml.YAMLError as exc:
        mark = getattr(exc, "context_mark", None) or getattr(exc, "problem_mark", None)
        where = f"{path}:{mark.line + 1}" if mark is not None else str(path)
        problem = getattr(exc, "problem", None) or str(exc)
        raise ValueError(f"{where}: expected 'key: value' lines ({problem})") from None
    except RecursionError:
        raise ValueError(f"{path}: YAML nested too deeply for a map YAML") from None
    except _TabInValue as exc:
        raise ValueError(str(exc)) from None
    except (ValueError, OverflowError, TypeError) as exc:  # e.g. an integer of 10**5 digits
        raise ValueError(f"{path}: unreadable YAML value ({exc})") from None
    if not isinstance(doc, dict):
        raise ValueError(f"{path}: expected 'key: value' lines, got {type(doc).__name__}")
    return {str(key): value for key, value in doc.items()}


def read_map_yaml(path: str | os.PathLike[str]) -> MapMetadata:
    """Parse a map_server YAML file and check every required key.

    Raises
    ------
    FileNotFoundError
        The YAML or the image it names does not exist.
    ValueError
        The YAML is not a small YAML mapping in UTF-8 (or UTF-16 or UTF-32
        with a byte-order mark; an image or a binary file passed by
        mistake, more than 1 MiB; bytes that are not UTF-8, as a Latin-1
        editor saves, are read as map_server reads them, byte for byte:
        skipped in comments, looked up as written in the image name, refused
        in the other keys' values), a required key is missing, a
        value is out of range (``resolution`` outside [1e-6, 1e6] m, origin x
        or y beyond ±1e9 m, thresholds outside [0, 1] or
        ``free_thresh >= occupied_thresh``, unknown ``mode``, ``negate`` other
        than 0, 1, true or false: for ``00``, ``0x1`` or ``2``, which
        map_server reads as C integers, the message says which and what to
        write), or the image is a directory, a device or the YAML itself. The
        message names the file.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "m.pgm").write_bytes(b"P5 1 1 255 \\xff")
    ...     _ = (Path(folder) / "m.yaml").write_text(
    ...         "image: m.pgm\\nresolution: 0.5\\norigin: [1, 2, 0]\\nnegate: 0\\n"
    ...         "occupied_thresh: 0.65\\nfree_thresh: 0.196\\n")
    ...     meta = read_map_yaml(Path(folder) / "m.yaml")
    >>> meta.image.name, meta.origin, meta.mode
    ('m.pgm', (1.0, 2.0, 0.0), 'trinary')
    """
    yaml_path = as_path(path, "path")
    entries = _yaml_entries(yaml_path)
    missing = [key for key in _REQUIRED if key not in entries]
    if missing:
        raise ValueError(f"{yaml_path}: missing required key(s) {', '.join(missing)}")

    image = entries["image"]
    if not isinstance(image, str) or not image or "\x00" in image or not _encodable(image):
        raise ValueError(f"{yaml_path}: image must be a file name, got {_short(image)}")
    image_path = _image_file(yaml_path, image)
    # One stat for both checks: a save in the other mode (another thread or process)
    # may remove the image between two, which read as "not a regular file".
    try:
        image_stat = image_path.stat()
    except OSError as exc:
        gone = exc.errno in _MISSING_ERRNOS
        if not (gone or getattr(exc, "winerror", None) in _MISSING_WINERRORS):
            raise
        raise _missing_image(yaml_path, image, image_path) from None
    if not stat.S_ISREG(image_stat.st_mode):
        kind = "a directory" if stat.S_ISDIR(image_stat.st_mode) else "not a regular file"
        raise ValueError(_printable(f"{yaml_path}: map image {image_path} is {kind}"))
    if os.path.samestat(image_stat, yaml_path.stat()):
        raise ValueError(f"{yaml_path}: the image key names the YAML file itself ({image!r})")

    resolution = _as_float(entries["resolution"], "resolution", yaml_path)
    origin_raw = entries["origin"]
    if not isinstance(origin_raw, list) or len(origin_raw) != 3:
        raise ValueError(
            f"{yaml_path}: origin must be a list [x, y, yaw], got {_short(origin_raw)}"
        )
    ox, oy, oyaw = (_as_float(v, "origin", yaml_path) for v in origin_raw)
    negate = _as_negate(entries["negate"], yaml_path)
    occ = _as_float(entries["occupied_thresh"], "occupied_thresh", yaml_path)
    free = _as_float(entries["free_thresh"], "free_thresh", yaml_path)
    if not (0.0 <= free < occ <= 1.0):
        raise ValueError(
            f"{yaml_path}: need 0 <= free_thresh < occupied_thresh <= 1, got "
            f"free_thresh={free}, occupied_thresh={occ}"
            + ("; they are probabilities, not percent" if max(occ, free) > 1.0 else "")
        )
    mode = entries.get("mode", "trinary")
    if not isinstance(mode, str) or mode.lower() not in _MODES:
        raise ValueError(
            f"{yaml_path}: mode must be one of {', '.join(_MODES)}, got {_short(mode)}"
        )
    try:  # the grid's own checks of resolution and origin, on a one-cell grid
        OccupancyGrid(
            np.zeros((1, 1)),
            resolution=resolution,
            origin=Pose2D(ox, oy, oyaw),
            occupied_thresh=occ,
            free_thresh=free,
        )
    except ValueError as exc:
        raise ValueError(f"{yaml_path}: {exc}") from None
    return MapMetadata(image_path, resolution, (ox, oy, oyaw), negate, occ, free, mode.lower())


def map_image_path(path: str | os.PathLike[str]) -> Path:
    """The image file a map_server map's YAML names, as :func:`read_map` finds it.

    The YAML is read and checked as :func:`read_map` reads it (UTF-16 and
    UTF-32 with a byte-order mark, bytes that are not UTF-8, tabs, ``image:
    017`` kept as the text ``017``, a name written on Windows with
    backslashes), so a program that must not write over a map's files (the
    ``navkit plan`` command's ``--plot`` and ``--json``) asks the reader
    itself, not a YAML parser of its own.

    Parameters
    ----------
    path : str or os.PathLike
        The map's YAML file.

    Returns
    -------
    pathlib.Path
        The image's path: absolute, or relative to the current folder as
        ``path`` is (the YAML's folder joined with a relative name).

    Raises
    ------
    TypeError
        ``path`` is not a str or path-like.
    FileNotFoundError
        The YAML or the image it names does not exist.
    ValueError
        The YAML is not one :func:`read_map` reads (a missing key, a value out
        of range, the image a directory or the YAML itself), naming the file.

    Examples
    --------
    >>> import tempfile
    >>> from navkit.mapping import OccupancyGrid
    >>> grid = OccupancyGrid.from_occupancy(np.eye(2, dtype=bool), resolution=0.1)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     image = write_map(grid, Path(folder) / "map.yaml")
    ...     map_image_path(Path(folder) / "map.yaml") == image
    True
    """
    return read_map_yaml(path).image


def _missing_image(yaml_path: Path, image: str, image_path: Path) -> FileNotFoundError:
    """The error for a map image ``image_path`` (``image`` in the YAML) that does not exist.

    It says what may have been meant, for maps made on other machines: an
    absolute path of the machine that saved the map (map_saver of ROS 1 before
    2013 and hand edits wrote them) with the file of its name beside the YAML;
    a name whose bytes are not UTF-8; a file spelt the same but for case or
    normalisation, found on Windows or macOS but not here.
    """
    hint = ""
    shown = str(image_path)
    # A drive (C:/maps/x.pgm, C:\maps\x.pgm), or a root written with backslashes.
    on_windows = PureWindowsPath(image)
    windows = bool(on_windows.drive) or ("\\" in image and bool(on_windows.anchor))
    if windows or Path(image).is_absolute():
        base = on_windows.name if windows else image_path.name
        hint = "a Windows path" if windows else "an absolute path"
        with contextlib.suppress(OSError, ValueError):
            if base and (yaml_path.parent / base).is_file():
                hint += f", of the machine that saved the map? {base!r} lies beside the YAML"
        hint = f" ({hint}: give the image's path relative to the YAML)"
    elif _ESCAPED_BYTES.search(image):
        # Bytes that are not UTF-8 (_yaml_entries): shown escaped, so that the
        # message can be printed and logged.
        shown = _printable(shown)
        latin = image.encode("utf-8", "surrogateescape").decode("latin-1")
        hint = (
            f" (the name's bytes that are not UTF-8 were looked up as written; read as "
            f"Latin-1 it is {latin!r}: if that is the file, save the YAML as UTF-8)"
        )
    elif (found := _respelled(image_path)) is not None:
        name = image_path.name
        nfc = unicodedata.normalize("NFC", found) == unicodedata.normalize("NFC", name)
        differs = (
            f"{found!a}, its accents composed otherwise (as macOS writes names)"
            if nfc
            else f"{found!r}, which differs in letter case"
        )
        hint = (
            f" (its folder holds {differs}: names are matched exactly here, as by "
            "map_server on Linux, not as on Windows or macOS; rename the file or "
            "correct the YAML)"
        )
    return FileNotFoundError(f"{yaml_path}: map image {shown} does not exist{hint}")


#: The most entries of an image's folder searched for another spelling of its name.
_RESPELLED_SCAN = 1 << 16


def _respelled(image: Path) -> str | None:
    """The name of an entry beside the missing ``image`` spelt as it but for case or normalisation.

    A map made on Windows or macOS, whose file systems match names regardless
    of case (and, on macOS, of NFC/NFD normalisation), may name ``Map.PGM`` for
    ``map.pgm``: found on those systems, not on Linux. Only the first
    :data:`_RESPELLED_SCAN` entries are looked at (the message's hint, not a search).
    """
    try:
        with os.scandir(image.parent) as entries:
            for count, entry in enumerate(entries):
                if count >= _RESPELLED_SCAN:
                    break
                if entry.name != image.name and _same_spelling(entry.name, image.name):
                    return entry.name
    except (OSError, ValueError):
        pass
    return None


def _encodable(name: str) -> bool:
    """Whether ``name`` is a file name the file system can be asked for.

    A YAML escape can make a lone surrogate (``"\\ud800.pgm"``), which no file
    system encoding takes: ``stat`` would raise ``UnicodeEncodeError``.
    """
    try:
        os.fsencode(name)
    except UnicodeEncodeError:
        return False
    return True


def _image_file(yaml_path: Path, image: str) -> Path:
    """The file a map YAML's ``image`` names: absolute, or relative to the YAML's folder.

    A relative name with backslashes written on Windows (``maps\\office.pgm``)
    names, where backslashes are not separators, a file with backslashes in
    its name: when there is none, the name is read as Windows reads it.
    """
    image_path = Path(image)
    if not image_path.is_absolute():
        image_path = yaml_path.parent / image_path
    if "\\" in image and os.sep != "\\":
        windows = PureWindowsPath(image)
        if not windows.anchor and not os.path.lexists(image_path):
            return yaml_path.parent.joinpath(*windows.parts)
    return image_path


def map_yaml_text(meta: MapMetadata, image_name: str) -> str:
    """map_server YAML text for ``meta`` naming the image ``image_name``.

    PyYAML quotes the name when plain YAML would misread it (``#``, ``: ``,
    leading ``[`` or spaces, ...).

    Raises
    ------
    ValueError
        ``image_name`` cannot be stored so that reading the YAML gives it back
        (it is not valid Unicode, or holds a character YAML treats as a line break).

    Examples
    --------
    >>> meta = MapMetadata(Path("x"), 0.05, (1.0, -2.0, 0.0), False, 0.65, 0.196, "trinary")
    >>> print(map_yaml_text(meta, "my map #2.pgm"), end="")
    image: 'my map #2.pgm'
    mode: trinary
    resolution: 0.05
    origin: [1.0, -2.0, 0.0]
    negate: 0
    occupied_thresh: 0.65
    free_thresh: 0.196
    """
    try:
        image_name.encode("utf-8")
    except UnicodeEncodeError:
        raise ValueError(
            f"the image name {image_name!r} is not valid Unicode and cannot be stored in "
            "a map YAML; choose another file name"
        ) from None
    ox, oy, oyaw = meta.origin
    doc = {
        "image": image_name,
        "mode": meta.mode,
        "resolution": float(meta.resolution),
        "origin": [float(ox), float(oy), float(oyaw)],
        "negate": int(meta.negate),
        "occupied_thresh": float(meta.occupied_thresh),
        "free_thresh": float(meta.free_thresh),
    }
    text = yaml.safe_dump(
        doc, sort_keys=False, default_flow_style=None, allow_unicode=True, width=1 << 30
    )
    try:
        back = yaml.load(text, Loader=_Loader)  # _Loader is a safe loader
    except yaml.YAMLError:
        back = None
    if not isinstance(back, dict) or back.get("image") != image_name:
        raise ValueError(
            f"the image name {image_name!r} would not read back from a map YAML; "
            "choose another file name"
        )
    return text


def _check_image_size(width: int, height: int, path: Path) -> None:
    """Refuse images with more pixels than a grid may have, before decoding them."""
    if width * height > OccupancyGrid.MAX_CELLS:
        raise ValueError(
            f"{path}: image of {width} x {height} = {width * height} pixels is larger than "
            f"the largest map navkit reads (OccupancyGrid.MAX_CELLS = 2**28 = "
            f"{OccupancyGrid.MAX_CELLS} pixels)"
        )


def _pgm_header(data: bytes, path: Path) -> tuple[str, int, int, int, int]:
    """Parse magic, width, height, maxval; return them and the raster offset.

    ``data`` holds at least the header (the file's first 64 KiB). The size is
    checked against ``OccupancyGrid.MAX_CELLS`` here, before any pixel is read.
    """
    if data[:2] not in (b"P5", b"P2"):
        raise ValueError(f"{path}: not a PGM image (magic {data[:2]!r}, expected P5 or P2)")
    fields: list[int] = []
    pos = 2
    n = len(data)
    while len(fields) < 3:
        while pos < n and data[pos : pos + 1].isspace():
            pos += 1
        if pos < n and data[pos : pos + 1] == b"#":
            while pos < n and data[pos : pos + 1] not in (b"\n", b"\r"):
                pos += 1
            continue
        start = pos
        while pos < n and not data[pos : pos + 1].isspace() and data[pos : pos + 1] != b"#":
            pos += 1
        token = data[start:pos]
        if not token:
            raise ValueError(f"{path}: PGM header ends before width, height and maxval")
        if not token.isdigit():
            raise ValueError(f"{path}: bad PGM header field {token[:20]!r} (expected an integer)")
        if len(token) > 12:
            raise ValueError(f"{path}: PGM header field {token[:20]!r}... is out of range")
        fields.append(int(token))
    width, height, maxval = fields
    if width <= 0 or height <= 0:
        raise ValueError(f"{path}: PGM size must be positive, got {width} x {height}")
    if not 0 < maxval < 65536:
        raise ValueError(f"{path}: PGM maxval must be in 1..65535, got {maxval}")
    _check_image_size(width, height, path)
    if pos >= n or not data[pos : pos + 1].isspace():
        raise ValueError(f"{path}: PGM header must end with one whitespace byte after maxval")
    return data[:2].decode(), width, height, maxval, pos + 1


def read_pgm(path: str | os.PathLike[str]) -> NDArray[np.float64]:
    """Read a binary (P5) or ASCII (P2) PGM image as grey levels scaled to 0..255.

    Returns a float64 array of shape (height, width) in file order (row 0 is the
    top of the image).

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "a.pgm").write_bytes(b"P2\\n2 1\\n100\\n0 100\\n")
    ...     read_pgm(Path(folder) / "a.pgm")
    array([[  0., 255.]])
    """
    pgm = as_path(path, "path")
    with open_regular(pgm, "PGM image") as fh:
        return _pgm_from(fh, pgm).whole()


def _p2_pixels(raster: bytes, count: int, pgm: Path, maxval: int) -> NDArray[np.int32]:
    """The first ``count`` values of a P2 ``raster``, read a block of text at a time.

    A list of every token and of every int held about 62 bytes a pixel (15.6 GiB
    at 2**28 pixels); a block's are transient, and the values take 4 bytes.
    """
    pixels = np.empty(count, dtype=np.int32)
    filled = start = 0
    while filled < count and start < len(raster):
        end = start + _P2_BLOCK_BYTES
        # Extended to the next whitespace, so that no value is cut in two.
        cut = _WHITESPACE.search(raster, end) if end < len(raster) else None
        end = cut.start() if cut else len(raster)
        tokens = raster[start:end].split()[: count - filled]
        for token in tokens:
            if not token.isdigit():
                raise ValueError(
                    f"{pgm}: P2 raster holds {token[:20]!r}, not a non-negative integer"
                )
            if len(token.lstrip(b"0")) > 5:  # > 65535, found without converting a huge number
                raise ValueError(f"{pgm}: PGM pixel value {token[:20]!r} exceeds maxval {maxval}")
        pixels[filled : filled + len(tokens)] = [int(t) for t in tokens]
        filled += len(tokens)
        start = end
    if filled < count:
        raise ValueError(f"{pgm}: PGM raster truncated: {filled} of {count} values")
    return pixels


class _Image(NamedTuple):
    """A decoded image: its size, and its grey levels 0..255 and alpha by bands of rows.

    ``rows(a, b)`` gives new float64 arrays of image rows ``a:b`` (alpha None
    when the image has none): :func:`read_map` converts an image a band at a
    time, so that its float64 temporaries stay a band's, not the image's.
    """

    height: int
    width: int
    rows: Callable[[int, int], tuple[NDArray[np.float64], NDArray[np.float64] | None]]

    def whole(self) -> NDArray[np.float64]:
        """The grey levels of the whole image."""
        return self.rows(0, self.height)[0]

    def both(self) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
        """The grey levels and alpha of the whole image."""
        return self.rows(0, self.height)


def _pgm_from(fh: BinaryIO, pgm: Path, *, map_server: bool = False) -> _Image:
    """:func:`read_pgm` of the open regular file ``fh`` (of ``pgm``), read from its start.

    ``map_server``: the grey levels Nav2's map_server reads (see :func:`_magick_grey`),
    not the samples scaled exactly.
    """
    fh.seek(0)
    head = fh.read(_PGM_HEADER_MAX)
    magic, width, height, maxval, offset = _pgm_header(head, pgm)
    count = width * height
    fh.seek(offset)
    # Never ask for more than the file holds: read(n) allocates n bytes first, and
    # a header of a few bytes may declare 2**28 pixels (gigabytes for a P2 raster).
    remaining = max(os.fstat(fh.fileno()).st_size - offset, 0)
    if magic == "P5":
        dtype = np.dtype(np.uint8) if maxval < 256 else np.dtype(">u2")
        need = count * dtype.itemsize
        raster = fh.read(min(need, remaining))
    else:
        # At most 5 digits and some whitespace per value; anything longer is
        # not a P2 raster of this size.
        raster = fh.read(min(count * 32 + _PGM_HEADER_MAX, remaining))
    if magic == "P5":
        if len(raster) < need:
            raise ValueError(
                f"{pgm}: PGM raster truncated: {counted(len(raster), 'byte')} for "
                f"{width} x {height} pixels ({counted(need, 'byte')} needed)"
            )
        # Widened to float64 only once checked (below): an int64 copy costs 8 bytes a pixel.
        pixels: NDArray[Any] = np.frombuffer(raster, dtype=dtype, count=count)
    else:
        pixels = _p2_pixels(raster, count, pgm, maxval)
    if pixels.size and (pixels.min() < 0 or pixels.max() > maxval):
        raise ValueError(f"{pgm}: PGM pixel values exceed maxval {maxval}")
    samples = pixels.reshape(height, width)

    def rows(a: int, b: int) -> tuple[NDArray[np.float64], None]:
        grey = samples[a:b].astype(np.float64)
        if map_server and maxval not in (255, 65535):
            return _magick_grey(grey, magic, maxval, count), None
        grey *= 255.0 / maxval  # in place: one float64 array of the rows' size
        return grey, None

    return _Image(height, width, rows)


#: GraphicsMagick's largest sample with 16 bits a sample (``MaxRGB``, QuantumDepth 16).
_MAX_RGB = 65535.0


def _magick_grey(
    samples: NDArray[np.float64], magic: str, maxval: int, pixels: int
) -> NDArray[np.float64]:
    """Grey levels 0..255 of PGM ``samples`` (float64, changed in place) as Nav2 reads them.

    ``samples`` may be some rows of an image of ``pixels`` pixels.

    Nav2's map_server (Humble to Iron) reads images with GraphicsMagick's
    Magick++ (``Image::pixelColor``), which Debian and Ubuntu build with 16 bits a
    sample (``libgraphicsmagick++-q16``). Its PNM reader (``coders/pnm.c``) gives
    a PGM of at least ``maxval`` pixels a grey colormap (``AllocateImageColormap``
    in ``magick/colormap.c``: entry ``i`` is ``i * (65535 // maxval)``, an integer
    division), and ``pixelColor`` reads that colormap: for a maxval other than
    255 and 65535 the levels fall short of the exact ``v * 65535 / maxval`` by up
    to one ``65535 // maxval`` step (maxval 1000: 65 in 65535, so the sample 1000
    reads as 252.9, not 255). A smaller image keeps its samples, scaled and
    rounded (``ScaleAnyToQuantum`` for P2, ``RoundDoubleToQuantum`` of the
    samples widened to 16 bits for P5). Checked against GraphicsMagick 1.3.40
    (Debian 12), Nav2's reading with Magick++, for maxval 3 to 4095.
    """
    q = samples
    if pixels >= maxval:
        q *= float(_MAX_RGB // maxval)  # the colormap entry of each sample
    elif magic == "P2":
        q *= _MAX_RGB
        q /= maxval
        q += 0.5
        np.floor(q, out=q)
    else:
        # P5 samples are widened to 16 bits first (257 v for one byte a sample), then
        # scaled by 65535 / sample_max, the widened maxval.
        wide = 257.0 if maxval < 256 else 1.0
        q *= wide
        q *= _MAX_RGB / (wide * maxval)
        q += 0.5
        np.floor(q, out=q)
        np.minimum(q, _MAX_RGB, out=q)
    q *= 255.0 / _MAX_RGB
    return q


def pgm_bytes(pixels: NDArray[np.uint8]) -> bytes:
    """Content of an 8-bit binary (P5) PGM; ``pixels`` row 0 is the top of the image.

    Examples
    --------
    >>> pgm_bytes(np.array([[0, 255]], dtype=np.uint8))
    b'P5\\n# CREATOR: navkit\\n2 1\\n255\\n\\x00\\xff'
    """
    height, width = pixels.shape
    header = f"P5\n# CREATOR: navkit\n{width} {height}\n255\n".encode("ascii")
    return header + np.ascontiguousarray(pixels, dtype=np.uint8).tobytes()


def png_bytes(pixels: NDArray[np.uint8]) -> bytes:
    """Content of an 8-bit RGBA PNG (the type map_saver writes scale maps in), by Pillow.

    ``pixels`` has shape ``(height, width, 4)``; row 0 is the top of the image.

    Raises
    ------
    ValueError
        ``pixels`` of another shape.
    ImportError
        Pillow is not installed (``pip install pillow``).

    Examples
    --------
    >>> data = png_bytes(np.array([[[0, 0, 0, 255], [128, 128, 128, 0]]], dtype=np.uint8))
    >>> data[1:4], data[12:16], int.from_bytes(data[16:20], "big"), data[25]
    (b'PNG', b'IHDR', 2, 6)
    """
    raster = np.ascontiguousarray(pixels, dtype=np.uint8)
    if raster.ndim != 3 or raster.shape[2] != 4:
        raise ValueError(f"pixels must have shape (h, w, 4), got {raster.shape}")
    image_module = _pillow("writing a scale-mode map image (a PNG with alpha)")
    out = io.BytesIO()
    image_module.fromarray(raster).save(out, format="PNG")  # (h, w, 4) uint8: RGBA
    return out.getvalue()


def _pillow(what: str) -> Any:
    """Pillow's ``PIL.Image`` module, or an ImportError saying ``what`` needs it."""
    try:
        from PIL import Image
    except ImportError:
        raise ImportError(
            f"{what} needs Pillow (only PGM is read and written without it); install it "
            "with `pip install pillow`"
        ) from None
    return Image


#: Held while :func:`_hidden_bomb_warning` changes the process-wide warning filters
#: (re-entrant: a block of one may open the image again).
_WARNINGS_LOCK = ForkSafeLock(reentrant=True)


@contextlib.contextmanager
def _hidden_bomb_warning(image_module: Any, size: tuple[int, int] | None) -> Iterator[None]:
    """Pillow's DecompressionBombWarning hidden in the block: our own size limit applies.

    Pillow warns when it opens (and some formats when they decode) an image
    of more than ``MAX_IMAGE_PIXELS`` pixels. ``warnings.catch_warnings``
    changes the filters of the whole process and puts back on exit the list
    it found on entry: two threads inside at once (maps read in parallel)
    leave the ignore filter installed for good when the later one to enter
    leaves last, and let the warning through in the other. navkit's threads
    therefore take turns here: while an image is opened (its header read,
    ``size`` None), and while one of ``size`` is decoded only if it is large
    enough for Pillow to warn (other images decode in parallel).
    """
    limit = image_module.MAX_IMAGE_PIXELS
    if size is not None and (limit is None or max(1, size[0]) * max(1, size[1]) <= limit):
        yield
        return
    with _WARNINGS_LOCK, warnings.catch_warnings():
        warnings.simplefilter("ignore", image_module.DecompressionBombWarning)
        yield


@contextlib.contextmanager
def _pillow_errors(
    path: Path, image_module: Any, size: tuple[int, int] | None = None
) -> Iterator[None]:
    """Turn whatever Pillow raises on a bad file into a ValueError naming it.

    Also hides Pillow's DecompressionBombWarning (:func:`_hidden_bomb_warning`)
    while an image is opened, or decoded when it has ``size``.
    """
    try:
        with _hidden_bomb_warning(image_module, size):
            yield
    except (FileNotFoundError, PermissionError):
        raise
    except image_module.UnidentifiedImageError:
        raise ValueError(f"{path}: not an image file Pillow can identify") from None
    except image_module.DecompressionBombError as exc:
        raise ValueError(
            f"{path}: {exc} This is Pillow's decompression-bomb limit "
            "(PIL.Image.MAX_IMAGE_PIXELS); navkit reads up to OccupancyGrid.MAX_CELLS = "
            "2**28 pixels: raise Pillow's limit or save the map as PGM to read it"
        ) from None
    except (OSError, SyntaxError, EOFError, ValueError, TypeError, IndexError, KeyError) as exc:
        raise ValueError(f"{path}: cannot read the image ({type(exc).__name__}: {exc})") from None
    except (struct.error, zlib.error) as exc:
        raise ValueError(f"{path}: cannot read the image ({type(exc).__name__}: {exc})") from None
    except Warning as exc:
        # Raised only where the caller turned warnings into errors (-W error):
        # Pillow warns of a damaged file (e.g. "Corrupt EXIF data") before failing.
        raise ValueError(f"{path}: cannot read the image ({type(exc).__name__}: {exc})") from None


#: Pillow's raw modes of PNGs with 16 bits per colour channel (its "RGB" and
#: "RGBA" images keep only the high byte of each sample), and the raw mode that
#: decodes the same bytes with the same bits per pixel into the low bytes (a
#: little-endian 16-bit mode keeps the second byte of each big-endian sample)
#: or, for grey + alpha, into all four bytes ``[Lhi, Llo, Ahi, Alo]``.
_DEEP_PNG_LOW = {"RGB;16B": "RGB;16L", "RGBA;16B": "RGBA;16L", "LA;16B": "RGBA"}
#: A raw mode with 16 bits per sample (not BMP's 16 bits per pixel "BGR;16").
_DEEP_RAWMODE = re.compile(r";16[BLN]$")


def _rawmodes(img: Any) -> list[str]:
    """The raw modes of the tiles Pillow will decode ``img`` with."""
    modes = []
    for tile in getattr(img, "tile", None) or ():
        args = tile[3] if len(tile) > 3 else None
        rawmode = args[0] if isinstance(args, tuple) and args else args
        if isinstance(rawmode, str):
            modes.append(rawmode)
    return modes


def _check_tiles(img: Any, path: Path) -> None:
    """Refuse an image whose tiles (the data Pillow decodes) do not cover its size.

    Pillow decodes the tiles into an image of the size the header declares and
    leaves the rest at zero (white in a TIFF whose 0 is white): a TIFF whose
    ``ImageLength`` byte is corrupted reads as millions of rows of invented free
    space. GIF frames may be smaller than the canvas (the background fills it);
    images without tiles are decoded by their plugin's own ``load``. The test
    is exact for any tiles (:func:`_boxes_cover`), overlapping ones too.
    """
    tiles = getattr(img, "tile", None) or ()
    if img.format == "GIF" or not tiles:
        return
    width, height = img.size
    boxes = np.array([tuple(tile[1]) for tile in tiles], dtype=np.int64).reshape(-1, 4)
    if not _boxes_cover(boxes, width, height):
        raise ValueError(
            f"{path}: the image data does not cover its declared size of {width} x "
            f"{height} pixels (width x height; is its header corrupted?)"
        )


#: Cells (checks x bands) up to which :func:`_always_held` adds up its events on a
#: dense table rather than halving them (a few hundred kilobytes).
_DENSE_CELLS = 1 << 15


def _boxes_cover(
    boxes: NDArray[np.int64], width: int, height: int, dense: int = _DENSE_CELLS
) -> bool:
    """Whether the union of ``boxes`` covers the pixels ``[0, width) x [0, height)``.

    A sweep across x: a box adds one to the rows it spans (in bands between
    the boxes' y edges) at its left edge and takes it back at its right edge;
    where the boxes change (at 0 and at each x edge inside the image) every
    band must be held by a box (:func:`_always_held`). Exact for any boxes,
    overlapping ones too, in time O(T log T) and memory O(T) for T boxes
    (review 45's grid of all their edges took T^2 cells, so past 65536 of
    them it compared areas only, and overlapping tiles leaving a gap passed).
    100,000 strips or regular tiles take about 0.1 s, as many random
    overlapping boxes about 1 s.

    Parameters
    ----------
    boxes : ndarray of int64, shape (T, 4)
        ``(x0, y0, x1, y1)`` of each box, pixels, right and bottom edges
        excluded (Pillow's tile boxes). Boxes reaching beyond the image, empty
        and inverted ones are allowed (they cover what they overlap of it).
    width, height : int
        The image's size, pixels.
    dense : int, optional
        :func:`_always_held`'s table size (tests make it small to halve often).

    Returns
    -------
    bool
        True if every pixel lies in a box (an image without pixels: True).
    """
    if width <= 0 or height <= 0:
        return True
    boxes = boxes.copy()
    np.clip(boxes[:, 0::2], 0, width, out=boxes[:, 0::2])
    np.clip(boxes[:, 1::2], 0, height, out=boxes[:, 1::2])
    boxes = boxes[(boxes[:, 2] > boxes[:, 0]) & (boxes[:, 3] > boxes[:, 1])]
    if not len(boxes):
        return False
    edges = np.unique(np.concatenate([boxes[:, 1], boxes[:, 3], [0, height]]))
    low, high = np.searchsorted(edges, boxes[:, 1]), np.searchsorted(edges, boxes[:, 3])
    # A box closing at the image's right edge changes no column of the image.
    closes = boxes[:, 2] < width
    x = np.concatenate([boxes[:, 0], boxes[closes, 2]])
    if x.min() > 0:
        return False  # the first column is in no box
    order = np.argsort(x, kind="stable")
    x = x[order]
    step = np.repeat(np.array([1, -1], np.int64), [len(boxes), int(closes.sum())])[order]
    # The last event at each x: from there to the next x the columns are alike.
    checks = np.flatnonzero(np.append(x[1:] != x[:-1], True))
    return _always_held(
        np.zeros(len(edges) - 1, np.int64),
        np.concatenate([low, low[closes]])[order],
        np.concatenate([high, high[closes]])[order],
        step,
        checks,
        dense,
    )


def _always_held(
    count: NDArray[np.int64],
    low: NDArray[np.int64],
    high: NDArray[np.int64],
    step: NDArray[np.int64],
    checks: NDArray[np.int64],
    dense: int,
) -> bool:
    """Whether every band's count stays above zero at each check of a run of events.

    Event ``i`` adds ``step[i]`` to bands ``low[i]`` to ``high[i] - 1`` of
    ``count`` (the counts before the first event); ``checks`` (increasing)
    are the events after which every band is checked. Up to ``dense`` cells
    the counts at every check are summed on a table; beyond, the events are
    halved at a check, and each half is solved on the bands its own events
    separate (between two of its edges all bands change alike, so the least
    count of each group is all that matters; a half of E events has at most
    2E + 1 such groups): O((E + B) log E) for E events on B bands.
    """
    bands = len(count)
    if len(checks) == 1 or len(checks) * (bands + 1) <= dense:
        # (Every run ends with a check: the events of check k are those up to it.)
        rows = np.repeat(np.arange(len(checks)), np.diff(checks, prepend=-1))
        table = np.zeros((len(checks), bands + 1), np.int64)
        np.add.at(table, (rows, low), step)
        np.add.at(table, (rows, high), -step)
        held = table.cumsum(axis=1)[:, :-1].cumsum(axis=0)
        held += count
        return bool((held > 0).all())
    middle = int(checks[len(checks) // 2 - 1]) + 1
    for first, last in ((0, middle), (middle, len(step))):
        low_part, high_part, step_part = low[first:last], high[first:last], step[first:last]
        part = checks[(checks >= first) & (checks < last)] - first
        # The half's edges (no sort: they are band numbers): group g of bands runs
        # from cuts[g] to cuts[g + 1] - 1, and edge e is the start of group rank[e].
        edge = np.zeros(bands + 1, np.bool_)
        edge[low_part] = edge[high_part] = edge[0] = edge[bands] = True
        cuts = np.flatnonzero(edge)
        rank = np.cumsum(edge) - 1
        least = np.minimum.reduceat(count, cuts[:-1])
        if not _always_held(least, rank[low_part], rank[high_part], step_part, part, dense):
            return False
        if first == 0:
            change = np.zeros(bands + 1, np.int64)
            np.add.at(change, low_part, step_part)
            np.add.at(change, high_part, -step_part)
            count = count + change.cumsum()[:-1]
    return True


def _deep_low_rawmode(img: Any, path: Path) -> str | None:
    """None for 8-bit colour, else the raw mode giving a 16-bit-colour PNG's other bytes.

    Pillow reads samples of 16 bits per colour channel to 8 bits (the high
    byte) while Nav2's map_server averages the full-depth channels
    (GraphicsMagick), so such images are either read whole
    (:func:`_deep_colour`: PNG) or refused here, never truncated.
    """
    rawmodes = _rawmodes(img)
    if img.mode.startswith("I") or not any(_DEEP_RAWMODE.search(m) for m in rawmodes):
        return None
    low = _DEEP_PNG_LOW.get(rawmodes[0]) if img.format == "PNG" and len(rawmodes) == 1 else None
    if low is None:
        raise ValueError(
            f"{path}: a {img.format} image with 16 bits per colour channel "
            f"(raw mode {', '.join(rawmodes)}), which Pillow reads only to 8 bits; save "
            "it with 8 bits per channel, as 16-bit greyscale, or as PGM"
        )
    return low


#: Bytes beyond twice its samples that a copy of a PNG with 16 bits per colour
#: channel may hold (ancillary chunks: ICC profiles, text) before it is refused.
_DEEP_PNG_SLACK = 1 << 24


def _deep_png_bytes(img: Any, fh: BinaryIO, path: Path) -> bytes:
    """The bytes of the open 16-bit colour PNG ``fh`` whose header ``img`` is, read once.

    Both decodes of :func:`_deep_colour` read this copy: decoding the file twice
    let one rewritten in place between them (same size) give a grid of one
    file's high bytes and the other's low bytes. The copy is of the file as it
    is now, none of it from the reader's buffer, so a header other than
    ``img`` (a file rewritten since) shows. Deflate and chunks add little to the
    samples, so a file larger than twice them plus :data:`_DEEP_PNG_SLACK` is
    refused unread.
    """
    width, height = img.size
    samples = width * height * 2 * len(img.getbands()) + height  # with a filter byte a row
    limit = 2 * samples + _DEEP_PNG_SLACK
    size = fh.seek(0, os.SEEK_END)  # a seek from the end drops what the reader buffered
    if size > limit:
        raise ValueError(
            f"{path}: a PNG of {width} x {height} pixels with 16 bits per colour channel "
            f"larger than {limit} bytes (twice its samples and {_DEEP_PNG_SLACK} bytes "
            "for other chunks): save it without the extra data"
        )
    fh.seek(0)
    return fh.read(size)


def _deep_colour(img: Any, low: str, data: bytes, image_module: Any) -> _Image:
    """Grey and alpha (0..255, or None) of a PNG with 16 bits per colour channel.

    The image is decoded twice from ``data``, one copy of the file's bytes
    (:func:`_deep_png_bytes`): as Pillow decodes it (the high bytes), then with
    the raw mode ``low`` (:data:`_DEEP_PNG_LOW`) on the same tile, which yields
    the low bytes. ``img`` is the header read from the file, from which ``low``
    was chosen and the size checked: a copy with another header (the file
    changed before it was copied) is refused.
    """
    rawmode = _rawmodes(img)[0]
    header = [tuple(tile[:4]) for tile in img.tile], img.size

    def opened() -> Any:
        with _hidden_bomb_warning(image_module, None):  # the header only, as in _read_with_pillow
            copy = image_module.open(io.BytesIO(data))
        if ([tuple(tile[:4]) for tile in copy.tile], copy.size) != header:
            copy.close()
            raise ValueError("the file changed while it was read")
        return copy

    with opened() as first:
        transparent = first.info.get("transparency")
        high = None if rawmode == "LA;16B" else np.asarray(first).astype(np.uint16)
    with opened() as again:
        tile = again.tile[0]
        again.tile = [(tile[0], tile[1], tile[2], low)]
        if high is None:
            second = np.asarray(again).astype(np.uint16)
        else:
            # In place: the samples reuse the high bytes' array, the low bytes
            # widened as they are or-ed in (no uint16 copy of them).
            samples = high
            samples <<= 8
            samples |= np.asarray(again)
    if high is None:  # LA: the four bytes of each pixel, [Lhi, Llo, Ahi, Alo]
        colour: NDArray[Any] = (second[..., 0] << 8 | second[..., 1])[..., np.newaxis]
        alpha16: NDArray[Any] | None = second[..., 2] << 8 | second[..., 3]
        del second
    else:
        colour = samples[..., :3]
        alpha16 = samples[..., 3] if rawmode == "RGBA;16B" else None
    key = (
        np.asarray(transparent, dtype=np.uint16)
        if alpha16 is None and isinstance(transparent, tuple) and len(transparent) == 3
        else None
    )

    def rows(a: int, b: int) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
        # x / 257 maps 0..65535 onto 0..255, exactly at both ends (65535 / 257 = 255).
        # The mean of the channels, summed one at a time into one float64 array rather
        # than widening all of them (24 bytes a pixel): sums of up to three 16-bit
        # integers are exact in any order, then divided as ndarray.mean divides.
        part = colour[a:b]
        grey = part[..., 0].astype(np.float64)
        for channel in range(1, part.shape[2]):
            grey += part[..., channel]
        grey /= part.shape[2]
        grey /= 257.0
        if alpha16 is not None:
            alpha = alpha16[a:b].astype(np.float64)
            alpha /= 257.0
            return grey, alpha
        if key is not None:
            # A transparent colour (PNG tRNS, of 16-bit samples here) is an alpha channel.
            return grey, np.where(np.all(part == key, axis=2), 0.0, 255.0)
        return grey, None

    return _Image(colour.shape[0], colour.shape[1], rows)


def _read_with_pillow(fh: BinaryIO, path: Path) -> _Image:
    """:func:`read_image` by Pillow of the open regular file ``fh`` (of ``path``)."""
    Image = _pillow(f"reading the map image {path.name}")
    with _pillow_errors(path, Image):
        img = Image.open(fh)  # reads the header only; Pillow leaves fh open
    with img:
        width, height = img.size
        _check_image_size(width, height, path)
        _check_tiles(img, path)
        low = _deep_low_rawmode(img, path)
        if low is not None:
            data = _deep_png_bytes(img, fh, path)
            with _pillow_errors(path, Image, img.size):
                return _deep_colour(img, low, data, Image)
        with _pillow_errors(path, Image, img.size):
            picture: Any = img
            if picture.mode == "F":
                # Pillow converts floats to 0..255 by clipping: a map of probabilities
                # in [0, 1] read as black, every cell occupied, without a word.
                raise ValueError(
                    f"{path}: a 32-bit floating-point image, which map_server does not "
                    "read and whose scale no map format fixes: save the map as an "
                    "8-bit grey image (0 occupied, 255 free)"
                )
            native = picture.mode in ("L", "LA", "RGB", "RGBA", "P", "1")
            if not native and not picture.mode.startswith("I"):
                picture = picture.convert("RGBA")
            if "transparency" in picture.info and picture.mode in ("L", "RGB", "P", "1"):
                # A transparent colour (PNG tRNS) is an alpha channel to map_server.
                picture = picture.convert("RGBA")
            elif picture.mode == "P":
                # Palette colours are averaged like RGB pixels (map_server's shade),
                # not converted to Pillow's weighted luma ("L").
                picture = picture.convert("RGB")
            elif picture.mode == "1":
                picture = picture.convert("L")
            arr = np.asarray(picture)
            mode = picture.mode
            sixteen_bit = mode.startswith("I;16") or (mode == "I" and img.format == "PNG")
            transparent = picture.info.get("transparency")
    if mode.startswith("I"):
        # 16-bit images (PNG's deepest grey, which older Pillow versions open as
        # mode "I") span 0..65535 whatever they hold; only 32-bit ones, whose range
        # no map format fixes, are scaled by what they hold.
        peak = 65535.0 if sixteen_bit or arr.max(initial=0) > 255 else 255.0
        keyed = isinstance(transparent, int) and not isinstance(transparent, bool)

        def deep_rows(a: int, b: int) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
            grey = arr[a:b].astype(np.float64)
            grey *= 255.0 / peak
            np.clip(grey, 0.0, 255.0, out=grey)
            if keyed:
                # A transparent grey (PNG tRNS) is an alpha channel to map_server, as
                # for 8-bit images (converted to RGBA above, which would lose 8 bits here).
                return grey, np.where(arr[a:b] == transparent, 0.0, 255.0)
            return grey, None

        return _Image(arr.shape[0], arr.shape[1], deep_rows)
    has_alpha = mode in ("LA", "RGBA")

    def rows(a: int, b: int) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
        part = arr[a:b]
        if part.ndim == 2:
            return part.astype(np.float64), None
        colour = part[..., :-1] if has_alpha else part
        # ndarray.mean(axis=2) of the channels without widening all of them to
        # float64 first (8 bytes a channel a pixel); the sums are exact.
        grey = colour[..., 0].astype(np.float64)
        for channel in range(1, colour.shape[2]):
            grey += colour[..., channel]
        grey /= colour.shape[2]
        alpha = part[..., -1].astype(np.float64) if has_alpha else None
        return grey, alpha

    return _Image(arr.shape[0], arr.shape[1], rows)


def read_image(path: Path) -> tuple[NDArray[np.float64], NDArray[np.float64] | None]:
    """Grey levels 0..255 (averaged over colour channels) and alpha (or None) of an image.

    PGM files are read with numpy, their grey levels as Nav2's map_server reads
    them (GraphicsMagick's; for a ``maxval`` other than 255 and 65535 they differ
    from the exact ``v * 255 / maxval`` that :func:`read_pgm` returns, see
    :func:`read_map`); anything else needs Pillow. 16-bit samples
    are scaled from 0..65535 (PNGs with 16-bit colour channels at full depth,
    not Pillow's 8-bit truncation); a ValueError naming the file refuses other
    images with 16-bit colour channels.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "a.pgm").write_bytes(pgm_bytes(np.array([[0, 205]], np.uint8)))
    ...     read_image(Path(folder) / "a.pgm")
    (array([[  0., 205.]]), None)
    """
    with open_regular(path, "image") as fh:
        return _image_from(fh, path).both()


def _image_from(fh: BinaryIO, path: Path) -> _Image:
    """:func:`read_image` of the open regular file ``fh`` (of ``path``), by bands of rows."""
    magic = fh.read(2)
    if magic in (b"P5", b"P2"):
        return _pgm_from(fh, path, map_server=True)
    if path.suffix.lower() == ".pgm":
        raise ValueError(f"{path}: not a PGM image (magic {magic!r}, expected P5 or P2)")
    if not magic:
        raise ValueError(f"{path}: the image file is empty")
    return _read_with_pillow(fh, path)


def pixel_occupancy(
    grey: NDArray[np.float64],
    alpha: NDArray[np.float64] | None,
    meta: MapMetadata,
) -> tuple[NDArray[np.float64], NDArray[np.bool_]]:
    """map_server's reading of pixels: occupancy probability and unknown mask.

    With ``negate`` 0, ``p = 1 - v / 255`` (computed so, as Nav2's map_server
    does: it decides pixels on a threshold such as ``free_thresh: 0.2``). In
    ``trinary`` mode the alpha channel, when there is one, is averaged in with
    the three colour channels (map_server's long-standing behaviour: an opaque
    205 grey reads as 217.5) and a pixel is occupied (p = 1) above
    ``occupied_thresh``, free (p = 0) below ``free_thresh`` and unknown
    otherwise. ``scale`` makes every pixel that is not fully opaque unknown and
    keeps ``p`` itself for the in-between ones; ``raw`` reads the grey value
    directly as a percentage (values above 100 are unknown). Rows are in image
    order. This is Nav2 Humble's reading (``map_io.cpp``); Nav2 from Jazzy on
    differs at exact thresholds, on colour, 16-bit and, in trinary mode,
    translucent pixels (see :func:`read_map`).

    Examples
    --------
    >>> meta = MapMetadata(Path("m.pgm"), 0.05, (0.0, 0.0, 0.0), False, 0.65, 0.196, "trinary")
    >>> prob, unknown = pixel_occupancy(np.array([[0.0, 205.0, 254.0]]), None, meta)
    >>> prob, unknown
    (array([[1. , 0.5, 0. ]]), array([[False,  True, False]]))
    """
    # The arithmetic is done in place in one new float64 array, which becomes the
    # returned probabilities: 8 bytes a pixel, plus the boolean masks.
    if meta.mode == "raw":
        value = np.rint(grey)
        unknown = value > 100
        value /= 100.0
        value[unknown] = 0.5
        return value, unknown
    if meta.mode == "trinary" and alpha is not None:
        # map_server averages the alpha in with red, green and blue in trinary mode.
        shade = 3.0 * grey
        shade += alpha
        shade /= 4.0 * 255.0
    else:
        shade = grey / 255.0
    # 1 - shade, not (255 - v) / 255: the two differ in the last bit for some
    # levels (204 with free_thresh 0.2), and map_server computes the former.
    p = shade if meta.negate else np.subtract(1.0, shade, out=shade)
    occupied = p > meta.occupied_thresh
    free = p < meta.free_thresh
    between = ~occupied & ~free
    if meta.mode == "trinary":
        p.fill(0.5)
        p[free] = 0.0
        p[occupied] = 1.0
        return p, between
    # Scale mode: map_server checks opacity first, then the thresholds.
    unknown = alpha < 255.0 if alpha is not None else np.zeros_like(between)
    p[free] = 0.0
    p[occupied] = 1.0
    return p, unknown


def read_map(path: str | os.PathLike[str]) -> OccupancyGrid:
    """Load a ROS map_server map (YAML + image) as an :class:`~navkit.mapping.OccupancyGrid`.

    Understands the keys ``image``, ``resolution``, ``origin`` [x, y, yaw],
    ``negate``, ``occupied_thresh``, ``free_thresh`` (all required, as in
    Nav2's map_server) and ``mode`` (``trinary`` by default, ``scale`` or
    ``raw``). PGM images (P5, P2) are read with numpy; other formats such as
    PNG need Pillow. The image's top row becomes the last grid row. The
    ``origin`` is the world pose of the outer (lower-left) corner of the
    image's bottom-left pixel, i.e. of grid cell (0, 0), whose centre is half
    a cell further along x and y; a non-zero yaw rotates the grid about that
    corner, as the orientation of the ``nav_msgs/OccupancyGrid`` that Nav2's
    map_server publishes for it (Nav2's costmaps ignore that orientation and
    place such a map unrotated). The YAML's thresholds become the grid's
    thresholds, so the views reproduce map_server's trinary classification.
    Unknown pixels become p = 0.5 (log-odds 0), or the middle of the unknown
    band when the thresholds do not class 0.5 as unknown. 16-bit images span
    0..65535: 16-bit grey, and PNGs with 16 bits per colour channel (RGB,
    grey + alpha, RGBA), are read at full depth, as Nav2's map_server up to
    Iron reads them (see Notes); other images with 16-bit colour channels (e.g.
    TIFF), which Pillow would truncate to 8 bits, are refused, and so are
    32-bit floating-point images (Pillow would clip them to 0..255; map_server
    does not read them).

    The YAML is read as map_server's yaml-cpp reads a hand-edited one: line
    ends ``\\n``, ``\\r\\n`` or ``\\r``; tabs between tokens and on blank or
    comment lines; bytes that are not UTF-8 (a Latin-1 editor's) skipped in
    comments and looked up as written in the ``image`` name.

    Parameters
    ----------
    path : str or path-like
        The map's YAML file; a relative ``image`` is found beside it. The
        ``image`` value is read as its text, as map_server's yaml-cpp reads
        it: ``image: yes``, ``1.50`` or ``2001-12-14`` name those files.

    Returns
    -------
    OccupancyGrid
        The map: log-odds of the pixels' occupancy probabilities (unknown
        pixels 0), the YAML's resolution, origin and thresholds. Probabilities
        are clipped to [0.001, 0.999] as by
        :meth:`~navkit.mapping.OccupancyGrid.from_probabilities`, except where
        that would move a cell across a threshold beyond the clipping (e.g.
        ``occupied_thresh: 0.9995``): such a cell gets the log-odds just past
        its threshold, so that the views class every pixel as map_server does.

    Raises
    ------
    TypeError
        A ``path`` that is not a str or path-like.
    FileNotFoundError
        Missing YAML or image file.
    ValueError
        Anything malformed, with the file and the problem named: a YAML that
        is not a small map YAML in UTF-8 (or UTF-16 or UTF-32 with a
        byte-order mark; an image passed instead, binary data; bytes that
        are not UTF-8 in a number, list or ``mode``),
        missing or invalid keys (see :func:`read_map_yaml` for the ranges),
        an image that is garbage, truncated, not an image (the YAML itself, a
        text file), a non-PNG image with 16-bit colour channels, a 32-bit
        floating-point image, a directory,
        a FIFO or a device (checked on the descriptor the file is then read
        from), or larger than ``OccupancyGrid.MAX_CELLS`` (``2**28``) pixels
        (checked from its header before decoding; images read with Pillow
        also against Pillow's decompression-bomb limit).
    ImportError
        A non-PGM image and Pillow is not installed.
    OSError
        The operating system refuses to read a file (e.g. ``PermissionError``).

    Notes
    -----
    Pixels are classed exactly as Nav2's map_server up to Iron classes them
    (``map_io.cpp`` of the ``humble`` branch; see :func:`pixel_occupancy`) and,
    for 8-bit images but for one tie in the last bit (grey 204 under
    ``free_thresh: 0.2`` is free here, unknown there), as ROS 1's. Nav2 from
    Jazzy on (``map_io.cpp`` rewritten in 2025) classes some pixels
    differently. It compares in float32 with ``>=`` and ``<=``: a pixel exactly
    at a threshold is occupied or free there, unknown here (with
    ``occupied_thresh: 1`` black is occupied there, never here; with
    ``free_thresh: 0`` white is free there). It converts colour to
    GraphicsMagick's luminance (weighted, not the mean of the channels) and
    16-bit images to 8 bits. In ``trinary`` mode it reads every pixel that is
    not fully opaque as unknown, where alpha is averaged in here (an opaque 205
    grey in an RGBA PNG is free here and in Humble, unknown in Jazzy). Maps
    written by map_saver or :func:`write_map` (grey PGM, 0 / 205 / 254, or
    scale PNGs with opaque grey and transparent unknown) read the same in both
    under the default thresholds.

    A PGM whose ``maxval`` is neither 255 nor 65535 is read as Nav2 reads it with
    GraphicsMagick (16 bits a sample, as Debian and Ubuntu build it): an image
    of at least ``maxval`` pixels through a grey colormap of ``65535 // maxval``
    steps, whose levels fall short of the exact ``v * 255 / maxval`` (maxval
    1000: sample 53 is 13 % in ``raw`` mode, not 14; 163 of the 1001 levels
    differ), a smaller one with its samples rounded to 16 bits (checked against
    GraphicsMagick 1.3.40 for maxval 3 to 4095). Not reproduced:
    GraphicsMagick reads a binary (P5) PGM with ``maxval`` 1 as packed bits,
    eight pixels a byte, where the PGM format (and navkit) has one byte a pixel.

    ``negate`` and ``raw`` mode: Nav2 (``map_io.cpp``, ``MapMode::Raw`` reads
    ``shade``, before ``negate`` applies) and navkit ignore ``negate`` in raw
    mode; ROS 1's map_server (``map_server/src/image_loader.cpp`` of
    ros-planning/navigation: ``if(negate) color_avg = 255 - color_avg;`` comes
    before ``if(mode==RAW)``) applies it, so a raw map with ``negate: 1`` reads
    255 - v there. ROS 1 also stores that level itself as the cell's value,
    with no limit at 100 (a byte copied into the int8 data: 101-127 stay,
    128-255 become negative), where Nav2 and navkit read levels above 100 as
    unknown.

    Peak memory, in bytes a pixel, besides the returned grid (4 bytes a cell, the
    float32 log-odds) and about 10 MiB: the decoded image, whose grey levels,
    probabilities and log-odds are computed a band of rows at a time. About 1.5
    for an 8-bit binary PGM or grey PNG (the raster), 2.5 for a 16-bit PGM, 6 for
    an ASCII PGM (its text, then 4-byte values), 6 for an 8-bit colour PNG
    (Pillow's image and a copy), and about 20 for a PNG with 16-bit colour
    channels, which is decoded twice at 8 bits by Pillow and combined
    (``RGBA``: 4 + 4 bytes a pixel outside NumPy's, 4 for a copy, 8 for the
    16-bit samples). At the ``2**28``-pixel limit that is, with the grid, about
    1.4 GiB for an 8-bit PGM and 6 GiB for a 16-bit RGBA PNG (review 45: 5 and 9
    GiB): on a small computer, keep large maps in PGM or 8-bit grey PNG.

    Examples
    --------
    >>> import tempfile
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     _ = (Path(folder) / "m.pgm").write_bytes(b"P5 2 1 255 \\x00\\xfe")
    ...     _ = (Path(folder) / "m.yaml").write_text(
    ...         "image: m.pgm\\nresolution: 0.5\\norigin: [1, 2, 0]\\nnegate: 0\\n"
    ...         "occupied_thresh: 0.65\\nfree_thresh: 0.196\\n")
    ...     grid = read_map(Path(folder) / "m.yaml")
    >>> grid.occupied().tolist(), grid.free().tolist(), grid.origin
    ([[True, False]], [[False, True]], Pose2D(x=1.0, y=2.0, theta=0.0))
    """
    with _printable_errors():
        meta = read_map_yaml(path)
        # read_map_yaml checked the image by name: it is checked again, and read, on
        # one open descriptor, whatever was put in its place since.
        with open_regular(meta.image, f"{as_path(path, 'path')}: map image") as fh:
            try:
                image = _image_from(fh, meta.image)
            except ValueError as exc:
                raise ValueError(_printable(f"{path}: map image {exc}")) from None
    rows = image.height
    logodds = np.empty((rows, image.width), dtype=np.float32)
    step = max(1, _READ_BLOCK_PIXELS // image.width)
    unknown_l = _unknown_logodds(meta.occupied_thresh, meta.free_thresh)
    # A band of image rows at a time: every step below is the same for each pixel
    # whatever the others hold, and its float64 temporaries stay a band's.
    for a in range(0, rows, step):
        b = min(rows, a + step)
        grey, alpha = image.rows(a, b)
        prob, unknown = pixel_occupancy(grey, alpha, meta)
        del grey, alpha
        # The image's top row becomes the last grid row.
        logodds[rows - b : rows - a] = _band_logodds(prob, unknown, meta, unknown_l)
    del image  # the decoded pixels, before the grid is checked
    return OccupancyGrid._adopting(
        logodds,
        resolution=meta.resolution,
        origin=Pose2D(*meta.origin),
        occupied_thresh=meta.occupied_thresh,
        free_thresh=meta.free_thresh,
    )


def _band_logodds(
    prob: NDArray[np.float64], unknown: NDArray[np.bool_], meta: MapMetadata, unknown_l: float
) -> NDArray[np.float32]:
    """Float32 log-odds of some image rows' :func:`pixel_occupancy`, in grid order (flipped).

    ``prob`` (a new array) is changed; ``unknown_l`` is :func:`_unknown_logodds`.
    """
    occ_t, free_t = meta.occupied_thresh, meta.free_thresh
    prob[unknown] = 0.5
    p = prob[::-1]
    unknown = unknown[::-1]
    known = OccupancyGrid.from_probabilities(
        p, resolution=meta.resolution, occupied_thresh=occ_t, free_thresh=free_t
    )
    # Unknown cells get exactly the log-odds write_map recognises as unknown.
    grid = known
    if unknown_l != 0.0 and unknown.any():
        grid = _with_logodds(known, np.where(unknown, np.float32(unknown_l), known.logodds))
    # Thresholds beyond the grid's probability clipping ([0.001, 0.999]) can make a
    # clipped cell change class (p = 1 not above occupied_thresh 0.9995): such
    # cells get log-odds that the grid's views class as map_server does.
    probe = OccupancyGrid.from_probabilities(
        [[1.0, 0.0]], resolution=1.0, occupied_thresh=occ_t, free_thresh=free_t
    )
    if probe.occupied()[0, 0] and probe.free()[0, 1]:
        return grid.logodds  # the thresholds lie inside the clipping: it changes no class
    want_occupied = ~unknown & (p > occ_t)
    want_free = ~unknown & (p < free_t)
    wrong = (grid.occupied() != want_occupied) | (grid.free() != want_free)
    if not wrong.any():
        return grid.logodds
    logodds = np.array(grid.logodds)
    logodds[wrong] = _class_logodds(
        p[wrong], want_occupied[wrong], want_free[wrong], occ_t, free_t, unknown_l
    )
    return logodds


def _with_logodds(grid: OccupancyGrid, logodds: NDArray[np.float32]) -> OccupancyGrid:
    """``grid`` with other log-odds (same size, resolution, origin and thresholds)."""
    return OccupancyGrid(
        logodds,
        resolution=grid.resolution,
        origin=grid.origin,
        occupied_thresh=grid.occupied_thresh,
        free_thresh=grid.free_thresh,
    )


def _class_logodds(
    p: NDArray[np.float64],
    occupied: NDArray[np.bool_],
    free: NDArray[np.bool_],
    occupied_thresh: float,
    free_thresh: float,
    unknown_l: float,
) -> NDArray[np.float32]:
    """Float32 log-odds of ``p`` in the class given, for cells clipping moved out of it.

    Occupied and free cells get the next float32 past their threshold's log-odds;
    the others ``p``'s own unclipped log-odds if the grid classes them unknown,
    else ``unknown_l``.
    """
    with np.errstate(divide="ignore"):
        out = np.log(p / (1.0 - p)).astype(np.float32)
    one = OccupancyGrid(
        np.where(np.isfinite(out), out, 0.0)[None, :],
        resolution=1.0,
        occupied_thresh=occupied_thresh,
        free_thresh=free_thresh,
    )
    bad = ~np.isfinite(out) | ~one.unknown()[0]
    out[bad] = np.float32(unknown_l)
    if occupied.any():  # occupied_thresh < 1 then: p > occupied_thresh
        bound = np.float32(math.log(occupied_thresh / (1.0 - occupied_thresh)))
        out[occupied] = np.nextafter(bound, np.float32(np.inf))
    if free.any():  # 0 < free_thresh
        bound = np.float32(math.log(free_thresh / (1.0 - free_thresh)))
        out[free] = np.nextafter(bound, np.float32(-np.inf))
    return out


def _unknown_logodds(occupied_thresh: float, free_thresh: float) -> float:
    """Log-odds :func:`read_map` gives unknown pixels (``write_map`` writes them back so).

    0 (p = 0.5, no evidence) when the thresholds class p = 0.5 as unknown;
    otherwise those of the middle of the unknown band, so that the grid's
    views still find the cells unknown, as map_server does. Computed by the
    grid's own conversion, so that a comparison with a grid's log-odds is exact.
    """
    if free_thresh <= 0.5 <= occupied_thresh:
        return 0.0
    middle = 0.5 * (free_thresh + occupied_thresh)
    one = OccupancyGrid.from_probabilities(
        [[middle]], resolution=1.0, occupied_thresh=occupied_thresh, free_thresh=free_thresh
    )
    if one.unknown()[0, 0]:
        return float(one.logodds[0, 0])
    # A band beyond the grid's probability clipping (above 0.999 or below 0.001):
    # the clipped middle would be occupied or free. The threshold's own log-odds
    # is unknown (neither above itself nor below the lower one's).
    for p in (middle, occupied_thresh, free_thresh):
        if 0.0 < p < 1.0:
            candidate = float(np.float32(math.log(p / (1.0 - p))))
            if _one_cell(candidate, occupied_thresh, free_thresh).unknown()[0, 0]:
                return candidate
    raise AssertionError("unreachable: a threshold strictly inside (0, 1) is unknown")


def _one_cell(logodds: float, occupied_thresh: float, free_thresh: float) -> OccupancyGrid:
    return OccupancyGrid(
        np.full((1, 1), logodds),
        resolution=1.0,
        occupied_thresh=occupied_thresh,
        free_thresh=free_thresh,
    )


def _scale_darkness(logodds: NDArray[np.float32]) -> NDArray[np.int64]:
    """``255 -`` mode ``"scale"``'s grey ``round(255 * (1 - p))`` of every value, by the formula.

    Non-decreasing in the log-odds: the oracle of :func:`_darkness_table`.
    """
    grey = np.rint(255.0 * (1.0 - row_probability(logodds))).astype(np.uint8)
    return 255 - grey.astype(np.int64)


@functools.cache
def _darkness_table() -> StepTable:
    """:func:`step_table` of :func:`_scale_darkness`: grey levels without an ``exp`` per cell."""
    return step_table(_scale_darkness, 255)


def _blocks(rows: int, cols: int, size: int) -> Iterator[tuple[int, int, int, int]]:
    """``(row0, row1, col0, col1)``: whole rows up to ``size`` cells, or parts of one row."""
    if cols >= size:
        for r in range(rows):
            for c in range(0, cols, size):
                yield r, r + 1, c, min(c + size, cols)
    else:
        step = size // cols
        for r in range(0, rows, step):
            yield r, min(r + step, rows), 0, cols


def _map_image(grid: OccupancyGrid, mode: str) -> NDArray[np.uint8]:
    """Image pixels of ``grid``, top row first (the grid's last row, highest y).

    Grey ``(rows, cols)`` in trinary mode, RGBA ``(rows, cols, 4)`` in scale
    mode (:func:`_scale_image`).
    """
    if mode != "trinary":
        return _scale_image(grid)
    occ_t, free_t = grid.occupied_thresh, grid.free_thresh
    occupied, free = grid.occupied(), grid.free()
    unknown = ~occupied & ~free
    # map_saver's 254 unless free_thresh is below its reading (1/255): then 255.
    pixels = np.full(grid.shape, 254 if _pixel_p(254) < free_t else 255, dtype=np.uint8)
    if unknown.any():
        pixels[unknown] = _unknown_pixel(occ_t, free_t, preferred=205)
    pixels[occupied] = 0
    return pixels[::-1]


def _scale_image(grid: OccupancyGrid) -> NDArray[np.uint8]:
    """Mode ``"scale"``'s RGBA image of ``grid``, top row first, C-contiguous.

    Every cell is opaque grey ``round(255 * (1 - p))`` (map_server reads it as
    occupied, free or an in-between value, as the grid's views class it)
    except the unknown cells, which are transparent (map_server's unknown, -1,
    in scale mode). Unknown cells are those whose log-odds are exactly the
    ones :func:`read_map` gives unknown pixels: 0 (never observed) when the
    thresholds class p = 0.5 as unknown, else the middle of the band. Where
    rounding would move a cell across a threshold, an occupied cell is 0, a
    free one 255 and another the nearest grey level map_server reads as unknown.

    Each grey level is found by look-up (:func:`_darkness_table`), the class
    corrections by a table of the 256 levels, over blocks of cells: the same
    pixels as the formula and the grid's views over the whole grid, with no
    ``exp`` per cell (only for cells whose grey rounding crosses a threshold)
    and, besides the image, memory for one block.
    """
    occ_t, free_t = grid.occupied_thresh, grid.free_thresh
    unknown_l = np.float32(_unknown_logodds(occ_t, free_t))
    # A pixel as one little-endian uint32, R | G << 8 | B << 16 | A << 24, at
    # class << 8 | darkness (255 - grey); classes unknown, occupied, free and
    # transparent (unknown cells written as such).
    grey = 255 - np.arange(256, dtype=np.uint32)
    p_px = _pixel_p(grey)
    greys = [grey, np.where(p_px > occ_t, grey, 0), np.where(p_px < free_t, grey, 255), grey]
    alphas = np.repeat(np.array([255, 255, 255, 0], dtype=np.uint32), 256)
    rgba_of = (np.concatenate(greys) * 0x010101 | alphas << 24).astype("<u4")
    # Unknown cells whose grey would read as occupied or free: the nearest unknown level.
    crossing = np.zeros(1024, dtype=np.bool_)
    crossing[:256] = (p_px > occ_t) | (p_px < free_t)
    rows, cols = grid.shape
    image = np.empty((rows, cols, 4), dtype=np.uint8)
    image_rgba = image.view("<u4")[..., 0]
    logodds = grid.logodds
    size = min(rows * cols, LOOK_UP_BLOCK)
    look_up = StepLookUp(_darkness_table(), size)
    darkness = np.empty(size, dtype=np.uint8)
    at = np.empty(size, dtype=np.uint16)
    for r0, r1, c0, c1 in _blocks(rows, cols, LOOK_UP_BLOCK):
        block = np.ascontiguousarray(logodds[r0:r1, c0:c1]).reshape(-1)
        m = block.size
        look_up(block, darkness[:m])
        # Classes by the grid's own views, on a one-row grid of the block.
        part = OccupancyGrid(
            block.reshape(1, -1), resolution=1.0, occupied_thresh=occ_t, free_thresh=free_t
        )
        cls = part.occupied()[0].view(np.uint8) + 2 * part.free()[0].view(np.uint8)
        cls[(cls == 0) & (block == unknown_l)] = 3
        np.left_shift(cls, 8, out=at[:m], dtype=np.uint16)
        at[:m] |= darkness[:m]
        pixels = rgba_of[at[:m]]
        between = crossing[at[:m]]
        if between.any():
            nearest = _nearest_unknown_pixels(row_probability(block[between]), occ_t, free_t)
            pixels[between] = nearest.astype(np.uint32) * 0x010101 | 0xFF000000
        # Grid rows r0..r1 - 1 are image rows rows - 1 - r0 down to rows - r1.
        image_rgba[rows - r1 : rows - r0, c0:c1][::-1] = pixels.reshape(r1 - r0, c1 - c0)
    return image


_GREY_LEVELS = np.arange(256)


def _pixel_p(levels: Any) -> Any:
    """map_server's occupancy of 8-bit grey ``levels`` (negate 0): ``1 - v / 255``."""
    return 1.0 - np.asarray(levels) / 255.0


def _unknown_pixel(occupied_thresh: float, free_thresh: float, *, preferred: int | None) -> int:
    """A grey level map_server reads as unknown under these thresholds.

    ``preferred`` when it is one (205, map_saver's unknown, in trinary mode),
    else the one nearest the middle of the unknown band; ValueError when the band
    holds no 8-bit grey level, as it can when it is narrower than 0.004: the levels'
    ``p`` are rounded, and the widest gap between two is 0.0039215686274510775,
    9.7e-17 more than 1/255 (review 29: the advice said "more than 1/255").
    """
    p = _pixel_p(_GREY_LEVELS)  # map_server's reading of each level (negate 0)
    unknown = (free_thresh <= p) & (p <= occupied_thresh)
    if preferred is not None and unknown[preferred]:
        return preferred
    if not unknown.any():
        raise ValueError(
            f"the grid's thresholds (free_thresh={free_thresh}, occupied_thresh="
            f"{occupied_thresh}) leave no 8-bit grey level that map_server reads as "
            "unknown, so its unknown cells cannot be written; widen the band between them "
            "(the same cells with thresholds at least 0.004 apart: OccupancyGrid(grid.logodds, "
            "resolution=grid.resolution, origin=grid.origin, occupied_thresh=..., "
            "free_thresh=...))"
        )
    middle = 0.5 * (free_thresh + occupied_thresh)
    return int(_GREY_LEVELS[unknown][np.argmin(np.abs(p[unknown] - middle))])


def _nearest_unknown_pixels(
    p: NDArray[np.float64], occupied_thresh: float, free_thresh: float
) -> NDArray[np.uint8]:
    """For each probability ``p``, the grey level map_server reads as unknown nearest to it.

    For in-between cells whose rounded grey would cross a threshold: the
    nearest level inside the band keeps both the class and the value as close
    as 8 bits allow (not the middle of the band, which could be ~0.2 away).
    ValueError, as :func:`_unknown_pixel`, when the band holds no level.
    """
    _unknown_pixel(occupied_thresh, free_thresh, preferred=None)  # raises if none
    level_p = _pixel_p(_GREY_LEVELS)
    inside = (free_thresh <= level_p) & (level_p <= occupied_thresh)
    # Levels in increasing order of their reading (255 reads 0, 0 reads 1).
    levels = _GREY_LEVELS[inside][::-1]
    readings = level_p[inside][::-1]
    upper = np.clip(np.searchsorted(readings, p), 0, len(readings) - 1)
    lower = np.clip(upper - 1, 0, len(readings) - 1)
    nearest = np.where(np.abs(readings[lower] - p) <= np.abs(readings[upper] - p), lower, upper)
    return np.asarray(levels[nearest], dtype=np.uint8)


def _replace_all(files: list[tuple[Path, bytes]]) -> None:
    """Write every ``(target, data)`` to a temporary file first, then rename them all.

    A failure while writing (disk full, permissions, an interrupt) leaves every
    target as it was and removes the temporary files.
    """
    with atomic_paths([target for target, _ in files]) as temporaries:
        for temporary, (_, data) in zip(temporaries, files, strict=True):
            temporary.write_bytes(data)


def _image_path(yaml_path: Path, image_format: str) -> Path:
    """The image written beside ``yaml_path``; refuses paths it would overwrite."""
    if not yaml_path.name:
        raise ValueError(f"path must name a YAML file, got {str(yaml_path)!r}")
    suffix = yaml_path.suffix.lower()
    if suffix == f".{image_format}":
        raise ValueError(
            f"path {str(yaml_path)!r} ends in .{image_format}, the image's own name: the "
            "image would overwrite the YAML; give the YAML file another suffix such as .yaml"
        )
    if suffix in _IMAGE_SUFFIXES:
        raise ValueError(
            f"path {str(yaml_path)!r} ends in {yaml_path.suffix}, an image suffix: the map "
            "YAML would overwrite an image file; give the YAML file the suffix .yaml"
        )
    image = yaml_path.with_suffix(f".{image_format}")
    for target in (yaml_path, image):
        if target.is_dir():
            raise ValueError(f"cannot write the map file {target}: it is a directory")
    # Under the lock of the renames: another thread's save of this map, its image
    # renamed and its YAML not yet, would read as a foreign image.
    with RENAME_LOCK:
        same = image.exists() and yaml_path.exists() and os.path.samefile(image, yaml_path)
        foreign = not same and image.exists() and not _names_image(yaml_path, image)
    if same:
        raise ValueError(f"{yaml_path} and {image} are the same file")
    if foreign:
        raise ValueError(
            f"{image} already exists and is not the image of the map {yaml_path}: saving "
            "would overwrite it (another map's image?); remove it or save under another name"
        )
    return image


def _names_image(yaml_path: Path, image: Path) -> bool:
    """Whether ``yaml_path`` is a map YAML whose ``image`` key is the file ``image``."""
    try:
        if not yaml_path.is_file():
            return False
        name = _yaml_entries(yaml_path).get("image")
        if not isinstance(name, str) or not name or "\x00" in name:
            return False
        named = _image_file(yaml_path, name)
        return named.exists() and os.path.samefile(named, image)
    except (OSError, ValueError):
        return False


class _Superseded(NamedTuple):
    """The previous mode's image to remove after a save, and the file it was when chosen."""

    path: Path
    device: int
    inode: int


def _superseded_image(yaml_path: Path, image: Path) -> _Superseded | None:
    """The other mode's image of the map at ``yaml_path``, if this save makes it stale.

    A save in one mode replaces the map at ``yaml_path`` whose image may be the
    other mode's file (``map.pgm`` when ``map.png`` is written, or the other
    way round). That file is returned, to be removed once the new map is in
    place, only when everything proves that it is this map's image as
    :func:`write_map` names it: the YAML at ``yaml_path`` is a map YAML whose
    ``image`` is exactly that file's name (relative, beside the YAML) and whose
    ``mode`` is the one written with that format; the file is a regular file,
    not a symbolic link (a save never writes one); and no other YAML in the
    folder names it. Anything else (another image name, a hand-edited YAML
    naming a shared image) gives None: the file is left alone. The file's
    device and inode are kept to check at removal that it is still that file.

    On a case-insensitive file system (macOS, Windows) ``map.yaml`` may be the
    file saved as ``MAP.yaml``, naming ``MAP.pgm``: a name differing from
    ``map.pgm`` only in case (or Unicode normalisation) counts when the file
    system says it is that file, and the YAML listed under its other spelling
    is the YAML itself, not another one.
    """
    for other_mode, image_format in _IMAGE_FORMAT.items():
        candidate = yaml_path.with_suffix(f".{image_format}")
        if candidate == image:
            continue
        try:
            if candidate.is_symlink() or not candidate.is_file() or not yaml_path.is_file():
                continue
            entries = _yaml_entries(yaml_path)
            if not _names_spelling_of(yaml_path, entries.get("image"), candidate):
                continue
            if entries.get("mode", "trinary") != other_mode:
                continue
            if any(_other_yaml_names(candidate, yaml_path)):
                continue
            found = candidate.lstat()
        except (OSError, ValueError):
            continue
        return _Superseded(candidate, found.st_dev, found.st_ino)
    return None


def _names_spelling_of(yaml_path: Path, named: object, candidate: Path) -> bool:
    """Whether a map YAML's ``image`` value ``named`` names ``candidate`` as the folder reads it.

    The same text; or, on a case-insensitive file system, a spelling differing
    only in case or Unicode normalisation that the file system takes for the
    same entry (``MAP.pgm`` written by a save of ``MAP.yaml``, read back as
    ``map.pgm``). Never through a symbolic link, nor another name of the file.
    """
    if named == candidate.name:
        return True
    if not isinstance(named, str) or not _same_spelling(named, candidate.name):
        return False
    entry = yaml_path.parent / named
    return not entry.is_symlink() and _same_file(entry, candidate)


def _same_spelling(name: str, other: str) -> bool:
    """Whether two file names differ only in case or Unicode normalisation (NFC/NFD).

    Case as a case-insensitive file system matches it: character by character
    (NTFS's upcase table, APFS's folding), Unicode's *simple* case folding,
    which keeps a name's length. ``str.casefold`` is the full folding, by
    which ``straße.pgm`` is ``STRASSE.pgm``: those are two files on Windows
    and macOS, and the hint named the other as "differing in letter case"
    (review 53). Full folding is the coarser, so it is tried first.

    Examples
    --------
    >>> _same_spelling("Map.PGM", "map.pgm"), _same_spelling("STRASSE.pgm", "straße.pgm")
    (True, False)
    >>> _same_spelling("STRAẞE.pgm", "straße.pgm")  # U+1E9E folds simply to ß
    True
    """
    if _folded(name, str.casefold) != _folded(other, str.casefold):
        return False
    return _folded(name, _simple_fold) == _folded(other, _simple_fold)


def _simple_fold(name: str) -> str:
    """``name`` by Unicode's simple case folding (CaseFolding.txt's C and S entries).

    A character ``str.casefold`` folds to one character (a C entry) folds so;
    one it folds to several (an F entry) folds to its lower case where that is
    one other character (the S entries: U+1E9E to ß, Greek capitals with
    prosgegrammeni to their small letters), else stays (ß, İ).
    """
    return "".join(_simple_fold_char(c) for c in name)


def _simple_fold_char(char: str) -> str:
    full = char.casefold()
    if len(full) == 1:
        return full
    lower = char.lower()
    return lower if len(lower) == 1 else char


def _folded(name: str, fold: Callable[[str], str]) -> str:
    return unicodedata.normalize("NFD", fold(unicodedata.normalize("NFD", name)))


def _same_file(path: Path, other: Path) -> bool:
    """``os.path.samefile``, False where either cannot be read."""
    try:
        return os.path.samefile(path, other)
    except (OSError, ValueError):
        return False


def _other_yaml_names(image: Path, yaml_path: Path) -> Iterator[bool]:
    """For each YAML file beside ``yaml_path`` but itself: whether it names ``image``.

    The YAML itself may be listed under another spelling (``MAP.yaml`` for
    ``map.yaml`` on a case-insensitive file system): the same file is skipped.
    """
    for entry in yaml_path.parent.iterdir():
        if entry.suffix.lower() in (".yaml", ".yml") and entry.name != yaml_path.name:
            if _same_spelling(entry.name, yaml_path.name) and _same_file(entry, yaml_path):
                continue
            yield _names_image(entry, image)


def _remove_superseded(old: _Superseded, yaml_path: Path, image: Path) -> None:
    """Remove the previous map's image after a successful save (see :func:`write_map`).

    Only while it is still the file chosen before the save and ``yaml_path``
    still names this save's ``image``: a save of the same map in the other mode
    that finished meanwhile (another process) wrote a new file there (a new
    inode, as every save renames one in place) and a YAML naming it, which
    removing it would have left naming a missing image.
    """
    try:
        now = old.path.lstat()
        if (now.st_dev, now.st_ino) != (old.device, old.inode):
            return
        if not _names_image(yaml_path, image):
            return
        # Asked again now that the new YAML is in place: a YAML skipped before the
        # save as the same file under another spelling (case-insensitive folders)
        # is now the new one; were it a hard link, it is now the old YAML, naming this.
        if any(_other_yaml_names(old.path, yaml_path)):
            return
        old.path.unlink(missing_ok=True)
    except FileNotFoundError:
        return
    except OSError as exc:
        # The new map is saved; failing the call now would suggest it was not.
        warnings.warn(
            f"the map was saved, but its previous image {old.path} could not be removed ({exc})",
            RuntimeWarning,
            stacklevel=3,
        )


def write_map(
    grid: OccupancyGrid, path: str | os.PathLike[str], *, mode: MapMode = "trinary"
) -> Path:
    """Save a grid as a ROS map_server map: ``path`` (YAML) and an image beside it.

    The image is what Nav2's map_saver writes by default: a P5 PGM in
    ``trinary`` mode, an RGBA PNG in ``scale`` mode (where map_server reads
    every opaque pixel as a value and only pixels that are not fully opaque
    as unknown, so a PGM, without alpha, could hold no unknown cell).
    The image's top row is the grid's last row, and the YAML's ``origin`` is
    the grid's origin ``[x, y, yaw]`` (the outer corner of cell (0, 0), as
    :func:`read_map` reads it; Nav2's costmaps ignore a non-zero yaw).

    An existing image is only replaced when it is the image of the map being
    replaced (the existing YAML at ``path`` names it): a save never writes over
    another map's image. Both files are written to temporary files in the same
    folder first and then renamed over the targets (``os.replace``), so a
    failure while writing (a full disk, an interrupt) leaves an existing map as
    it was. The image is
    renamed first; if the YAML's rename then fails (a permission error), the
    old image is put back. Only a crash between the two renames (microseconds)
    could pair the new image with the old YAML.

    Saving over a map in the other mode (``map.yaml`` written in trinary mode
    with ``map.pgm``, then in scale mode with ``map.png``) removes the previous
    image once the new map is in place, so that no orphan is left behind to
    block a later save. Only a file this function could have written for that
    map is removed: the replaced YAML names it exactly ``<stem>.pgm`` (mode
    ``trinary``) or ``<stem>.png`` (mode ``scale``), it is a regular file (not
    a symbolic link) and no other YAML in the folder names it. Any other file
    is never removed, nor is that one if, by the time this save ends, another
    save of the map has replaced it or the YAML; if the removal fails, a
    ``RuntimeWarning`` says so and the new map stays saved. Saves in threads
    of one process take turns from that choice to the removal (their writes
    included), so that overlapping saves of a map in the two modes leave one
    map and its image only; saves from other processes are not waited for.

    Parameters
    ----------
    grid : OccupancyGrid
        The map to save.
    path : str or path-like
        YAML file to write; the image is the same name with suffix ``.pgm``
        (trinary) or ``.png`` (scale): ``map.yaml`` → ``map.pgm``, stored
        relative to the YAML.
    mode : {"trinary", "scale"}
        ``trinary`` writes map_saver's pixels (0 occupied, 254 free, 205
        unknown, or a mid grey when 205 would not be unknown under the grid's
        thresholds, and 255 for free when 254 would not be free, under a
        ``free_thresh`` of at most 1/255). ``scale`` writes opaque grey
        ``round(255 * (1 - p))`` (moved across a threshold where rounding
        would change the cell's class) and the unknown cells transparent:
        those whose log-odds are what :func:`read_map` gives unknown pixels
        (0, never observed, when the thresholds class p = 0.5 as unknown;
        else the middle of the band). Other cells between the thresholds are
        in-between values to map_server. Either way loading the files with
        :func:`read_map` gives back the same occupied/free/unknown classes
        (in scale mode also the unknown cells' log-odds exactly and the
        in-between cells' probabilities to half a grey level, or, where
        rounding would cross a threshold, as the nearest grey level
        map_server reads as unknown; occupied and
        free cells come back certain, as map_server's 100 and 0), and
        map_server reads occupied, free and unknown cells as such.

    Returns
    -------
    Path
        The image file written.

    Raises
    ------
    TypeError
        ``grid`` is not an OccupancyGrid, ``mode`` not a str, ``path`` not a
        str or path-like.
    ValueError
        Unknown ``mode``; a ``path`` ending in the image's suffix (in any
        case: the image would overwrite the YAML) or in another image suffix
        (``.png``, ``.jpg``, ...: the YAML would overwrite an image); an image name that
        the YAML could not give back when read; the YAML or the image path is
        a directory or a loop of symbolic links; the image path holds a file
        that the existing YAML at ``path`` does not name (another map's
        image); unknown cells to write while the grid's thresholds leave no
        8-bit grey level between them (a band narrower than 1/255). Nothing
        is written then.
    ImportError
        ``mode="scale"`` without Pillow installed (it writes the PNG); nothing
        is written.
    FileNotFoundError
        The folder of ``path`` does not exist, or is (or lies below) a loop of
        symbolic links (``strerror`` ``"no such folder"``, the loop named after
        it; the folder as ``filename``). Nothing is written.
    OSError
        Writing fails (disk full, permissions, ...): the temporary files are
        removed and an existing map is left as it was.

    Notes
    -----
    A map received as a message (:func:`grid_from_msg`) is saved by its
    grid's classes, which are not map_saver's. map_saver classes the
    message's values themselves, with ``<=`` and ``>=`` against its
    thresholds rounded to whole percents: a value up to
    ``rint(100 * free_thresh)`` is free, one from
    ``rint(100 * occupied_thresh)`` on occupied (Nav2's defaults 0.25 and
    0.65, ROS 1's 25 and 65). The grid classes ``p = value / 100`` strictly
    against its own thresholds (0.196 and 0.65): a 65 is saved occupied by
    map_saver and unknown here, and 20..25 free there and unknown here.
    Only messages with values other than 0, 100 and -1 (Cartographer's, say)
    hold such values. For map_saver's classes, save the grid with thresholds
    half a percent inside its: ``OccupancyGrid(grid.logodds,
    resolution=grid.resolution, origin=grid.origin, occupied_thresh=0.645,
    free_thresh=0.255)``.

    Examples
    --------
    >>> import tempfile
    >>> grid = OccupancyGrid.from_occupancy(np.array([[True, False]]), resolution=0.5)
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     image = write_map(grid, Path(folder) / "room.yaml")
    ...     again = read_map(Path(folder) / "room.yaml")
    ...     print(image.name, again.occupied().tolist())
    ...     print((Path(folder) / "room.yaml").read_text(), end="")
    room.pgm [[True, False]]
    image: room.pgm
    mode: trinary
    resolution: 0.5
    origin: [0.0, 0.0, 0.0]
    negate: 0
    occupied_thresh: 0.65
    free_thresh: 0.196
    """
    if not isinstance(grid, OccupancyGrid):
        raise TypeError(f"grid must be an OccupancyGrid, got {type(grid).__name__}")
    # Checked and written as the plain str: an np.str_ (or any str subclass) went into
    # the YAML, whose safe dumper raised its own RepresenterError for it.
    mode = cast(MapMode, as_text(mode, "mode"))  # checked next
    if mode not in _WRITE_MODES:
        raise ValueError(f"mode must be 'trinary' or 'scale', got {mode!r}")
    # Its messages name the folder: escaped where it is not UTF-8, as read_map's
    # (ffd685d; review 54, FRESH2).
    with _printable_errors():
        image_format = _IMAGE_FORMAT[mode]
        yaml_path = as_path(path, "path")
        image = _image_path(yaml_path, image_format)
        o = grid.origin
        meta = MapMetadata(
            image,
            grid.resolution,
            (o.x, o.y, o.theta),
            False,
            grid.occupied_thresh,
            grid.free_thresh,
            mode,
        )
        text = map_yaml_text(meta, image.name)
        pixels = _map_image(grid, mode)  # image rows run top down
        data = pgm_bytes(pixels) if image_format == "pgm" else png_bytes(pixels)
        # Decided before the YAML that names it is replaced, and removed after; all three
        # under the lock of the renames, so that another thread's save of this map in
        # the other mode comes wholly before or after (else both could decide before
        # either renamed, and leave the other mode's image beside the map, a "foreign"
        # image refusing later saves; or one's removal could unlink the other's new
        # image renamed between its check and its unlink). Other processes are not
        # waited for: _remove_superseded checks the file is still the one chosen.
        with RENAME_LOCK:
            # The image checked again (the lock is re-entrant): another thread may have
            # saved a map of another YAML naming the same image ("map" and "map.yaml"
            # both write map.pgm) since the first check; both would save, and one
            # map would read the other's image.
            _image_path(yaml_path, image_format)
            superseded = _superseded_image(yaml_path, image)
            _replace_all([(image, data), (yaml_path, text.encode("utf-8"))])
            if superseded is not None:
                _remove_superseded(superseded, yaml_path, image)
        return image
