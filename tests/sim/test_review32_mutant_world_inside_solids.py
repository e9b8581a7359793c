"""``World.collides`` for a footprint wholly inside one of many solid circles (review 32).

A footprint that touches no boundary is inside or outside every obstacle, and
``_point_in_solid`` decides which by one of its points. With more than 16
solid circles it tests exactly only those whose bounding square, widened by a
relative 1e-9, holds the point. Mutants shrinking that square instead (radius
``/ (1 + 1e-9)`` or ``* (1 - 1e-9)``) survived the world's tests: a point
1e-10 of the radius inside a large circle was taken for outside. Oracle: the
geometry itself (a solid circle holds the points nearer its centre than its
radius). Likewise for a robot wholly inside a moving disc (a mutant reading the
disc's centre as ``(cx, -cy)`` survived). Checked: each test fails on its
mutants of ``_world.py`` and passes on HEAD.
"""

from __future__ import annotations

from navkit.sim import Circle, MovingObstacle, World


def test_a_point_just_inside_one_of_many_solid_circles_collides() -> None:
    big = 1e5
    # More than 16 solid circles: the exact test runs on those whose bounding
    # square holds the point. The robot's centre is 1e-5 m (1e-10 of the radius)
    # inside the big circle, its radius 1e-6 m: it touches no boundary.
    far = [Circle((3e5 + 10.0 * k, 3e5), 1.0) for k in range(20)]
    world = World([Circle((0.0, 0.0), big), *far])
    for x, y in ((big - 1e-5, 0.0), (0.0, big - 1e-5), (-(big - 1e-5), 0.0)):
        assert world.collides(1e-6, (x, y, 0.0))
    assert not world.collides(1e-6, (big + 1e-5, 0.0, 0.0))


def test_a_footprint_inside_a_moving_disc_collides_where_the_disc_is() -> None:
    # The disc (radius 1 m) moves at (0.5, -0.25) m/s from (3, 4): at t = 2 s its
    # centre is (4, 3.5). A robot of 0.1 m at the centre touches no boundary: inside.
    # Mutants of the moving discs' test (``y + cy`` for ``y - cy``) answered for the
    # disc mirrored in the x axis.
    disc = MovingObstacle.constant_velocity(1.0, start_xy=(3.0, 4.0), velocity_xy=(0.5, -0.25))
    world = World(moving=[disc])
    assert world.collides(0.1, (4.0, 3.5, 0.0), t=2.0)
    assert world.collides(0.1, (3.0, 4.0, 0.0))
    assert not world.collides(0.1, (4.0, -3.5, 0.0), t=2.0)
    assert not world.collides(0.1, (3.0, 4.0, 0.0), t=2.0)
