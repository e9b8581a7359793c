"""The command imports what its subcommand needs and no more (issue 17: start-up time).

Each check runs the command in a fresh interpreter and looks at ``sys.modules``
afterwards: ``navkit --help`` loads neither numpy nor the simulator, ``navkit
list`` no scipy, matplotlib or numba, ``navkit run greedy`` no other scenario's
module and ``navkit plan`` no scenario at all.
"""

from __future__ import annotations

import json
import os
import subprocess
import sys
from pathlib import Path

import pytest

import navkit.sim.scenarios as scenarios
from navkit.cli import _app
from navkit.cli._parser import build_parser

# Runs navkit.cli.main on the arguments after the first; writes its exit code
# and the modules then loaded to the file named by the first.
_PROBE = """
import json, sys
from navkit.cli import main
code = main(sys.argv[2:])
with open(sys.argv[1], "w", encoding="utf-8") as f:
    json.dump({"code": code, "modules": sorted(sys.modules)}, f)
"""

_OTHER_SCENARIOS = ("_demo", "_demo_loop", "_diff_astar", "_indoor_nav", "_omni_apf", "_soccer")


def _loaded(tmp_path: Path, *argv: str) -> tuple[int, set[str]]:
    """The command's exit code and the top-level packages and navkit modules it loaded."""
    report = tmp_path / "report.json"
    env = {k: v for k, v in os.environ.items() if not k.startswith("NUMBA_DISABLE")}
    done = subprocess.run(
        [sys.executable, "-c", _PROBE, str(report), *argv],
        env=env, capture_output=True, text=True, timeout=300, cwd=tmp_path,
    )  # fmt: skip
    assert done.returncode == 0, done.stderr[-2000:]
    found = json.loads(report.read_text(encoding="utf-8"))
    modules: list[str] = found["modules"]
    return found["code"], {m for m in modules if m.startswith("navkit.")} | {
        m.split(".")[0] for m in modules
    }


def test_help_loads_neither_numpy_nor_the_simulator(tmp_path: Path) -> None:
    code, loaded = _loaded(tmp_path, "--help")
    assert code == 0
    heavy = loaded & {"numpy", "scipy", "shapely", "numba", "matplotlib", "navkit.sim"}
    assert not heavy, heavy


def test_list_loads_no_scipy_matplotlib_or_numba(tmp_path: Path) -> None:
    code, loaded = _loaded(tmp_path, "list")
    assert code == 0
    assert "navkit.sim.scenarios._greedy" in loaded  # it did look at the scenarios
    heavy = loaded & {"scipy", "numba", "llvmlite", "matplotlib", "rosbags"}
    assert not heavy, heavy


def test_run_loads_the_named_scenario_alone(tmp_path: Path) -> None:
    # A --data that is not a folder ends the command once the scenario is chosen
    # and the command's module loaded, before anything runs.
    code, loaded = _loaded(tmp_path, "run", "greedy", "--data", str(tmp_path / "absent"))
    assert code == 1
    assert "navkit.sim.scenarios._greedy" in loaded
    others = loaded & {f"navkit.sim.scenarios.{name}" for name in _OTHER_SCENARIOS}
    assert not others, others
    assert not loaded & {"numba", "matplotlib"}


def test_plan_loads_no_scenario(tmp_path: Path) -> None:
    code, loaded = _loaded(
        tmp_path, "plan", str(tmp_path / "absent.yaml"), "--start", "0,0", "--goal", "1,1"
    )
    assert code == 1
    assert "navkit.cli._plan" in loaded
    scenario_modules = {m for m in loaded if m.startswith("navkit.sim.scenarios")}
    assert not scenario_modules, scenario_modules


def test_ctrl_c_while_the_named_scenario_loads_exits_130_in_one_line(tmp_path: Path) -> None:
    # The scenario's module is now imported while the arguments are parsed.
    code = """
import importlib.abc, sys
class Interrupt(importlib.abc.MetaPathFinder):
    def find_spec(self, fullname, path, target=None):
        if fullname == "navkit.sim.scenarios._greedy":
            raise KeyboardInterrupt
        return None
sys.meta_path.insert(0, Interrupt())
from navkit.cli import main
sys.exit(main(["run", "greedy", "--quiet"]))
"""
    done = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=300, cwd=tmp_path
    )
    assert done.returncode == 130, done.stderr[-2000:]
    assert done.stderr == "navkit: interrupted\n"
    assert done.stdout == ""


def test_default_parser_has_the_registered_scenarios_and_their_help(
    capsys: pytest.CaptureFixture[str],
) -> None:
    lazy, listed = build_parser(), build_parser(sorted(scenarios.SCENARIOS))
    helps = ((["run", "--help"], "greedy, indoor-nav"), (["warmup", "--help"], "geometry"))
    for argv, expected in helps:
        texts = []
        for parser in (lazy, listed):
            with pytest.raises(SystemExit):
                parser.parse_args(argv)
            texts.append(capsys.readouterr().out)
        assert texts[0] == texts[1]
        assert expected in texts[0]
    for name in scenarios.SCENARIOS:
        assert lazy.parse_args(["run", name]).scenario == name
    with pytest.raises(SystemExit):
        lazy.parse_args(["run", "Greedy"])


def test_scenario_names_resolve_to_the_registered_classes() -> None:
    assert sorted(scenarios.SCENARIOS) == sorted(
        ["demo", "diff-astar", "greedy", "indoor-nav", "omni-apf", "soccer"]
    )
    for name, cls in scenarios.SCENARIOS.items():
        assert cls.name == name
        assert scenarios.get_scenario(name) is cls
        assert getattr(scenarios, cls.__name__) is cls
        assert cls.__name__ in scenarios.__all__
        assert cls.__name__ in dir(scenarios)
    with pytest.raises(AttributeError, match="no attribute 'Nope'"):
        scenarios.Nope  # noqa: B018
    with pytest.raises(ValueError, match="unknown scenario 'nope'; known: demo, diff-astar"):
        scenarios.get_scenario("nope")


def test_main_dispatches_warmup(capsys: pytest.CaptureFixture[str]) -> None:
    # tests/cli/test_cli_warmup.py's check, which _app's lazy imports made skip.
    assert _app.main(["warmup", "--only", "geometry", "--workers", "1"]) == 0
    assert "geometry" in capsys.readouterr().out

