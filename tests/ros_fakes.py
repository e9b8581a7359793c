"""Stand-ins for the rclpy (ROS 2) message classes navkit's users hold, without ROS.

Each class behaves as the class ``rosidl_generator_py`` generates (its
``_msg.py.em`` template, Humble to Rolling) behaves at runtime, field by field:

* every field is a property whose setter checks the value as the generated
  setter does with field checks on (the default): a ``float32``/``float64``
  field takes a Python ``float`` only (``numpy.float64`` is one,
  ``numpy.float32`` and ``int`` are not), an integer field a Python ``int``
  (``numpy.int64`` is not) within its type's range, a nested message an
  instance of its class — anything else raises ``AssertionError``;
* a sequence of a numeric type (``float32[] ranges``, ``int8[] data``) is
  stored as an ``array.array`` of its type code (``'f'``, ``'b'``): the setter
  keeps an ``array.array`` of that code as it is and copies a ``Sequence`` of
  Python numbers into a new one; a NumPy array is neither (assertion error);
* a fixed-size numeric array (``float64[9] orientation_covariance``,
  ``float64[36] covariance``) is a ``numpy.ndarray`` of its dtype and size;
* ``geometry_msgs/Quaternion`` defaults to ``w = 1.0``, every other number to 0.

:func:`deliver` gives the message as a subscriber receives it: ``float32``
fields rounded to float32 (still Python floats: ``0.05`` arrives as
``0.05000000074505806``), sequences as new ``array.array`` objects of their
type code, fixed arrays as new NumPy arrays.
"""

from __future__ import annotations

import array
import math
import struct
from collections import UserList, UserString
from collections.abc import Sequence, Set
from typing import Any, ClassVar

import numpy as np

_FLOAT32_MAX = 3.402823466e38
_FLOAT64_MAX = 1.7976931348623157e308
_INT_BOUNDS = {
    "int8": (-(2**7), 2**7),
    "uint8": (0, 2**8),
    "int32": (-(2**31), 2**31),
    "uint32": (0, 2**32),
}
_TYPECODES = {"float": "f", "double": "d", "int8": "b", "uint8": "B"}


def _round_float32(value: float) -> float:
    return float(struct.unpack("f", struct.pack("f", value))[0])


class _Field:
    """One field: ``kind`` is a rosidl type name, ``sequence<T>``, ``T[N]`` or a class."""

    def __init__(self, kind: Any, default: Any = None) -> None:
        self.kind = kind
        self.default = default

    def __set_name__(self, owner: type, name: str) -> None:
        self.name = name
        self.slot = "_" + name

    def __get__(self, obj: Any, objtype: type | None = None) -> Any:
        if obj is None:
            return self
        return getattr(obj, self.slot)

    def fresh_default(self) -> Any:
        kind = self.kind
        if isinstance(kind, type):
            return kind()
        if kind.startswith("sequence<"):
            inner = kind[len("sequence<") : -1]
            return array.array(_TYPECODES[inner]) if inner in _TYPECODES else []
        if "[" in kind:
            return np.zeros(int(kind[kind.index("[") + 1 : -1]), dtype=np.float64)
        if kind == "string":
            return ""
        if kind in ("float", "double"):
            return float(self.default or 0.0)
        return int(self.default or 0)

    def __set__(self, obj: Any, value: Any) -> None:
        name, kind = self.name, self.kind
        if isinstance(kind, type):
            assert isinstance(value, kind), (
                f"The '{name}' field must be a sub message of type '{kind.__name__}'"
            )
        elif kind.startswith("sequence<"):
            inner = kind[len("sequence<") : -1]
            code = _TYPECODES.get(inner)
            if code is not None and isinstance(value, array.array):
                assert value.typecode == code, (
                    f"The '{name}' array.array() must have the type code of '{code}'"
                )
                setattr(obj, self.slot, value)
                return
            assert isinstance(value, (Sequence, Set, UserList)) and not isinstance(
                value, (str, UserString)
            ), f"The '{name}' field must be a set or sequence"
            if code is None:
                assert all(isinstance(v, _CLASSES[inner]) for v in value), (
                    f"The '{name}' field must be a set or sequence and each value of type '{inner}'"
                )
                setattr(obj, self.slot, value)
                return
            if inner in _INT_BOUNDS:
                lo, hi = _INT_BOUNDS[inner]
                assert all(isinstance(v, int) for v in value) and all(
                    lo <= v < hi for v in value
                ), f"The '{name}' field must be a set or sequence and each integer in range"
            else:
                bound = _FLOAT32_MAX if inner == "float" else _FLOAT64_MAX
                assert all(isinstance(v, float) for v in value) and all(
                    not (v < -bound or v > bound) or math.isinf(v) for v in value
                ), f"The '{name}' field must be a set or sequence and each value of type 'float'"
            setattr(obj, self.slot, array.array(code, value))
            return
        elif "[" in kind:
            size = int(kind[kind.index("[") + 1 : -1])
            if isinstance(value, np.ndarray):
                assert value.dtype == np.float64, (
                    f"The '{name}' numpy.ndarray() must have the dtype of 'numpy.float64'"
                )
                assert value.size == size, (
                    f"The '{name}' numpy.ndarray() must have a size of {size}"
                )
                setattr(obj, self.slot, value)
                return
            assert (
                isinstance(value, (Sequence, Set, UserList))
                and not isinstance(value, (str, UserString))
                and len(value) == size
                and all(isinstance(v, float) for v in value)
            ), f"The '{name}' field must be a set or sequence with length {size}"
            value = np.array(value, dtype=np.float64)
        elif kind == "string":
            assert isinstance(value, str), f"The '{name}' field must be of type 'str'"
        elif kind in ("float", "double"):
            bound = _FLOAT32_MAX if kind == "float" else _FLOAT64_MAX
            assert isinstance(value, float), f"The '{name}' field must be of type 'float'"
            assert not (value < -bound or value > bound) or math.isinf(value), (
                f"The '{name}' field must be a {kind} in [{-bound}, {bound}]"
            )
        else:
            lo, hi = _INT_BOUNDS[kind]
            assert isinstance(value, int), f"The '{name}' field must be of type 'int'"
            assert lo <= value < hi, f"The '{name}' field must be an integer in [{lo}, {hi - 1}]"
        setattr(obj, self.slot, value)


class _Message:
    """Base of the fakes: keyword construction as rosidl's ``__init__(**kwargs)``."""

    __slots__ = ()
    _FIELDS: ClassVar[tuple[str, ...]] = ()

    def __init__(self, **kwargs: Any) -> None:
        unknown = sorted(k for k in kwargs if k not in self._FIELDS)
        assert not unknown, "Invalid arguments passed to constructor: " + ", ".join(unknown)
        for name in self._FIELDS:
            field = type(self).__dict__[name]
            setattr(self, name, kwargs[name] if name in kwargs else field.fresh_default())

    def __eq__(self, other: object) -> bool:
        if type(other) is not type(self):
            return False
        for name in self._FIELDS:
            a, b = getattr(self, name), getattr(other, name)
            if isinstance(a, np.ndarray):
                if not np.array_equal(a, b):
                    return False
            elif a != b:
                return False
        return True

    __hash__ = None  # type: ignore[assignment]

    @classmethod
    def get_fields_and_field_types(cls) -> dict[str, str]:
        out = {}
        for name in cls._FIELDS:
            kind = cls.__dict__[name].kind
            out[name] = kind.__name__ if isinstance(kind, type) else kind
        return out


def _message(name: str, fields: dict[str, Any]) -> type[_Message]:
    namespace: dict[str, Any] = {
        "__slots__": tuple("_" + f for f in fields),
        "_FIELDS": tuple(fields),
    }
    for field_name, kind in fields.items():
        namespace[field_name] = kind if isinstance(kind, _Field) else _Field(kind)
    cls = type(name, (_Message,), namespace)
    _CLASSES[name] = cls
    return cls


_CLASSES: dict[str, type[_Message]] = {}

# builtin_interfaces / std_msgs
Time = _message("Time", {"sec": "int32", "nanosec": "uint32"})
Header = _message("Header", {"stamp": Time, "frame_id": "string"})

# geometry_msgs
Point = _message("Point", {"x": "double", "y": "double", "z": "double"})
Vector3 = _message("Vector3", {"x": "double", "y": "double", "z": "double"})
Quaternion = _message(
    "Quaternion",
    {"x": "double", "y": "double", "z": "double", "w": _Field("double", default=1.0)},
)
Pose = _message("Pose", {"position": Point, "orientation": Quaternion})
PoseStamped = _message("PoseStamped", {"header": Header, "pose": Pose})
PoseWithCovariance = _message("PoseWithCovariance", {"pose": Pose, "covariance": "double[36]"})
Twist = _message("Twist", {"linear": Vector3, "angular": Vector3})
TwistWithCovariance = _message("TwistWithCovariance", {"twist": Twist, "covariance": "double[36]"})

# nav_msgs
MapMetaData = _message(
    "MapMetaData",
    {
        "map_load_time": Time,
        "resolution": "float",
        "width": "uint32",
        "height": "uint32",
        "origin": Pose,
    },
)
OccupancyGrid = _message(
    "OccupancyGrid", {"header": Header, "info": MapMetaData, "data": "sequence<int8>"}
)
Odometry = _message(
    "Odometry",
    {
        "header": Header,
        "child_frame_id": "string",
        "pose": PoseWithCovariance,
        "twist": TwistWithCovariance,
    },
)
Path = _message("Path", {"header": Header, "poses": "sequence<PoseStamped>"})

# sensor_msgs
LaserScan = _message(
    "LaserScan",
    {
        "header": Header,
        "angle_min": "float",
        "angle_max": "float",
        "angle_increment": "float",
        "time_increment": "float",
        "scan_time": "float",
        "range_min": "float",
        "range_max": "float",
        "ranges": "sequence<float>",
        "intensities": "sequence<float>",
    },
)
Imu = _message(
    "Imu",
    {
        "header": Header,
        "orientation": Quaternion,
        "orientation_covariance": "double[9]",
        "angular_velocity": Vector3,
        "angular_velocity_covariance": "double[9]",
        "linear_acceleration": Vector3,
        "linear_acceleration_covariance": "double[9]",
    },
)


def deliver(msg: Any) -> Any:
    """``msg`` as a subscriber receives it (serialised and deserialised)."""
    cls = type(msg)
    out = cls.__new__(cls)
    for name in cls._FIELDS:
        kind = cls.__dict__[name].kind
        value = getattr(msg, name)
        if isinstance(kind, type):
            value = deliver(value)
        elif kind.startswith("sequence<"):
            inner = kind[len("sequence<") : -1]
            if inner in _TYPECODES:
                code = _TYPECODES[inner]
                value = array.array(code, array.array(code, value).tobytes())
            else:
                value = [deliver(v) for v in value]
        elif "[" in kind:
            value = np.array(value, dtype=np.float64)
        elif kind == "float":
            value = _round_float32(value)
        object.__setattr__(out, "_" + name, value)
    return out


def stamp(seconds: int, nanoseconds: int) -> Any:
    """A ``builtin_interfaces/Time``."""
    return Time(sec=seconds, nanosec=nanoseconds)


def pose_msg(x: float, y: float, yaw: float) -> Any:
    """A planar ``geometry_msgs/Pose`` (z = 0, rotation about z by ``yaw``)."""
    return Pose(
        position=Point(x=float(x), y=float(y), z=0.0),
        orientation=Quaternion(x=0.0, y=0.0, z=math.sin(0.5 * yaw), w=math.cos(0.5 * yaw)),
    )
