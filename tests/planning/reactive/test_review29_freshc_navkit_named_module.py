"""``with_goal`` keeps a subclass's state whatever its module's name (review 29, FRESHC).

``AttractiveField.with_goal`` (called by the controller every step) skips
looking for what a subclass adds when the class's module name starts with
``"navkit."``, to spare navkit's own fields the 3 µs. A user's subclass in a
package of that name (a plugin namespace ``navkit.contrib``, a fork's module)
then lost its own parameter: ``AttributeError`` in its ``_force`` at the first
step. navkit's own fields are now told apart by a set of their classes.
"""

from __future__ import annotations

from typing import Any

import numpy as np
import pytest
from numpy.typing import NDArray
from test_review29_freshb_user_field_state import Boost as _Boost
from test_review29_freshb_user_field_state import SlotBoost as _SlotBoost

from navkit.control import PotentialFieldController

F64 = NDArray[np.float64]


class Boost(_Boost):
    """Review 29's cone with a gain set in ``__init__``, in a module named navkit...."""


class SlotBoost(_SlotBoost):
    """The same with the gain in a slot."""

    __slots__ = ()


# As if defined in a plugin package named navkit.contrib.
Boost.__module__ = SlotBoost.__module__ = "navkit.contrib.fields"


@pytest.mark.parametrize("kind", [Boost, SlotBoost])
def test_with_goal_keeps_the_parameter_of_a_subclass_in_a_navkit_named_module(
    kind: type[Any],
) -> None:
    moved = kind((0.0, 0.0), 0.5).with_goal((3.0, 4.0))
    assert moved.gain == 0.5  # before: AttributeError
    np.testing.assert_allclose(moved.force([0.0, 0.0]), [[0.3, 0.4]], rtol=0, atol=1e-15)


@pytest.mark.parametrize("kind", [Boost, SlotBoost])
def test_the_controller_drives_it(kind: type[Any]) -> None:
    ctl = PotentialFieldController(max_speed=1.0, attraction=kind((0.0, 0.0), 0.5))
    np.testing.assert_allclose(
        ctl.desired_velocity([0.0, 0.0, 0.0], (2.0, 0.0)), [0.5, 0.0], rtol=0, atol=1e-15
    )
