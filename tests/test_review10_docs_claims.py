"""The documentation's prose claims, recomputed.

``tests/test_docs.py`` runs the pages' code; this file checks what the prose
around it says — defaults, option lists, numbers quoted from a computation,
command lines, the API reference's coverage and the benchmark names the
performance pages cite — against the code, so that a change on either side
fails here. Each test reads the page text (whitespace collapsed, so line
breaks do not matter) and looks for the sentence built from the computed value.
"""

from __future__ import annotations

import importlib
import inspect
import math
import pkgutil
import re
import shlex
import subprocess
import sys
import tomllib
import typing
from pathlib import Path

import numpy as np
import pytest

import navkit
from navkit.cli._parser import build_parser, join_negative_points
from navkit.control import FollowTheCarrot, OnOffTracker
from navkit.control._path_following import Phase
from navkit.kinematics import OmniDrive
from navkit.mapping import (
    LaserScan,
    OccupancyGrid,
    ScanMapper,
    ScanMatcher,
    costmap,
    integrate_scan,
    traversal_costs,
)
from navkit.planning import BlendedAttraction
from navkit.sim import WARMUP_STEPS, RangeNoise
from navkit.sim.scenarios import SCENARIOS

ROOT = Path(__file__).resolve().parents[1]
DOCS = ROOT / "docs"
SHARED = ROOT.parent / "shared" / "data"


def _page(relative: str) -> str:
    """A page's text with every run of whitespace collapsed to one space."""
    path = ROOT / relative
    return " ".join(path.read_text(encoding="utf-8").split())


def _default(func: typing.Any, name: str) -> typing.Any:
    return inspect.signature(func).parameters[name].default


def _logit(p: float) -> float:
    return math.log(p / (1.0 - p))


def _num(x: float) -> str:
    """``x`` as the prose writes it: ``0.65``, ``10``, ``0.196``."""
    return f"{x:g}"


# ---------------------------------------------------------------------------
# The API reference: one page per public package, every page reachable.


def _public_packages() -> list[str]:
    out = []
    for info in pkgutil.walk_packages(navkit.__path__, "navkit."):
        if any(part.startswith("_") for part in info.name.split(".")):
            continue
        module = importlib.import_module(info.name)
        if info.ispkg or hasattr(module, "__all__"):
            out.append(info.name)
    return sorted(out)


def test_every_public_package_has_an_api_page_in_the_nav_and_on_the_home_page() -> None:
    targets = {}
    for page in sorted((DOCS / "api").glob("*.md")):
        for target in re.findall(r"^::: ([\w.]+)\s*$", page.read_text(encoding="utf-8"), re.M):
            targets[target] = page
    # navkit.planning only re-exports its two halves, which have their own pages;
    # the top-level package has its own (navkit.__version__, review 44).
    expected = sorted(["navkit", *(p for p in _public_packages() if p != "navkit.planning")])
    assert sorted(targets) == expected
    assert set(navkit.planning.__all__) == set(
        navkit.planning.grid.__all__ + navkit.planning.reactive.__all__
    )
    mkdocs = (ROOT / "mkdocs.yml").read_text(encoding="utf-8")
    home = (DOCS / "index.md").read_text(encoding="utf-8")
    for target, page in targets.items():
        rel = page.relative_to(DOCS).as_posix()
        assert f"{target}: {rel}" in mkdocs, f"{rel} is not in mkdocs.yml's nav"
        assert f"[`{target}`]({rel})" in home, f"docs/index.md does not link {rel}"


def test_layers_quoted_as_the_architecture_test_enforces_them() -> None:
    chain = "planning ← control ← behaviours ← sim ← plot ← the command line"
    assert chain in _page("README.md")
    assert chain in _page("docs/index.md")
    arch = (ROOT / "tests" / "test_architecture.py").read_text(encoding="utf-8")
    ranks = dict(re.findall(r'"(\w+)": (\d+),', arch))
    order = ["planning", "control", "behaviours", "sim", "plot", "cli"]
    assert [int(ranks[n]) for n in order] == sorted(int(ranks[n]) for n in order)
    assert len({ranks[n] for n in order}) == len(order)


# ---------------------------------------------------------------------------
# Install: extras, dependency floors, the command line.


def _pyproject() -> tuple[dict[str, str], str, set[str]]:
    """pyproject.toml's dependency floors, ``requires-python`` and extras."""
    with (ROOT / "pyproject.toml").open("rb") as file:
        project = tomllib.load(file)["project"]
    floors = {}
    for requirement in project["dependencies"]:
        if ";" in requirement:  # a newer Python's floor (see _newer_python_floors)
            continue
        floor = re.fullmatch(r"([\w-]+)>=([\d.]+)", requirement)
        assert floor is not None, requirement
        floors[floor[1]] = floor[2]
    return floors, project["requires-python"], set(project["optional-dependencies"])


def _newer_python_floors() -> dict[str, dict[str, str]]:
    """pyproject.toml's floors under a ``python_version >= 'X.Y'`` marker, by that version."""
    with (ROOT / "pyproject.toml").open("rb") as file:
        project = tomllib.load(file)["project"]
    floors: dict[str, dict[str, str]] = {}
    for requirement in project["dependencies"]:
        if ";" not in requirement:
            continue
        found = re.fullmatch(
            r"([\w-]+)>=([\d.]+); python_version >= '([\d.]+)'", requirement
        )
        assert found is not None, requirement
        floors.setdefault(found[3], {})[found[1]] = found[2]
    return floors


def test_readme_states_the_newer_pythons_floors() -> None:
    readme = _page("README.md")
    newer = _newer_python_floors()
    assert newer, "no marker floors: drop this test and the README sentence"
    for version, floors in newer.items():
        sentence = rf"On Python {re.escape(version)} the floors are [^:]*: (.*?)\.(?: |$)"
        quoted = re.search(sentence, readme)
        assert quoted is not None, version
        stated = dict(re.findall(r"(\w+) \(>= ([\d.]+)\)", quoted[1]))
        assert {k.lower(): v for k, v in stated.items()} == floors


def test_readme_dependency_floors_and_extras_are_pyprojects() -> None:
    declared, requires_python, extras = _pyproject()
    readme = _page("README.md")
    quoted = re.search(r"Runtime dependencies: (.*?)\. Python >= ([\d.]+)\.", readme)
    assert quoted is not None
    floors = dict(re.findall(r"(\w+) \(>= ([\d.]+)\)", quoted[1]))
    assert len(declared) == 6
    assert {k.lower(): v for k, v in floors.items()} == declared
    assert requires_python == f">={quoted[2]}"
    assert len(extras) == 6
    in_readme = re.search(r"Extras: (.*?)\. `python -m pip", readme)
    assert in_readme is not None
    assert set(re.findall(r"`(\w+)`", in_readme[1])) == extras
    started = _page("docs/getting-started.md")
    in_page = re.search(r"Extras add what only some uses need: (.*?)\. ##", started)
    assert in_page is not None
    assert set(re.findall(r"`(\w+)`", in_page[1])) >= extras


def _documented_command_lines() -> list[tuple[str, str]]:
    """Every ``navkit ...`` line of the ```bash blocks of README.md and docs/."""
    out = []
    for page in [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]:
        text = page.read_text(encoding="utf-8")
        for block in re.findall(r"```bash\n(.*?)```", text, re.S):
            joined = block.replace("\\\n", " ")
            for line in joined.splitlines():
                line = line.split("#", 1)[0].split("&&")[-1].strip()
                if line.startswith("navkit "):
                    out.append((page.relative_to(ROOT).as_posix(), line))
    return out


def test_every_documented_command_line_parses() -> None:
    lines = _documented_command_lines()
    assert len(lines) >= 8
    parser = build_parser(sorted(SCENARIOS))
    for page, line in lines:
        argv = join_negative_points(shlex.split(line)[1:])
        try:
            parser.parse_args(argv)
        except SystemExit:  # pragma: no cover - the assertion message is the point
            pytest.fail(f"{page}: `{line}` is not a valid navkit command line")


def test_readme_lists_every_subcommand() -> None:
    parser = build_parser(sorted(SCENARIOS))
    sub = next(a for a in parser._actions if a.dest == "command")
    row = re.search(r"\| `navkit` \(command\) \| (.*?) \|", _page("README.md"))
    assert row is not None
    assert sub.choices is not None
    assert re.findall(r"`navkit (\w+)", row[1]) == list(sub.choices)


def test_warmup_steps_quoted_exist() -> None:
    quoted = re.findall(r"--only (\w+)", _page("docs/compilation.md"))
    assert quoted and set(quoted) <= set(WARMUP_STEPS)


# ---------------------------------------------------------------------------
# Defaults and constants the guides quote.


def test_mapping_guide_defaults() -> None:
    page = _page("docs/guides/mapping.md")
    occ = _default(OccupancyGrid, "occupied_thresh")
    free = _default(OccupancyGrid, "free_thresh")
    assert (
        f"`occupied_thresh` (default {_num(occ)}), free when \\( p < \\) "
        f"`free_thresh` ({_num(free)})"
    ) in page
    tutorial = _page("docs/tutorials/map-to-plan.md")
    assert f"`occupied_thresh` ({_num(occ)}), free below `free_thresh` ({_num(free)})" in tutorial
    # The inverse sensor model, as logits of the probabilities quoted.
    quoted = re.search(
        r"`miss` \(\\\( \\operatorname\{logit\} ([\d.]+) \\\)\), its end cell .*? "
        r"`hit` \(\\\( \\operatorname\{logit\} ([\d.]+) \\\)\), clamped to "
        r"\\\( \[\\operatorname\{logit\} ([\d.]+), \\operatorname\{logit\} ([\d.]+)\] \\\)",
        page,
    )
    assert quoted is not None
    miss, hit, lo, hi = (float(q) for q in quoted.groups())
    assert _default(integrate_scan, "miss") == pytest.approx(_logit(miss), abs=1e-12)
    assert _default(integrate_scan, "hit") == pytest.approx(_logit(hit), abs=1e-12)
    assert _default(integrate_scan, "clamp") == pytest.approx((_logit(lo), _logit(hi)), abs=1e-12)
    # "One scan takes a crossed cell only to p = 0.4: above free_thresh".
    assert f"only to \\( p = {_num(miss)} \\): above `free_thresh`" in page
    assert miss > free
    # Costs.
    k = _default(costmap, "cost_scaling_factor")
    assert _default(traversal_costs, "cost_scaling_factor") == k
    assert f"`cost_scaling_factor` (default {_num(k)} /m)" in page
    w = _default(traversal_costs, "cost_weight")
    assert f"`cost_weight` \\( w = {_num(w)} \\)" in page
    assert f"band cells at {_num(1 + w)} (`1 + cost_weight`)" in _page("docs/guides/planning.md")
    # The local grid's default size.
    half = _default(LaserScan.to_local_grid, "half_width")
    res = _default(LaserScan.to_local_grid, "resolution")
    n = 2 * round(half / res) + 1
    assert f"`scan.to_local_grid(half_width={half!r}, resolution={res!r})`" in page
    assert f"({n} × {n} cells by default" in page
    assert f"the greedy step on a {n} × {n} laser grid" in _page("docs/papers.md")
    # Scan matching and mapping.
    assert f"(`levels={_default(ScanMatcher, 'levels')}`:" in page
    dist, rot = _default(ScanMapper, "min_distance"), _default(ScanMapper, "min_angle")
    assert f"`min_distance` ({_num(dist)} m) or turned `min_angle` ({_num(rot)} rad)" in page
    tutorial = _page("docs/tutorials/scans-to-map.md")
    assert f"moved {_num(dist)} m or turned {_num(rot)} rad" in tutorial
    # hit and miss are log-odds; the prose gives their probabilities.
    occupied = round(1.0 / (1.0 + math.exp(-_default(ScanMapper, "hit"))), 12)
    free_p = round(1.0 / (1.0 + math.exp(-_default(ScanMapper, "miss"))), 12)
    assert f"occupied {_num(occupied)} / free {_num(free_p)} update probabilities" in page
    assert f"`hit=logit({_num(occupied)})` and `miss=logit({_num(free_p)})`" in page


def test_scan_matcher_weights_quoted_in_the_tutorial() -> None:
    page = _page("docs/tutorials/scans-to-map.md")
    mapper_weight = ScanMapper()._matcher._rotation_weight
    bare_weight = _default(ScanMatcher, "rotation_weight")
    bench = (ROOT / "benchmarks" / "carmen_navkit.py").read_text(encoding="utf-8")
    harness = re.search(r"^ROTATION_WEIGHT = ([\d.]+)$", bench, re.M)
    assert harness is not None
    assert (
        f"the benchmark uses a heading weight of {harness[1]}/rad instead of `ScanMapper`'s "
        f"default {_num(mapper_weight)}/rad (a bare `ScanMatcher` has no pull, {_num(bare_weight)})"
    ) in page


def test_control_guide_defaults_poles_and_phases() -> None:
    page = _page("docs/guides/control.md")
    tol = _default(OnOffTracker, "rotate_angle")
    assert f"`rotate_angle` ({math.degrees(tol):.0f}°)" in page
    # ON-OFF's largest excursion r0 sin(b) exp(-b / tan(b)), as a share of r0.
    stray = math.sin(tol) * math.exp(-tol / math.tan(tol))
    assert f"({100 * stray:.2f} % of the start distance for {math.degrees(tol):.0f}°)" in page
    k = _default(FollowTheCarrot, "heading_gain")
    v = _default(FollowTheCarrot, "max_speed")
    d = _default(FollowTheCarrot, "carrot_distance")
    poles = sorted(np.roots([1.0, k, k * v / d]).real, reverse=True)
    assert f"(\\( k = {_num(k)} \\), \\( v = {_num(v)} \\), \\( d = {_num(d)} \\))" in page
    assert f"its poles are −{-poles[0]:.1f} and −{-poles[1]:.1f} s⁻¹: overdamped" in page
    quoted = re.search(r"`tracker\.phase` says what it is doing \((.*?)\) and `tracker", page)
    assert quoted is not None
    phases: tuple[str, ...] = typing.get_args(Phase)
    assert re.findall(r'`"(\w+)"`', quoted[1]) == list(phases)


def test_blended_attraction_claims() -> None:
    page = _page("docs/guides/planning.md")
    r_thr = _default(BlendedAttraction, "threshold_radius")
    width = _default(BlendedAttraction, "width")
    assert (
        f"navkit's defaults (\\( r_\\text{{thr}} = {_num(r_thr)} \\), "
        f"\\( \\omega = {_num(width)} \\))"
    ) in page
    d = np.linspace(2e-4, 1.5, 15000)
    points = np.column_stack((d, np.zeros_like(d)))

    def outward_up_to(**options: float) -> float:
        """The largest distance at which the radial force points away from the goal."""
        radial = BlendedAttraction((0.0, 0.0), **options).force(points)[:, 0]
        return float(d[radial > 0].max())

    quoted = re.search(r"pull toward the goal everywhere beyond (\d+) mm", page)
    assert quoted is not None
    assert math.ceil(1e3 * outward_up_to()) == int(quoted[1])
    # The figure caption: rings at about 0.55 m for narrow widths, 4-5 cm off for wide ones.
    assert "widths 0.05 and 0.1 m have a ring of local minima at about 0.55 m" in page
    for narrow in (0.05, 0.1):
        assert round(outward_up_to(threshold_radius=0.5, width=narrow), 2) == 0.55
    assert "widths 0.3 and 0.5 m move the minimum 4–5 cm off the goal" in page
    for wide in (0.3, 0.5):
        assert 0.04 <= outward_up_to(threshold_radius=0.5, width=wide) <= 0.05


def test_sim_guide_range_noise_and_three_wheel_layout() -> None:
    noise = RangeNoise()
    assert noise.limits[0] == 3.0 and math.isinf(noise.limits[-1])
    low, high = (100 * s for s in noise.sigma)
    assert f"{low:.2f} % below {_num(noise.limits[0])} m and {high:.2f} % beyond" in _page(
        "docs/guides/sim.md"
    )
    # The docs name the mounting angles in [0°, 360°); wheel_angles reads them wrapped.
    drive = OmniDrive.three_wheel(wheel_radius=0.05, base_radius=0.2)
    angles = np.degrees(drive.wheel_angles) % 360.0
    quoted = "wheels at " + ", ".join(f"{a:.0f}°" for a in angles)
    for page in ("README.md", "docs/guides/kinematics.md", "docs/papers.md"):
        assert quoted in _page(page), page


def test_papers_page_has_every_scenario() -> None:
    page = _page("docs/papers.md")
    for name in SCENARIOS:
        assert f"## {name} —" in page, name
        assert f'--8<-- "figures/scenario_{name}.txt"' in page, name
        assert (DOCS / "figures" / f"scenario_{name}.txt").is_file(), name


# ---------------------------------------------------------------------------
# The performance pages: dated, and citing benchmarks that exist.


def test_performance_page_workloads_are_compare_peers_workloads() -> None:
    listing = subprocess.run(
        [sys.executable, str(ROOT / "benchmarks" / "compare_peers.py"), "--list"],
        capture_output=True, text=True, check=True, cwd=ROOT, timeout=120,
    ).stdout.splitlines()
    names = [line.split()[0] for line in listing if line.strip()]
    quick = [line.split()[0] for line in listing if line.split()[1:2] == ["quick"]]
    raw = (DOCS / "performance.md").read_text(encoding="utf-8")
    page = _page("docs/performance.md")
    rows = re.search(r"## Latest results(.*?)## The workloads", raw, re.S)
    assert rows is not None
    in_table = {
        line.split("|")[1].strip()
        for line in rows[1].splitlines()
        if line.startswith("| ") and not line.startswith(("| workload", "| ---"))
    }
    assert in_table == set(names)
    assert f"--quick # {len(quick)} workloads" in page
    assert f"# all {len(names)} workloads" in page
    assert re.search(r"- date: \d{4}-\d\d-\d\d \d\d:\d\d UTC", raw)
    assert re.search(r"- machine: \S", raw)


def test_docs_cite_benchmark_files_and_tests_that_exist() -> None:
    bench = ROOT / "benchmarks"
    sources = "\n".join(p.read_text(encoding="utf-8") for p in bench.glob("*.py"))
    cited_files = set()
    cited_tests = set()
    for page in [ROOT / "README.md", *sorted(DOCS.rglob("*.md"))]:
        text = page.read_text(encoding="utf-8")
        cited_files |= set(re.findall(r"benchmarks/([\w.*]+\.(?:py|md))", text))
        cited_tests |= set(re.findall(r"`(test_\w+)`", text))
    assert "test_bench_cold_start.py" in cited_files
    for name in cited_files:
        assert list(bench.glob(name)), f"benchmarks/{name} is cited but does not exist"
    assert cited_tests
    for name in cited_tests:
        assert f"def {name}(" in sources, f"{name} is cited but no benchmark defines it"


def test_first_use_table_is_dated() -> None:
    page = _page("docs/compilation.md")
    assert re.search(
        r"measured by `benchmarks/test_bench_cold_start\.py` with numba [\d.]+ on Python "
        r"[\d.]+ on a \d-core machine, \d{4}-\d\d-\d\d",
        page,
    )


# ---------------------------------------------------------------------------
# Numbers quoted from runs on the real data sets.

WILLOW = SHARED / "ros-map-server-maps" / "willow_garage_2010" / "willow-2010-02-18-0.10.yaml"


@pytest.mark.skipif(not WILLOW.is_file(), reason="the Willow Garage map is absent")
def test_willow_caption_numbers() -> None:
    from navkit.planning import MapPlanner

    grid = OccupancyGrid.load(WILLOW)
    figures = (DOCS / "figures" / "make_figures.py").read_text(encoding="utf-8")
    cells = []
    for name in ("WILLOW_START_CELL", "WILLOW_GOAL_CELL"):
        found = re.search(rf"^{name} = \((\d+), (\d+)\)$", figures, re.M)
        assert found is not None, name
        cells.append((int(found[1]), int(found[2])))
    start_xy, goal_xy = grid.cell_to_world(cells)
    astar, fd = (MapPlanner(grid, robot_radius=0.3, planner=p).plan(start_xy, goal_xy)
                 for p in ("astar", "field_dstar"))  # fmt: skip
    shorter = round(100 * (1 - fd.length / astar.length))
    assert (
        f"Field D*'s path is about {shorter} % shorter and has {len(fd.points)} points "
        f"instead of {len(astar.points)}."
    ) in _page("docs/guides/planning.md")
    assert f"about {shorter} % shorter with a handful of points" in _page(
        "docs/tutorials/map-to-plan.md"
    )


BAG = SHARED / "robot-localization-odom-imu-bags" / "test2.bag"


@pytest.mark.skipif(not BAG.is_file(), reason="robot_localization's test2.bag is absent")
def test_bag_fusion_table() -> None:
    """The tutorial's table of end errors is what its code computes."""
    pytest.importorskip("rosbags")
    raw = (DOCS / "tutorials" / "bag-fusion.md").read_text(encoding="utf-8")
    namespace: dict[str, typing.Any] = {}
    blocks = re.findall(r"```python\n(.*?)```", raw, re.S)
    # Run the page's code with its paths anchored at the repository, printing nothing.
    code = "\n".join(blocks).replace('"../shared/data/', f'"{SHARED.as_posix()}/')
    namespace["print"] = lambda *args, **kwargs: None
    exec(compile(code, "bag-fusion.md", "exec"), namespace)
    PlanarFusion, err = namespace["PlanarFusion"], namespace["end_error"]
    t0, x0 = namespace["t0"], namespace["x0"]
    computed = [
        err(namespace["naive"]),
        err(PlanarFusion(t0=t0).update_batch(namespace["speed_only"])),
        err(PlanarFusion(x0, t0=t0).update_batch(namespace["speed_only"])),
        err(PlanarFusion(x0, t0=t0).update_batch(namespace["with_yaw"])),
        err(namespace["result"]),
    ]
    table = re.findall(r"^\| .*? \| (?:\*\*)?([\d.]+) m(?:\*\*)? \|$", raw, re.M)
    assert len(table) == len(computed)
    for quoted, value in zip(table, computed, strict=True):
        decimals = len(quoted.split(".")[1])
        assert f"{value:.{decimals}f}" == quoted
    page = " ".join(raw.split())
    assert f"Three facts about the robot bring it to **{100 * computed[-1]:.0f} cm**" in page
    assert f"the fusion ends **{computed[0]:.1f} m** off" in page
    rows = len(namespace["result"].accepted)
    assert f"log ({rows:,} rows)" in page


def test_scans_to_map_quotes_the_weight_sweep() -> None:
    """The tutorial's failure counts are the csail rows of the results' weight sweep."""
    results = (ROOT / "benchmarks" / "carmen_results.md").read_text(encoding="utf-8")
    header = re.search(r"^\| log \| seed \| (w = .*) \|$", results, re.M)
    assert header is not None
    weights = [w.strip() for w in header[1].split("|")]
    default, chosen = weights.index("w = 1"), weights.index("w = 3.5")
    rows = re.findall(r"^\| csail \| (\d) \| (.*) \|$", results, re.M)
    assert [seed for seed, _ in rows] == ["0", "1", "2"]
    gross = [[int(cell.rsplit(",", 1)[1]) for cell in cells.split("|")] for _, cells in rows]
    before = sorted({g[default] for g in gross})
    after = sorted({g[chosen] for g in gross})
    assert len(after) == 1
    assert (
        f"({after[0]} consecutive pairs off by more than 0.5 m or 10° instead of "
        f"{before[0]} to {before[-1]}, seeds 0–2 of the results' weight sweep)"
    ) in _page("docs/tutorials/scans-to-map.md")
    assert "a gross failure is a consecutive pair off by more than 0.5 m or 10°" in " ".join(
        results.split()
    )
