"""Adapters that turn navkit's algorithms into :class:`~navkit.sim.Simulation` controllers."""

from __future__ import annotations

from typing import Generic, Protocol, TypeVar

from navkit._shared.dunders import slot_state
from navkit._shared.validation import as_bool, positive_float
from navkit.geometry import Pose2D, Twist2D
from navkit.sim._done import done_flag
from navkit.sim._simulation import Observation

__all__ = ["Tracker", "TrackerController"]

#: Highest control rate accepted, Hz.
_MAX_RATE = 1e6


class Tracker(Protocol):
    """What :class:`TrackerController` drives: a path tracker.

    navkit's :class:`~navkit.control.FollowTheCarrot`,
    :class:`~navkit.control.OnOffTracker` and
    :class:`~navkit.control.RegulatedPurePursuit` are trackers; so is any
    object with a ``step(pose, dt)`` method returning a ``Twist2D`` and a
    ``done`` flag (a property or a plain attribute). Type a tracker of your own
    against it; ``TrackerController`` is generic in the tracker type, so
    ``TrackerController(tracker, ...).tracker`` keeps that type (its
    ``set_path``, say).

    Examples
    --------
    >>> from navkit.sim import Observation
    >>> class Forward:  # a Tracker that drives straight on for 1 s of commands
    ...     def __init__(self) -> None:
    ...         self.done, self.elapsed = False, 0.0
    ...     def step(self, pose: Pose2D, dt: float) -> Twist2D:
    ...         self.elapsed += dt
    ...         self.done = self.elapsed >= 1.0
    ...         return Twist2D(0.5, 0.0, 0.0)
    >>> tracker: Tracker = Forward()
    >>> follow = TrackerController(Forward(), control_rate=10.0, use_estimate=False)
    >>> obs = Observation(0.0, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0), dt=0.5)
    >>> follow(obs), follow.tracker.elapsed  # tracker keeps its type: Forward
    (Twist2D(vx=0.5, vy=0.0, omega=0.0), 0.5)
    >>> _ = follow(obs); follow.done
    True
    """

    @property
    def done(self) -> bool:
        """Whether the tracker has finished (the simulation then ends, "controller done").

        Read after every control step; a plain attribute serves too.
        """
        ...

    def step(self, pose: Pose2D, dt: float) -> Twist2D:
        """One control step: the command to hold for the next ``dt`` seconds.

        Parameters
        ----------
        pose : Pose2D
            The robot's pose in the world frame (m, m, rad in (-π, π]): the
            estimator's or the true pose (see :class:`TrackerController`).
        dt : float
            How long the command is held, s (> 0).

        Returns
        -------
        Twist2D
            The command in the robot frame (m/s, m/s, rad/s); anything else
            raises ``TypeError`` in :class:`TrackerController`.

        Examples
        --------
        >>> from navkit.control import OnOffTracker
        >>> on_off = OnOffTracker(max_speed=0.5)
        >>> on_off.set_path([[0.0, 0.0], [1.0, 0.0]])
        >>> tracker: Tracker = on_off
        >>> tracker.step(Pose2D(0.0, 0.0, 0.0), 0.05)  # facing the waypoint: full speed
        Twist2D(vx=0.5, vy=0.0, omega=0.0)
        """
        ...


_T = TypeVar("_T", bound=Tracker)


class TrackerController(Generic[_T]):
    """A path tracker as a :class:`~navkit.sim.Simulation` controller.

    Each control step calls ``tracker.step(pose, dt)`` with the estimator's
    pose (``use_estimate=True``; a zero twist while there is no estimate yet)
    or the true pose (an oracle, for tests and baselines). ``dt`` is how long
    the simulation holds the command, :attr:`Observation.dt
    <navkit.sim.Observation.dt>` (whole physics steps, counted exactly: a
    control rate that does not divide the physics rate holds some commands a
    step longer than others, 0.03 s and 0.04 s at 30 Hz of 100 Hz), or
    ``1 / control_rate`` for an observation without ``dt``. The run ends when
    the tracker is done (:attr:`done`). Give the tracker its path
    (``tracker.set_path(route)``) before the run; the adapter only steps it.

    Parameters
    ----------
    tracker : Tracker
        A navkit path tracker (FollowTheCarrot, OnOffTracker,
        RegulatedPurePursuit) or anything with ``step(pose, dt)`` and ``done``
        (see :class:`Tracker`).
    control_rate : float
        The simulation's ``control_rate``, Hz, in (0, 1e6]: its inverse is the
        tracker's ``dt`` for an observation without ``dt``.
    use_estimate : bool, default True
        Track the estimator's pose (True) or the true pose (False). A
        :class:`~navkit.sim.Simulation` without an estimator refuses True
        (``ValueError``): no estimate would come, and the robot would stand
        still until the run timed out.

    Attributes
    ----------
    tracker : Tracker
        The tracker stepped, typed as given (``TrackerController[FollowTheCarrot]``
        has a ``FollowTheCarrot``).

    Raises
    ------
    TypeError
        A ``tracker`` without a ``step(pose, dt)`` method and a ``done`` flag;
        a parameter of the wrong type.
    ValueError
        A ``control_rate`` not > 0, NaN or inf.

    Examples
    --------
    >>> from shapely.geometry import box
    >>> from navkit.control import FollowTheCarrot
    >>> from navkit.kinematics import DiffDrive
    >>> from navkit.sim import Robot, Simulation, World
    >>> tracker = FollowTheCarrot(max_speed=0.5)
    >>> tracker.set_path([[1.0, 1.0], [3.0, 1.0]])
    >>> follow = TrackerController(tracker, control_rate=20.0, use_estimate=False)
    >>> robot = Robot(drive=DiffDrive(track=0.3, wheel_radius=0.05), footprint=0.15)
    >>> trace = Simulation(World([box(0.0, 0.0, 4.0, 2.0).exterior]), robot, follow,
    ...                    start=(1.0, 1.0, 0.0), goal=(3.0, 1.0), control_rate=20.0,
    ...                    stop_at_goal=False).run()
    >>> follow.done, trace.metrics.reached, trace.metrics.collisions
    (True, True, 0)
    """

    __slots__ = ("__weakref__", "_dt", "_use_estimate", "tracker")
    __getstate__ = slot_state  # pickle protocols 0 and 1 too

    def __init__(self, tracker: _T, *, control_rate: float, use_estimate: bool = True) -> None:
        step = getattr(tracker, "step", None)
        # ``done`` may be a property or class attribute (looked up on the type, so a
        # property is not evaluated) or a plain instance attribute.
        has_done = hasattr(type(tracker), "done") or hasattr(tracker, "done")
        if not callable(step) or not has_done:
            raise TypeError(
                f"tracker must have a step(pose, dt) method and a done flag, "
                f"got {type(tracker).__name__}"
            )
        rate = positive_float(control_rate, "control_rate")
        if rate > _MAX_RATE:
            raise ValueError(f"control_rate must be in (0, {_MAX_RATE:g}] Hz, got {rate:g}")
        self.tracker: _T = tracker
        self._dt = 1.0 / rate
        self._use_estimate = as_bool(use_estimate, "use_estimate")

    def __repr__(self) -> str:
        # The rate back from its period, in the fewest digits that give the period
        # back: 1 / (1 / rate) may differ from the rate given in the last bit, and 15
        # digits alone printed 1/3 Hz as 0.333333333333333, a period 3e-15 s longer.
        rate = 1.0 / self._dt
        for digits in range(1, 18):
            shortest = float(f"{rate:.{digits}g}")
            if 1.0 / shortest == self._dt:
                rate = shortest
                break
        return (
            f"{type(self).__name__}({self.tracker!r}, control_rate={rate!r}, "
            f"use_estimate={self._use_estimate})"
        )

    @property
    def done(self) -> bool:
        """Whether the tracker has finished its path (the run then ends).

        Returns
        -------
        bool
            ``tracker.done``.

        Raises
        ------
        TypeError
            ``tracker.done`` has no truth value (an array of several flags, say),
            or is a method (``def done(self)`` without ``@property``).

        Examples
        --------
        >>> from navkit.control import OnOffTracker
        >>> TrackerController(OnOffTracker(), control_rate=10.0).done
        False
        """
        return done_flag(self.tracker.done, "tracker.done")

    def __call__(self, obs: Observation) -> Twist2D:
        """One control step: the tracker's twist at the observed pose.

        Parameters
        ----------
        obs : Observation
            The simulation's observation.

        Returns
        -------
        Twist2D
            The tracker's command, robot frame; zero without an estimate when
            ``use_estimate`` is set.

        Examples
        --------
        >>> from navkit.control import OnOffTracker
        >>> follow = TrackerController(OnOffTracker(), control_rate=10.0)
        >>> follow(Observation(0.0, None, None, None, None, (), None, Pose2D(0.0, 0.0, 0.0)))
        Twist2D(vx=0.0, vy=0.0, omega=0.0)
        """
        if not isinstance(obs, Observation):
            raise TypeError(f"obs must be an Observation, got {type(obs).__name__}")
        pose = obs.estimate if self._use_estimate else obs.true_pose
        if pose is None:
            return Twist2D(0.0, 0.0, 0.0)
        # The time the command will actually be held, for trackers that rate-limit or
        # integrate by dt: the nominal period is up to a physics step off it.
        twist = self.tracker.step(pose, self._dt if obs.dt is None else obs.dt)
        if not isinstance(twist, Twist2D):
            raise TypeError(f"tracker.step must return a Twist2D, got {type(twist).__name__}")
        return twist
