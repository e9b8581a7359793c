"""Mutants of the command line that survived the tests (review 44, MUTANT20).

A frozen application that ships its sources still finds its cached kernels
(``_kernels``); ``main`` refuses a string or a sequence holding a non-string
as ``argv`` (``_app``); ``plan``'s check that an output is not the map's image
refuses, with its own message, a YAML that is not a mapping or names no image
(``_plan``: the file may change between ``read_map`` and the check).
"""

from __future__ import annotations

import importlib.util
import io
import sys
import warnings
from pathlib import Path

import pytest

from navkit.cli import _kernels, _plan, main
from navkit.errors import KernelCacheWarning

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from numba_index import write_index


@pytest.mark.parametrize("frozen", [False, True])
def test_a_frozen_application_with_its_sources_finds_its_cached_kernels(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch, frozen: bool
) -> None:
    # A freezer that keeps the .py files beside the bytecode: numba caches as usual
    # (here under NUMBA_CACHE_DIR), and the command must look there, frozen or not.
    if frozen:
        monkeypatch.setattr(sys, "frozen", True, raising=False)
    else:
        monkeypatch.delattr(sys, "frozen", raising=False)
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: str(tmp_path))
    (package, module, function), _ = _kernels.KERNELS["astar"]
    spec = importlib.util.find_spec(package)
    assert spec is not None and spec.submodule_search_locations
    source_dir = Path(next(iter(spec.submodule_search_locations)))
    folder = tmp_path / _kernels._subfolder(source_dir)
    assert _kernels.cache_folders(package) == [folder]
    assert not _kernels.kernels_cached("astar")
    folder.mkdir()
    write_index(folder, package, module, function)
    assert _kernels.kernels_cached("astar")


@pytest.mark.parametrize("argv", ["list", "--version"])
def test_a_string_as_argv_is_refused_not_split_into_letters(argv: str) -> None:
    with pytest.raises(TypeError, match=r"^argv must be a sequence of str or None, got '"):
        main(argv)


@pytest.mark.parametrize(
    "argv", [["list", 3], [b"list"], ["--version", None], [Path("list")]]
)  # fmt: skip
def test_a_sequence_holding_a_non_string_is_refused(argv: list[object]) -> None:
    with pytest.raises(TypeError, match=r"^argv must be a sequence of str or None, got \["):
        main(argv)  # type: ignore[arg-type]


@pytest.mark.parametrize(
    "text", ["- image: map.pgm\n", "just a line\n", "", "resolution: 0.05\n"]
)  # fmt: skip
def test_an_output_beside_a_yaml_naming_no_image_is_refused_with_the_readers_message(
    tmp_path: Path, text: str
) -> None:
    # The map's image as read_map finds it (map_image_path, since review 54): a
    # YAML it refuses is refused with its message, naming the YAML.
    map_yaml = tmp_path / "map.yaml"
    map_yaml.write_text(text, encoding="utf-8")
    output = tmp_path / "out.png"
    output.write_bytes(b"kept")
    with pytest.raises(ValueError, match=r"map\.yaml: "):
        _plan._check_not_an_input("--plot", str(output), str(map_yaml))
    assert output.read_bytes() == b"kept"


def test_the_cache_subfolder_is_numbas_own_for_a_relative_source_folder(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    from numba.core.caching import _CacheLocator

    monkeypatch.chdir(tmp_path)
    relative = Path("app") / "navkit"
    py_file = str(relative / "kernels.py")
    expected = _CacheLocator.get_suitable_cache_subpath(py_file)  # type: ignore[no-untyped-call]
    assert _kernels._subfolder(relative) == expected


def test_kernels_cached_beside_a_read_only_install_are_found(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # Without NUMBA_CACHE_DIR, numba caches in its user-wide folder when it cannot
    # write __pycache__ beside the sources: the command looks there too.
    monkeypatch.delattr(sys, "frozen", raising=False)
    monkeypatch.setattr(_kernels, "_numba_cache_dir", lambda: "")
    monkeypatch.setattr(_kernels, "_user_wide_dir", lambda: tmp_path)
    (package, module, function), _ = _kernels.KERNELS["field_dstar"]
    spec = importlib.util.find_spec(package)
    assert spec is not None and spec.submodule_search_locations
    folder = tmp_path / _kernels._subfolder(Path(next(iter(spec.submodule_search_locations))))
    assert folder in _kernels.cache_folders(package)
    before = _kernels.kernels_cached("field_dstar")
    folder.mkdir()
    index = write_index(folder, package, module, function)
    assert _kernels.kernels_cached("field_dstar")
    if not before:  # not already cached in __pycache__ by an earlier run
        index.unlink()
        assert not _kernels.kernels_cached("field_dstar")


class _Flushes(io.StringIO):
    flushed = 0

    def flush(self) -> None:
        self.flushed += 1
        super().flush()


@pytest.mark.filterwarnings("always")
def test_check_cache_says_the_libraries_warning_in_one_flushed_line(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def problem() -> str:
        warnings.warn(
            "cannot cache\n  navkit's kernels:   read-only", KernelCacheWarning, stacklevel=1
        )
        return "read-only"

    monkeypatch.setattr(_kernels, "cache_problem", problem)
    stream = _Flushes()
    assert _kernels.check_cache(stream) == "read-only"
    assert stream.getvalue() == "navkit: warning: cannot cache navkit's kernels: read-only\n"
    assert stream.flushed


@pytest.mark.filterwarnings("always")
def test_check_cache_leaves_other_warnings_to_pythons_own_display(
    monkeypatch: pytest.MonkeyPatch,
) -> None:
    def problem() -> None:
        warnings.warn("numba's own", UserWarning, stacklevel=1)

    monkeypatch.setattr(_kernels, "cache_problem", problem)
    stream = io.StringIO()
    with pytest.warns(UserWarning, match="numba's own"):
        assert _kernels.check_cache(stream) is None
    assert stream.getvalue() == ""


def test_the_compile_notice_is_flushed(monkeypatch: pytest.MonkeyPatch) -> None:
    # Said before minutes of compiling: a buffered standard error would hold it back.
    monkeypatch.setattr(_kernels, "jit_disabled", lambda: False)
    monkeypatch.setattr(_kernels, "kernels_cached", lambda kind: False)
    stream = _Flushes()
    assert _kernels.announce_compilation("astar", stream)
    assert "compil" in stream.getvalue() and stream.flushed


@pytest.mark.parametrize("package", ["navkit.no_such_package", "navkit.cli._kernels"])
def test_no_cache_folders_for_what_is_not_a_package(package: str) -> None:
    assert _kernels.cache_folders(package) == []
