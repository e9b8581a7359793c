"""Run every paper scenario of ``navkit.sim.scenarios`` and write its table and picture.

Writes ``docs/figures/scenario_<name>.txt`` (the result's ``table()``) and
``scenario_<name>.png`` (``plot_scene`` of its scene), which the "Reproducing the
papers" page includes. Run from the repository root, with the real data in
``../shared/data``::

    python docs/figures/scenarios.py            # every scenario, the paper's trials
    python docs/figures/scenarios.py soccer     # one
"""

from __future__ import annotations

import sys
import time
from pathlib import Path

from navkit.plot import plot_scene, save_figure
from navkit.sim.scenarios import SCENARIOS

HERE = Path(__file__).resolve().parent


def main(names: list[str]) -> None:
    for name in names or sorted(SCENARIOS):
        start = time.perf_counter()
        result = SCENARIOS[name]().run(seed=0, workers=None)
        elapsed = time.perf_counter() - start
        (HERE / f"scenario_{name}.txt").write_text(result.table() + "\n", encoding="utf-8")
        if result.scene is not None:
            save_figure(plot_scene(result.scene), HERE / f"scenario_{name}.png", dpi=90)
        print(f"{name}: {len(result.trials)} trials in {elapsed:.1f} s")


if __name__ == "__main__":
    main(sys.argv[1:])
