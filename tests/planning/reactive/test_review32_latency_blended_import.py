"""``BlendedAttraction`` imports scipy.special when built, not on its first force (review 32).

Its sigmoid is ``scipy.special.expit``, imported inside the force: the first
``PotentialFieldController.step`` with a blended attraction paid the import,
0.12-0.34 s on a 2-core machine, in the control loop. It is now imported
when the field is made.
"""

from __future__ import annotations

import subprocess
import sys


def _loaded_after(code: str) -> str:
    out = subprocess.run(
        [sys.executable, "-c", "import sys\n" + code + "\nprint('scipy.special' in sys.modules)"],
        capture_output=True,
        text=True,
        check=True,
        timeout=120,
    )
    return out.stdout.strip().splitlines()[-1]


def test_importing_the_controllers_does_not_import_scipy_special() -> None:
    # What the fix keeps: the import is paid by those who build a blended field.
    assert _loaded_after("import navkit.control, navkit.planning") == "False"


def test_building_a_blended_attraction_imports_scipy_special() -> None:
    code = (
        "from navkit.planning import BlendedAttraction\n"
        "BlendedAttraction((1.0, 2.0), threshold_radius=0.5)"
    )
    assert _loaded_after(code) == "True"
