"""navkit as users get it from a built distribution, not from this checkout.

CI installs the checkout in editable mode, so nothing else looks at the sdist, the
wheel or at how an installed navkit finds the data sets.
"""

from __future__ import annotations

import os
import re
import shutil
import subprocess
import sys
import zipfile
from pathlib import Path

import pytest

from navkit.errors import DataNotFoundError
from navkit.sim.scenarios import _data

ROOT = Path(__file__).resolve().parents[1]
PYPROJECT = (ROOT / "pyproject.toml").read_text(encoding="utf-8")
CACHE_PARTS = {"__pycache__", ".hypothesis", ".mypy_cache", ".pytest_cache", ".ruff_cache"}
CACHE_SUFFIXES = (".pyc", ".pyo", ".nbi", ".nbc")


def _is_cache(name: str) -> bool:
    return bool(CACHE_PARTS & set(name.split("/"))) or name.endswith(CACHE_SUFFIXES)


def test_build_backend_floor_reads_the_license_field() -> None:
    # ``license = "BSD-3-Clause"`` (an SPDX string, PEP 639) is refused by
    # setuptools before 77 ("project.license must be valid exactly by one
    # definition"); the build-system floor must not allow those versions.
    license_field = re.search(r'^license = "(.+)"$', PYPROJECT, re.M)
    floor = re.search(r'^requires = \[.*"setuptools>=(\d+)', PYPROJECT, re.M)
    assert floor is not None
    if license_field is not None:
        assert int(floor[1]) >= 77


def test_declared_license_file_exists_and_matches_the_expression() -> None:
    files = re.search(r"^license-files = \[(.*)\]$", PYPROJECT, re.M)
    assert files is not None, "the license text must ship in the wheel and the sdist"
    names = re.findall(r'"([^"]+)"', files[1])
    assert names
    for name in names:
        text = (ROOT / name).read_text(encoding="utf-8")
        if 'license = "BSD-3-Clause"' in PYPROJECT:
            assert "Redistribution and use in source and binary forms" in text
            assert "Neither the name of the copyright holder" in text


def test_metadata_names_where_the_project_lives() -> None:
    urls = re.search(r"^\[project\.urls\]\n(.*?)(?:^\[|\Z)", PYPROJECT, re.M | re.S)
    assert urls is not None
    assert re.search(r'^Repository = "https://', urls[1], re.M)


def _sdist_files() -> set[str]:
    """The files ``MANIFEST.in`` adds, by setuptools' own template engine.

    setuptools' sdist adds the package sources, README and pyproject by itself;
    everything else reaches the sdist only through MANIFEST.in.
    """
    egg_info = pytest.importorskip("setuptools.command.egg_info")
    manifest = ROOT / "MANIFEST.in"
    assert manifest.is_file(), "without MANIFEST.in the sdist lacks the tests' files"
    found: list[str] = []
    for folder, dirs, names in os.walk(ROOT):
        dirs[:] = [d for d in dirs if d != ".git"]
        rel = Path(folder).relative_to(ROOT)
        found.extend((rel / n).as_posix() for n in names)
    files = egg_info.FileList()
    files.allfiles = found
    for line in manifest.read_text(encoding="utf-8").splitlines():
        if line.strip() and not line.lstrip().startswith("#"):
            files.process_template_line(line)
    return set(files.files)


def test_sdist_holds_what_the_tests_read_and_no_caches() -> None:
    shipped = _sdist_files()
    needed = {"LICENSE", "CHANGELOG.md", "mkdocs.yml", ".ci/run", "tests/conftest.py",
              "tests/typing_user/user_api.py", "benchmarks/compare_peers.py",
              "benchmarks/carmen_results.md", "docs/getting-started.md"}
    assert needed <= shipped, sorted(needed - shipped)
    tracked = subprocess.run(["git", "ls-files", "tests", "docs", "benchmarks"], cwd=ROOT,
                             capture_output=True, text=True, check=False)
    if tracked.returncode == 0:  # a checkout (not an unpacked sdist)
        assert set(tracked.stdout.split()) <= shipped
    assert not [name for name in shipped if _is_cache(name)]


def test_installed_navkit_looks_for_data_only_where_it_can_be(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    # A wheel installs navkit in <venv>/lib/python3.X/site-packages: the checkout's
    # <root>/../shared/data rule must not turn that into <venv>/lib/shared/data.
    venv = tmp_path / "venv"
    installed = venv / "lib" / "python3.11" / "site-packages" / "navkit" / "sim" / "scenarios"
    work = tmp_path / "a" / "b" / "c" / "d" / "work"
    for folder in (installed, work, venv / "lib" / "shared" / "data"):
        folder.mkdir(parents=True)
    monkeypatch.delenv(_data.ENV_VAR, raising=False)
    monkeypatch.chdir(work)
    monkeypatch.setattr(_data, "__file__", str(installed / "_data.py"))
    looked = _data._candidates(None)
    assert all(venv not in p.parents for p in looked), looked
    with pytest.raises(DataNotFoundError, match="--data") as caught:
        _data.find_data("ros-map-server-maps/turtlebot3_world/map.yaml")
    assert str(venv) not in str(caught.value)


def test_checkout_still_finds_the_data_beside_its_root(
    tmp_path: Path, monkeypatch: pytest.MonkeyPatch
) -> None:
    root = tmp_path / "checkout"
    module = root / "src" / "navkit" / "sim" / "scenarios"
    module.mkdir(parents=True)
    (root / "pyproject.toml").write_text("[project]\n", encoding="utf-8")
    target = tmp_path / "shared" / "data" / "sets" / "x.yaml"
    target.parent.mkdir(parents=True)
    target.write_text("", encoding="utf-8")
    work = tmp_path / "elsewhere" / "a" / "b" / "c" / "d"
    work.mkdir(parents=True)
    monkeypatch.delenv(_data.ENV_VAR, raising=False)
    monkeypatch.chdir(work)
    monkeypatch.setattr(_data, "__file__", str(module / "_data.py"))
    assert _data.find_data("sets/x.yaml") == target


@pytest.mark.slow
def test_built_wheel_holds_every_module_and_nothing_else(tmp_path: Path) -> None:
    # Build from a copy that, like a developer's checkout, holds numba's and
    # Python's caches beside the sources: none of them may reach the wheel.
    tree = tmp_path / "tree"
    tree.mkdir()
    for name in ("pyproject.toml", "README.md", "CHANGELOG.md", "LICENSE", "MANIFEST.in"):
        if (ROOT / name).is_file():
            shutil.copy2(ROOT / name, tree / name)
    # The checkout's own caches are left out of the copy (under -n 2 the other worker
    # may be writing numba's temporary files there: a file listed, then renamed away)
    # and stand-ins planted instead.
    shutil.copytree(ROOT / "src" / "navkit", tree / "src" / "navkit",
                    ignore=shutil.ignore_patterns("__pycache__"))  # fmt: skip
    for package in ("", "planning/grid"):
        stray = tree / "src" / "navkit" / package / "__pycache__"
        stray.mkdir()
        for name in ("_fake.py311.nbi", "_fake.grid_search-1.py311.1.nbc", "_fake.cpython-311.pyc"):
            (stray / name).write_bytes(b"\0")
    out = tmp_path / "dist"
    built = subprocess.run(
        [sys.executable, "-m", "pip", "wheel", "--no-deps", "-q", "-w", str(out), str(tree)],
        capture_output=True, text=True, check=False, timeout=600,
    )
    if built.returncode != 0 and re.search(
        r"No matching distribution|Could not find a version|NewConnectionError|"
        r"Failed to establish|Temporary failure in name resolution", built.stderr
    ):
        pytest.skip("pip cannot fetch the build backend (offline)")
    assert built.returncode == 0, built.stderr[-2000:]
    (wheel,) = out.glob("navkit-*.whl")
    names = set(zipfile.ZipFile(wheel).namelist())
    sources = {
        "navkit/" + p.relative_to(ROOT / "src" / "navkit").as_posix()
        for p in (ROOT / "src" / "navkit").rglob("*")
        if p.is_file() and not _is_cache(p.relative_to(ROOT).as_posix())
    }
    assert "navkit/py.typed" in sources
    packaged = {n for n in names if n.startswith("navkit/")}
    assert packaged == sources, (sorted(sources - packaged), sorted(packaged - sources))
    info = {n.split("/", 1)[1] for n in names if ".dist-info/" in n}
    assert "licenses/LICENSE" in info
    entry_points = next(n for n in names if n.endswith(".dist-info/entry_points.txt"))
    assert "navkit = navkit.cli:main" in zipfile.ZipFile(wheel).read(entry_points).decode()
