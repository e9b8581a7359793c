"""MovingAI grid-pathfinding benchmark files: ``.map`` grids and ``.scen`` problems.

The format of N. Sturtevant, "Benchmarks for Grid-Based Pathfinding", IEEE
Trans. on Computational Intelligence and AI in Games 4(2):144-148, 2012
(movingai.com/benchmarks/formats.html), the standard test set of grid
planners: every map comes with problems and their optimal 8-connected path
lengths (straight moves 1, diagonal moves sqrt(2), no corner cutting).
"""

from __future__ import annotations

import codecs
import math
import numbers
import os
import re
from collections.abc import Iterable
from dataclasses import dataclass
from itertools import chain
from pathlib import Path
from typing import TYPE_CHECKING, Any, BinaryIO, Protocol

import numpy as np
from numpy.typing import ArrayLike, NDArray

from navkit._shared.counts import bytes_text, counted
from navkit._shared.dunders import bounded_repr
from navkit._shared.frozen import frozen_setattr, reduce_record, restore_read_only
from navkit._shared.types import BoolArray, FloatArray, IntArray
from navkit._shared.validation import (
    as_array,
    as_float_array,
    as_sequence,
    holds_bool,
    refuse_masked,
)
from navkit.mapping.io._paths import as_path, open_regular

__all__ = ["MovingAIMap", "MovingAIScenarios", "read_movingai_map", "read_movingai_scenarios"]

#: The terrain characters of the format: passable (``.``, ``G``), out of bounds
#: (``@``, ``O``), trees (``T``), swamp (``S``: passable from regular terrain) and
#: water (``W``: traversable, but not from regular terrain).
TERRAIN = ".G@OTSW"
#: The characters whose cells a unit on land can enter: those of the benchmark's paths.
PASSABLE = ".GS"
#: Most cells of a map a scenario may name: what navkit's grid planners take (int32
#: cell indices).
MAX_CELLS = 2**31 - 1
#: Most cells of a map itself (:class:`MovingAIMap`, :func:`read_movingai_map`):
#: 8192 x 8192, larger than any map of the benchmark. Its terrain takes 4 bytes a
#: cell (``<U1``), a file's reading about 13 at its peak and :attr:`MovingAIMap.costs`
#: 8 more: 832 MiB and 512 MiB here, where 2**31 - 1 cells needed 26 and 16 GiB.
MAX_MAP_CELLS = 2**26
#: Longest header or scenario line read, in bytes: a binary file is refused at once.
LINE_MAX = 4096
# Lookup tables by character code: whether it is terrain, whether it is passable.
_IS_TERRAIN = np.zeros(256, dtype=bool)
_IS_TERRAIN[list(TERRAIN.encode("ascii"))] = True
_IS_PASSABLE = np.zeros(256, dtype=bool)
_IS_PASSABLE[list(PASSABLE.encode("ascii"))] = True
# Bytes a read of a map's rows past its first read takes (see _read_on).
_CHUNK = 1 << 20
# The end of a line: either byte (a CR-only file's lines end in CR alone).
_LINE_END = re.compile(rb"[\r\n]")
# A C double as HOG2's stream reads it, without a sign: float() also took "1_0",
# "-0.0" and surrounding blanks.
_LENGTH = re.compile(r"(?:[0-9]+(?:\.[0-9]*)?|\.[0-9]+)(?:[eE][+-]?[0-9]+)?")


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class MovingAIMap:
    """The terrain of a MovingAI ``.map`` file, one character per cell.

    Parameters
    ----------
    terrain : array_like of str, shape (rows, cols)
        One character of ``".G@OTSW"`` per cell, row 0 the top row of the file
        (the format's y = 0) and column 0 its left end (x = 0): a 2-D array of
        one-character strings, or a sequence of equally long row strings.
        Stored as a read-only ``<U1`` copy (4 bytes a cell). At least one
        cell, at most ``2**26`` (8192 x 8192).

    Raises
    ------
    TypeError
        ``terrain`` not strings.
    ValueError
        A character outside ``".G@OTSW"`` (named with its cell), rows of
        different lengths, not two dimensions, no cells or too many.

    Notes
    -----
    Row 0 is the file's top row, as the ``.scen`` files' cells expect: the
    grid planners take :attr:`costs` and those cells as they are. An
    :class:`~navkit.mapping.OccupancyGrid` puts row 0 at the lowest y (as an
    image map is read): a grid made from these rows shows the file's picture
    upside down unless the rows are flipped (``np.flipud``, and cell
    ``(row, col)`` becomes ``(rows - 1 - row, col)``).

    Examples
    --------
    >>> grid = MovingAIMap(["..@", "T.."])
    >>> grid.passable
    array([[ True,  True, False],
           [False,  True,  True]])
    >>> grid.costs[0]
    array([ 1.,  1., inf])
    """

    terrain: NDArray[np.str_]

    if TYPE_CHECKING:
        # The generated ``__init__`` takes array_like (``__post_init__`` converts it).
        def __init__(self, terrain: ArrayLike) -> None: ...

    def __post_init__(self) -> None:
        # A UCS-4 character is its code point: a uint32 copy viewed as <U1 is the
        # str array (an astype from bytes ("S1") took 56 ms a megacell).
        terrain = _terrain_codes(self.terrain).astype(np.uint32).view(np.dtype("U1"))
        terrain.flags.writeable = False
        object.__setattr__(self, "terrain", terrain)

    @property
    def passable(self) -> BoolArray:
        """True on the cells a unit on land can enter, shape (rows, cols).

        ``.``, ``G`` and ``S`` (swamp): the cells of the benchmark's optimal
        paths. Water (``W``), traversable only from other water, is not
        passable here. A new array at each access.

        Examples
        --------
        >>> MovingAIMap(["..@", "T.S"]).passable
        array([[ True,  True, False],
               [False,  True,  True]])
        """
        passable: BoolArray = _IS_PASSABLE[self.terrain.view(np.uint32) & 255]
        return passable

    @property
    def costs(self) -> FloatArray:
        """Cost grid for the grid planners, shape (rows, cols): 1 where passable, else inf.

        For :class:`~navkit.planning.AStarPlanner` and the other grid
        planners: with their default ``corner_cutting=False`` the path costs
        are the ``.scen`` files' optimal lengths, in cell lengths. A new array
        at each access (change it freely: to add obstacles, say).

        Examples
        --------
        >>> MovingAIMap(["..@"]).costs
        array([[ 1.,  1., inf]])
        """
        return np.where(self.passable, 1.0, np.inf)

    @property
    def shape(self) -> tuple[int, int]:
        """``(rows, cols)``: the file's ``(height, width)``.

        Examples
        --------
        >>> MovingAIMap(["..@", "T.."]).shape
        (2, 3)
        """
        rows, cols = self.terrain.shape
        return rows, cols

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, ("terrain",))

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from a pickle's field values, the arrays read-only again."""
        restore_read_only(self, state, ("terrain",))

    def __repr__(self) -> str:
        rows, cols = self.shape
        passable = int(self.passable.sum())
        return f"{type(self).__name__}(<{rows} x {cols} terrain, {passable} passable>)"


def _terrain_codes(terrain: Any) -> NDArray[np.uint8]:
    """``terrain`` as a C-contiguous (rows, cols) uint8 array of ASCII codes, checked."""
    refuse_masked(terrain, "terrain")
    if isinstance(terrain, str):
        raise TypeError(
            "terrain must be rows of characters (a 2-D array or a list of str), got str"
        )
    if issubclass(type(terrain), np.ndarray):
        arr = terrain
    else:
        items = as_sequence(terrain, "terrain")
        if not items:
            raise ValueError("terrain must have at least one cell, got an empty sequence")
        if all(isinstance(row, str) for row in items):
            widths = {len(row) for row in items}
            if len(widths) != 1:
                raise ValueError(f"terrain rows must be equally long, got lengths {sorted(widths)}")
            arr = np.array([list(row) for row in items], dtype="U1").reshape(len(items), -1)
        else:
            try:
                arr = np.asarray(items)
            except (TypeError, ValueError) as exc:
                raise ValueError(
                    f"terrain must be a (rows, cols) array of characters: {exc}"
                ) from None
            if arr.ndim == 2:
                # NumPy makes str of numbers and bytes beside str: 1 became the cell '1'.
                _refuse_not_str(set(map(type, chain.from_iterable(items))))
    if arr.dtype.kind == "O" and arr.size:
        _refuse_not_str(set(map(type, arr.flat)))
        arr = arr.astype(str)
    if arr.dtype.kind != "U":
        raise TypeError(f"terrain must hold one-character str cells, got dtype {arr.dtype}")
    if arr.ndim != 2:
        raise ValueError(f"terrain must have 2 dimensions (rows, cols), got shape {arr.shape}")
    if arr.size == 0:
        raise ValueError(f"terrain must have at least one cell, got shape {arr.shape}")
    if arr.size > MAX_MAP_CELLS:
        raise ValueError(
            f"terrain must have at most 2**26 = {MAX_MAP_CELLS} cells (256 MiB of <U1), "
            f"got {arr.size} cells ({bytes_text(4.0 * arr.size)})"
        )
    as_u1 = np.ascontiguousarray(arr, dtype="U1")
    if arr.dtype.itemsize > 4 and not np.array_equal(as_u1, arr):
        raise ValueError("terrain must hold one character per cell, got a longer string")
    wide = as_u1.view(np.uint32)
    # Narrowed first, looked up once: no uint32 temporaries of the grid's size.
    codes = wide.astype(np.uint8)
    bad = ~_IS_TERRAIN[codes]
    if wide.max() > 255:
        bad |= wide > 255
    if bad.any():
        row, col = (int(i) for i in np.argwhere(bad)[0])
        raise ValueError(
            f"terrain[{row}, {col}] is {str(as_u1[row, col])!r}, not a MovingAI terrain "
            f"character (one of {TERRAIN!r}); {counted(int(bad.sum()), 'such cell')}"
        )
    return codes


def _refuse_not_str(types: set[type]) -> None:
    """Refuse terrain cells of any type but str (``types``: those of the cells)."""
    for kind in types:
        if not issubclass(kind, str):
            raise TypeError(f"terrain must hold str cells, got an element of type {kind.__name__}")


@frozen_setattr
@dataclass(frozen=True, slots=True, eq=False)
class MovingAIScenarios:
    """The problems of a MovingAI ``.scen`` file, one per row of each array.

    Cells are ``(row, col)``, the file's ``(y, x)``: pass them to the grid
    planners as they are.

    Parameters
    ----------
    buckets : array_like of int, shape (k,)
        Each problem's bucket (problems grouped by length), >= 0.
    map_names : sequence of str, length k
        The map file each problem is on, as written in the file.
    map_shapes : array_like of int, shape (k, 2)
        ``(rows, cols)`` of that map (the file's height and width), >= 1.
    start_cells, goal_cells : array_like of int, shape (k, 2)
        ``(row, col)`` of start and goal, inside the map shape.
    optimal_lengths : array_like of float, shape (k,)
        The optimal 8-connected path length (straight moves 1, diagonal moves
        sqrt(2), no corner cutting), in cell lengths, finite and >= 0. The
        files print 8 decimals: compare to about 1e-6 relative.

    Raises
    ------
    TypeError
        Arrays that are not integers (or, for the lengths, real numbers); map
        names that are not strings.
    ValueError
        Wrong shapes or lengths, negative values, empty map names, a map shape
        of more than ``2**31 - 1`` cells, cells outside their map, non-finite
        lengths.

    Notes
    -----
    The arrays are stored as read-only int64 and float64 copies (the
    caller's arrays are neither kept nor frozen).

    Examples
    --------
    >>> problems = MovingAIScenarios([0], ["arena.map"], [[49, 49]], [[1, 2]], [[3, 2]], [2.0])
    >>> len(problems), problems.start_cells[0].tolist(), problems.optimal_lengths[0]
    (1, [1, 2], np.float64(2.0))
    """

    buckets: IntArray
    map_names: tuple[str, ...]
    map_shapes: IntArray
    start_cells: IntArray
    goal_cells: IntArray
    optimal_lengths: FloatArray

    if TYPE_CHECKING:
        # The generated ``__init__`` takes array_likes (``__post_init__`` converts them).
        def __init__(
            self,
            buckets: ArrayLike,
            map_names: Iterable[str],
            map_shapes: ArrayLike,
            start_cells: ArrayLike,
            goal_cells: ArrayLike,
            optimal_lengths: ArrayLike,
        ) -> None: ...

    def __post_init__(self) -> None:
        names = as_sequence(self.map_names, "map_names")
        for i, name in enumerate(names):
            if not isinstance(name, str):
                raise TypeError(f"map_names must hold str, got {type(name).__name__}")
            if not name:
                raise ValueError(f"map_names[{i}] is empty: it must name the problem's map")
        # Plain str (str.__str__ copies a subclass's value): np.str_ names printed as
        # np.str_('a.map') in the record's repr.
        names = tuple(str.__str__(name) for name in names)
        k = len(names)
        buckets = _int_array(self.buckets, "buckets", (k,), low=0)
        shapes = _int_array(self.map_shapes, "map_shapes", (k, 2), low=1)
        # No map of more cells can be read (MovingAIMap, read_movingai_map).
        huge = np.flatnonzero(shapes[:, 0] > MAX_CELLS // shapes[:, 1])
        if huge.size:
            i = int(huge[0])
            raise ValueError(
                f"map_shapes[{i}] {tuple(shapes[i].tolist())} has more than {MAX_CELLS} cells"
            )
        starts = _int_array(self.start_cells, "start_cells", (k, 2), low=0)
        goals = _int_array(self.goal_cells, "goal_cells", (k, 2), low=0)
        for cells, name in ((starts, "start_cells"), (goals, "goal_cells")):
            outside = np.flatnonzero(np.any(cells >= shapes, axis=1))
            if outside.size:
                i = int(outside[0])
                raise ValueError(
                    f"{name}[{i}] {tuple(cells[i].tolist())} is outside its map of shape "
                    f"{tuple(shapes[i].tolist())} (cells are (row, col))"
                )
        lengths = np.array(
            as_float_array(self.optimal_lengths, "optimal_lengths", shape=(k,), finite=False),
            dtype=np.float64,
            copy=True,
        )
        bad = np.flatnonzero(~(np.isfinite(lengths) & (lengths >= 0.0)))
        if bad.size:
            i = int(bad[0])
            raise ValueError(f"optimal_lengths[{i}] must be finite and >= 0, got {lengths[i]}")
        lengths += 0.0  # -0.0 becomes 0.0
        object.__setattr__(self, "map_names", names)
        for name, array in (
            ("buckets", buckets), ("map_shapes", shapes), ("start_cells", starts),
            ("goal_cells", goals), ("optimal_lengths", lengths),
        ):  # fmt: skip
            array.flags.writeable = False
            object.__setattr__(self, name, array)

    def __len__(self) -> int:
        return len(self.map_names)

    __repr__ = bounded_repr

    def __reduce__(self) -> tuple[Any, ...]:
        """Copy and pickle support: the arrays read-only again, also in subclasses' copies."""
        return reduce_record(self, _SCENARIO_ARRAYS)

    def __setstate__(self, state: list[Any]) -> None:
        """Restore from a pickle's field values, the arrays read-only again."""
        restore_read_only(self, state, _SCENARIO_ARRAYS)


_SCENARIO_ARRAYS = ("buckets", "map_shapes", "start_cells", "goal_cells", "optimal_lengths")


def _int_array(value: Any, name: str, shape: tuple[int, ...], *, low: int) -> IntArray:
    """``value`` as an int64 copy of ``shape`` with every entry >= ``low``."""
    if isinstance(value, (list, tuple)) and holds_bool(value):
        raise TypeError(f"{name} must hold integers, got an element of type bool")
    arr = as_array(value, name)
    if arr.dtype.kind == "f" and arr.size == 0 and not issubclass(type(value), np.ndarray):
        arr = arr.astype(np.int64)  # an empty list
    elif arr.dtype.kind == "f" and not issubclass(type(value), np.ndarray):
        # NumPy makes float64 of integers beyond int64 and of int8 mixed with uint64.
        items = np.array(value, dtype=object)
        if items.shape == arr.shape and all(_is_int(item) for item in items.flat):
            arr = items
    if arr.dtype.kind == "O" and all(_is_int(item) for item in arr.flat):
        pass  # Python ints, perhaps beyond 64 bits: refused by range below
    elif arr.dtype.kind not in "iu":
        raise TypeError(f"{name} must hold integers, got dtype {arr.dtype}")
    if arr.shape == (0,) and shape[0] == 0:
        arr = arr.reshape(shape)  # no problems: [] is a (0, 2) table too
    if arr.shape != shape:
        raise ValueError(f"{name} must have shape {shape}, got {arr.shape}")
    if arr.size:
        # NumPy's reductions on integer arrays; Python's on object arrays of ints.
        if arr.dtype.kind == "O":
            smallest, largest = min(arr.flat), max(arr.flat)
        else:
            smallest, largest = arr.min(), arr.max()
        if smallest < low:
            raise ValueError(f"{name} must be >= {low}, got {int(smallest)}")
        if largest > _INT64_MAX:
            raise ValueError(f"{name} must be at most {_INT64_MAX}, got {int(largest)}")
    return np.array(arr, dtype=np.int64, copy=True)


def _is_int(item: object) -> bool:
    return isinstance(item, numbers.Integral) and not isinstance(item, (bool, np.bool_))


_INT64_MAX = int(np.iinfo(np.int64).max)


def read_movingai_map(path: str | os.PathLike[str]) -> MovingAIMap:
    """Read a MovingAI ``.map`` file.

    The header (``type octile``, ``height H``, ``width W``, in any order) is
    followed by a ``map`` line and H rows of W terrain characters; blank
    lines after them, and any number of spaces or tabs after a row, are
    ignored (as HOG2, the benchmark's own code, skips them: a map padded to
    a fixed width reads as its rows); line ends may be ``\\n``,
    ``\\r\\n`` or, in a file whose first line ends so, ``\\r`` alone (classic
    Mac OS: HOG2 reads those too, its ``fscanf`` skipping any white space
    between rows), and a UTF-8 byte-order mark may start the file.

    Parameters
    ----------
    path : str or path-like
        The ``.map`` file.

    Returns
    -------
    MovingAIMap
        The terrain, with its ``passable`` cells and a ``costs`` grid for the
        grid planners.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` not a str or path-like.
    ValueError
        ``path`` not a regular file, or a malformed file (named, with the line
        and the problem): a header key missing, repeated or unknown, a type
        other than ``octile``, a size that is not a positive integer or
        exceeds ``2**26`` cells, too few or too many rows, a row of the
        wrong length, a character that is not terrain.
    OSError
        The operating system refuses to read the file.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "tiny.map"
    ...     _ = path.write_text("type octile\\nheight 2\\nwidth 3\\nmap\\n..@\\nT..\\n")
    ...     grid = read_movingai_map(path)
    >>> grid.shape, grid.passable.sum()
    ((2, 3), np.int64(4))
    """
    file = as_path(path, "path")
    with open_regular(file, "MovingAI map") as opened:
        fh = _lines(opened)
        rows, cols, number = _map_header(fh, file)
        # Rows of cols characters and a line end each, then only blank lines; never
        # more than the file holds: read(n) allocates n bytes first, and a header of
        # 40 bytes may claim 2**26 cells.
        remaining = max(os.fstat(fh.fileno()).st_size - fh.tell(), 0)
        body = fh.read(min(rows * (cols + 2) + LINE_MAX, remaining))
        sizes: dict[int, int] = {}
        if body.count(b"\n") < rows:
            body, sizes = _read_on(fh, body, rows, cols, remaining - len(body))
        # Blank lines after the rows are ignored however many there are: read past
        # in bounded chunks, kept only if something else follows.
        extra = fh.read(LINE_MAX)
        while extra and not extra.strip():
            extra = fh.read(1 << 20)
    lines = body.split(b"\n")
    while lines and not lines[-1].strip():
        lines.pop()
    if extra or len(lines) > rows:
        raise ValueError(
            f"{file}: more than the {counted(rows, 'row')} of the header's height after "
            "the 'map' line"
        )
    if len(lines) < rows:
        raise ValueError(
            f"{file}: {counted(len(lines), 'row')} after the 'map' line, the header's "
            f"height is {rows}"
        )
    for i, line in enumerate(lines):
        # A CR line end, or blanks after the row (HOG2 skips them).
        line = lines[i] = line.rstrip(b" \t\r")
        if len(line) != cols:
            raise ValueError(
                f"{file}:{number + 1 + i}: a row of "
                f"{counted(sizes.get(i, len(line)), 'character')}, the header's width is {cols}"
            )
    codes = np.frombuffer(b"".join(lines), dtype=np.uint8).reshape(rows, cols)
    bad = ~_IS_TERRAIN[codes]
    if bad.any():
        row, col = (int(i) for i in np.argwhere(bad)[0])
        code = int(codes[row, col])
        char = repr(chr(code)) if 32 <= code < 127 else f"byte 0x{code:02x}"
        raise ValueError(
            f"{file}:{number + 1 + row}: {char} at column {col} is not a MovingAI terrain "
            f"character (one of {TERRAIN!r})"
        )
    return MovingAIMap(codes.astype(np.uint32).view(np.dtype("U1")))


def _read_on(
    fh: _Lines, body: bytes, rows: int, cols: int, left: int
) -> tuple[bytes, dict[int, int]]:
    """``body`` and as much more of ``fh`` as holds ``rows`` line ends, blanks after rows dropped.

    ``body`` was read for rows of ``cols`` characters and a line end each:
    rows followed by blanks (any number: HOG2's ``fscanf`` skips them; a map
    padded to a fixed width) take more, and the rows past ``body`` were taken
    for lines after the last row. The rest is read in chunks, each line kept
    as the caller would see it after stripping its blanks; one longer than
    ``cols`` is refused by the caller for its length alone, so it is kept as
    ``cols + 1`` placeholder bytes and its length returned. Memory stays the
    first read's (rows of up to ``cols + 1`` bytes) and a chunk; no read asks
    for more than the ``left`` bytes the file holds after ``body`` (a read
    allocates what it asks for first).

    Returns
    -------
    bytes, dict
        The lines joined by LF (after the ``rows``-th line end, the rest of the
        last chunk as read), and the length of each line kept as a
        placeholder, by its index.
    """
    kept: list[bytes] = []
    sizes: dict[int, int] = {}
    # The line so far: its text up to its last non-blank, the blanks after that
    # (their count, and the first cols + 1 of them: more never fit in a row), and,
    # once it is longer than a row, that length instead of the text.
    head, blanks, run, size = b"", b"", 0, -1
    data = body
    while True:
        parts = data.split(b"\n")
        for k, part in enumerate(parts):
            core = part.rstrip(b" \t\r")
            if core:
                if size < 0 and len(head) + run + len(core) <= cols:
                    head += blanks + core
                else:
                    size = (len(head) if size < 0 else size) + run + len(core)
                    head = b""
                run = len(part) - len(core)
                blanks = part[len(core) : len(core) + cols + 1]
            else:
                run += len(part)
                blanks += part[: max(cols + 1 - len(blanks), 0)]
            if k == len(parts) - 1:
                break  # the line goes on in the next chunk
            if size >= 0:
                sizes[len(kept)] = size
            kept.append(head if size < 0 else b"#" * (cols + 1))
            head, blanks, run, size = b"", b"", 0, -1
            if len(kept) >= rows:
                return b"\n".join([*kept, *parts[k + 1 :]]), sizes
        data = fh.read(min(_CHUNK, left)) if left > 0 else b""
        if not data:
            break
        left -= len(data)
    if size >= 0:
        sizes[len(kept)] = size
    kept.append(head + blanks if size < 0 else b"#" * (cols + 1))
    return b"\n".join(kept), sizes


class _Lines(Protocol):
    """What the readers take of a file: a :class:`BinaryIO` or a :class:`_CRLines`."""

    def read(self, size: int, /) -> bytes: ...
    def readline(self, size: int, /) -> bytes: ...
    def tell(self) -> int: ...
    def fileno(self) -> int: ...


class _CRLines:
    """A file whose lines end in CR alone, read as if they ended in LF.

    One byte for one, so offsets, sizes (``fstat``) and line numbers stay the
    file's. Any CR or LF ends a line (a stray LF too, as a CR did in an LF file).
    """

    __slots__ = ("_fh",)

    def __init__(self, fh: BinaryIO) -> None:
        self._fh = fh

    def read(self, size: int, /) -> bytes:
        return self._fh.read(size).replace(b"\r", b"\n")

    def readline(self, size: int, /) -> bytes:
        # Binary files split lines at LF only: read ahead and step back to the end.
        start = self._fh.tell()
        chunk = self._fh.read(size)
        end = _LINE_END.search(chunk)
        if end is not None:
            chunk = chunk[: end.end()]
            self._fh.seek(start + end.end())
        return chunk.replace(b"\r", b"\n")

    def tell(self) -> int:
        return self._fh.tell()

    def fileno(self) -> int:
        return self._fh.fileno()


def _lines(fh: BinaryIO) -> _Lines:
    """``fh`` (at its start), read through :class:`_CRLines` when its first line ends in CR alone.

    HOG2's readers (``fscanf`` and ``>>``) take any white space for a line end,
    so a classic Mac OS file is a benchmark file to them; a CR-only file was
    read here as one line of the whole file and refused for its first "line".
    """
    head = fh.read(LINE_MAX + 2)
    fh.seek(0)
    end = _LINE_END.search(head)
    # (A CR as the last byte read ends a line too long to be read either way.)
    if end is not None and end.group() == b"\r" and head[end.end() : end.end() + 1] != b"\n":
        return _CRLines(fh)
    return fh


def _map_header(fh: _Lines, file: Path) -> tuple[int, int, int]:
    """Read a ``.map`` header up to its ``map`` line: (rows, cols, that line's number)."""
    header: dict[str, str] = {}
    number = 0
    while True:
        raw = fh.readline(LINE_MAX + 1)
        number += 1
        if number == 1:
            raw = raw.removeprefix(codecs.BOM_UTF8)  # as Windows Notepad writes
        if not raw:
            raise ValueError(f"{file}: no 'map' line: not a MovingAI map")
        text = _ascii_line(raw, file, number, "map")
        words = text.split()
        if not words:
            continue
        if words == ["map"]:
            break
        if len(words) != 2 or words[0] not in ("type", "height", "width"):
            raise ValueError(
                f"{file}:{number}: {text.strip()[:80]!r} is not a header line ('type octile', "
                "'height H', 'width W' or 'map')"
            )
        if words[0] in header:
            raise ValueError(f"{file}:{number}: a second {words[0]!r} line")
        header[words[0]] = words[1]
    missing = [key for key in ("type", "height", "width") if key not in header]
    if missing:
        raise ValueError(f"{file}: no {missing[0]!r} line before the 'map' line")
    if header["type"] != "octile":
        raise ValueError(f"{file}: type {header['type']!r}, expected 'octile'")
    rows, cols = (_size(header[key], key, file) for key in ("height", "width"))
    cells = rows * cols
    if cells > MAX_MAP_CELLS:
        # Sizes of hundreds of digits fit a header line: 4.0 * cells raised OverflowError.
        size = 4.0 * cells if cells.bit_length() < 1000 else math.inf
        raise ValueError(
            f"{file}: {_digits(rows)} x {_digits(cols)} cells, more than 2**26 = "
            f"{MAX_MAP_CELLS} ({bytes_text(size)} of <U1 terrain; 256 MiB at most)"
        )
    return rows, cols, number


def _digits(n: int) -> str:
    """``n`` for a message: written out up to 40 digits, else its first digits and length."""
    text = str(n)
    return text if len(text) <= 40 else f"{text[:6]}... ({len(text)} digits)"


def _ascii_line(raw: bytes, file: Path, number: int, kind: str) -> str:
    """A header or scenario line as text: refused if too long or not ASCII."""
    if len(raw) > LINE_MAX:
        raise ValueError(
            f"{file}:{number}: a line longer than {LINE_MAX} bytes: not a MovingAI {kind} file"
        )
    try:
        return raw.decode("ascii")
    except UnicodeDecodeError:
        raise ValueError(
            f"{file}:{number}: bytes that are not ASCII: not a MovingAI {kind} file"
        ) from None


def _size(text: str, key: str, file: Path) -> int:
    if not (text.isascii() and text.isdigit()) or int(text) == 0:
        raise ValueError(f"{file}: {key} {text!r} is not a positive integer")
    return int(text)


def read_movingai_scenarios(path: str | os.PathLike[str]) -> MovingAIScenarios:
    """Read a MovingAI ``.scen`` file (version 1).

    After a ``version 1`` line, one problem per line: ``bucket map width
    height start_x start_y goal_x goal_y optimal_length``, separated by tabs
    (or, where a line has no tabs, spaces). x is the column and y the row:
    the cells are returned as ``(row, col)`` = ``(y, x)``. Blank lines, and
    spaces or tabs after a line's last field, are ignored; line ends may be
    ``\\n``, ``\\r\\n`` or, in a file whose first line ends so, ``\\r`` alone
    (classic Mac OS: HOG2's stream reads take any white space between fields);
    a UTF-8 byte-order mark may start the file. The map names are kept as written
    (often relative to the ``.scen`` file's folder, or as ``maps/<set>/<name>``).

    The format declares no count of problems, so a file cut at a line end
    reads as its first problems. A file cut inside its last line is refused:
    inside a field before the length, as a line without 9 fields; inside the
    length (nothing follows it), when that line has no line end and its
    length has fewer decimals than the file prints every other length with
    (the benchmark's files: 8). A file of lengths printed with varying
    decimals (``%g``), or of one problem, gives a length cut there as read.

    Parameters
    ----------
    path : str or path-like
        The ``.scen`` file.

    Returns
    -------
    MovingAIScenarios
        The problems in file order.

    Raises
    ------
    FileNotFoundError
        ``path`` does not exist, or is a loop of symbolic links.
    TypeError
        ``path`` not a str or path-like.
    ValueError
        ``path`` not a regular file, or a malformed file (named, with the line
        and the problem): no ``version 1`` line, a line without 9 fields or
        with a control character, an empty map name, a field that is not a
        non-negative integer of ASCII digits (or, for the length, a finite
        decimal number without sign), a bucket beyond int64, a map of more
        than ``2**31 - 1`` cells, a cell outside its map's width and height;
        a last line without its line end whose length has fewer decimals
        than every other line's (a file cut inside it).
    OSError
        The operating system refuses to read the file.

    Examples
    --------
    >>> import tempfile
    >>> from pathlib import Path
    >>> with tempfile.TemporaryDirectory() as folder:
    ...     path = Path(folder) / "tiny.map.scen"
    ...     _ = path.write_text("version 1\\n0\\ttiny.map\\t3\\t2\\t0\\t0\\t2\\t1\\t2.41421356\\n")
    ...     problems = read_movingai_scenarios(path)
    >>> problems.start_cells.tolist(), problems.goal_cells.tolist(), problems.map_shapes.tolist()
    ([[0, 0]], [[1, 2]], [[2, 3]])
    """
    file = as_path(path, "path")
    ints: list[tuple[int, ...]] = []
    names: list[str] = []
    lengths: list[float] = []
    with open_regular(file, "MovingAI scenario") as opened:
        fh = _lines(opened)
        head = fh.readline(LINE_MAX + 1).removeprefix(codecs.BOM_UTF8)
        first = _ascii_line(head, file, 1, "scenario")
        if first.split() not in (["version", "1"], ["version", "1.0"]):
            raise ValueError(
                f"{file}:1: {first.strip()[:80]!r}, expected 'version 1': not a MovingAI "
                "scenario file of version 1"
            )
        number = 1
        # Decimals of the lengths so far: one count while the file prints them alike.
        decimals: set[int | None] = set()
        for raw in iter(lambda: fh.readline(LINE_MAX + 1), b""):
            number += 1
            # Blanks after the last field are no field (HOG2 reads a stream of words).
            text = _ascii_line(raw, file, number, "scenario").rstrip(" \t\r\n")
            if not text:
                continue
            if not text.replace("\t", " ").isprintable():
                raise ValueError(
                    f"{file}:{number}: a control character: a scenario line holds printable "
                    "fields separated by tabs or spaces"
                )
            fields = text.split("\t") if "\t" in text else text.split()
            if len(fields) != 9:
                raise ValueError(
                    f"{file}:{number}: {counted(len(fields), 'field')}, a problem has 9 (bucket "
                    "map width height start_x start_y goal_x goal_y optimal_length)"
                )
            values = []
            for field, label in zip(fields[:8], _SCEN_FIELDS, strict=False):
                if label is None:
                    continue
                word = field.strip()
                if not (word.isascii() and word.isdigit()):
                    raise ValueError(
                        f"{file}:{number}: {label} {word[:40]!r} is not a non-negative integer"
                    )
                values.append(int(word))
            word = fields[8].strip()
            length = float(word) if _LENGTH.fullmatch(word) else math.nan
            if not math.isfinite(length):
                raise ValueError(
                    f"{file}:{number}: optimal_length {word[:40]!r} is not a finite number >= 0"
                )
            _refuse_cut_length(word, raw, decimals, file, number)
            bucket, width, height, sx, sy, gx, gy = values
            if width == 0 or height == 0:
                raise ValueError(f"{file}:{number}: a map of width {width} and height {height}")
            # Python ints here: NumPy's int64 table raised a bare OverflowError.
            if height * width > MAX_CELLS:
                raise ValueError(
                    f"{file}:{number}: a map of {_digits(height)} x {_digits(width)} cells, more "
                    f"than {MAX_CELLS}"
                )
            if bucket > _INT64_MAX:
                raise ValueError(
                    f"{file}:{number}: bucket {_digits(bucket)} is more than {_INT64_MAX}"
                )
            name = fields[1].strip()
            if not name:
                raise ValueError(f"{file}:{number}: an empty map name")
            for x, y, what in ((sx, sy, "start"), (gx, gy, "goal")):
                if x >= width or y >= height:
                    raise ValueError(
                        f"{file}:{number}: {what} (x, y) = ({x}, {y}) is outside the map's "
                        f"width {width} and height {height}"
                    )
            ints.append((bucket, height, width, sy, sx, gy, gx))
            names.append(name)
            lengths.append(length)
    table = np.array(ints, dtype=np.int64).reshape(-1, 7)
    return MovingAIScenarios(
        table[:, 0], names, table[:, 1:3], table[:, 3:5], table[:, 5:7], lengths
    )


def _refuse_cut_length(
    word: str, raw: bytes, decimals: set[int | None], file: Path, number: int
) -> None:
    """Refuse the optimal length ``word`` of line ``raw`` if the file looks cut inside it.

    Nothing follows the length on its line: a file cut inside the last one
    (``38.21320`` left of ``38.21320344``, or ``3``) gave a shorter length,
    read silently. A line that ends without a line end or blank, its length
    printed with fewer decimals than the file prints every other length with
    (the benchmark's files: 8), is taken as cut. ``decimals`` gathers the
    counts of the lines read (None for a length without a point or with an
    exponent); a file printing them with varying decimals (``%g``) is not
    checked.
    """
    point = "." in word and "e" not in word.lower()
    count = len(word.partition(".")[2]) if point else None
    if raw[-1:] not in (b"\n", b"\r", b" ", b"\t") and len(decimals) == 1:
        (usual,) = decimals
        # A cut only removes digits: a whole length printed with more decimals is read.
        if usual is not None and (count is None or count < usual):
            raise ValueError(
                f"{file}:{number}: the file ends inside this line, its optimal_length "
                f"{word[:40]!r} printed with {'no' if count is None else count} decimals where "
                f"every other line has {usual}: it looks truncated; end the line with a "
                "newline if it is whole"
            )
    decimals.add(count)


# The integer fields of a scenario line, by position (None: the map name).
_SCEN_FIELDS = ("bucket", None, "width", "height", "start_x", "start_y", "goal_x", "goal_y")
