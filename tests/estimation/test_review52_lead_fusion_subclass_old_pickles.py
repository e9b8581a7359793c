"""Old pickles of a PlanarFusion subclass keep what the subclass added (review 52, FRESH).

0a92d0d migrates PlanarFusion pickles made before the filter reduced itself
(1efa428), but the migration dropped a subclass's own attributes: its
``__dict__`` entries and its slots loaded as missing, silently. They are
restored as Python restores them. Real pickle bytes (zlib-compressed) of a
subclass with a ``__dict__`` (``Named``, ``name = "left"``) and one with a slot
(``Slotted``, ``tag = "right"``), after one odometry update; a slow test makes
them again from git.
"""

from __future__ import annotations

import base64
import pickle
import sys
import types
import zlib
from pathlib import Path

import numpy as np
import pytest

from navkit.estimation import PlanarFusion

sys.path.insert(0, str(Path(__file__).resolve().parents[1]))
from old_release import install_module, made_at

MODULE = "review52_fusion_subclasses"
SUBCLASSES = (
    "from navkit.estimation import PlanarFusion\n"
    "class Named(PlanarFusion):\n    pass\n"
    "class Slotted(PlanarFusion):\n    __slots__ = ('tag',)\n"
)
OLD = {
    "908ac92": (
        (
            "eNprYJm6RZIBDHqkilLLMlPLTY3i00qLM/Pz4otLk5JzEouLU4un9LD6JeampkyZPEWzcUrtlB6WPCAX"
            "SOWkppVMKa6dotHDEp9UmjalRyyvNLegUi8+Ob8oVS+3NKckM7GoKLFySg9PfFFqcn5ecUlRaXIJ0Jwe"
            "VrDKKT3seSkQJZOneDO0TnFmTJrSPiVoioY3o7etN1vblAyeHtaUksqCVJAmpjSLKZ0dEHnmHkabKX5+"
            "fl7/gQBMeDOUTEnqdCrgZmBIWn+5M19zpT0DFCw0TVfaZtNin3Vs95eH6+/bK8gcDboesdP+wL/A1mTO"
            "lfZL1Vvus4mWwtXDwIRrYpdbpALg4sos3Ceyjhfvh/FlXdJ6HlaVYOgjBHxzNnif5q+E61OJk9860QBh"
            "D7q9MLD6mOCtWe4tcHG+wBsOTGyY6tDNk94wd4UQkj50f+Ayz85+qbTwjvf2s2aCwEqS/Umuvh1yra8D"
            "d6wj076ZJOurFlnn/rBqCpn6WtD0PYCG1057YvVjNwcXIN58NNCApq+hBmwv6emXuHjYaU+uvmU48uMB"
            "tHyhRKX86IeWHx3Q8s8BHPmR4ThqfnTAkR8b0MxrQMuPSjjyowOO/EhqOsivW5a2x/u+PScz4+rH3oTV"
            "Q8pF4uNvyaI1N2OXvrdXn7zCzPP8e4L67M/bfZn3QNthM9fqC0c9dBw6vy50bJ+o6WDsIte8wUvFQU//"
            "w/FSZxWHfLewA/4yH+ynf0i/c0n3A8nxeiBszcYGiQ9UT9+kAkh9tJPm7iA2fiH14HuS3aORXKbOS4Q+"
            "UtPPaP2Lv/69ejh/687YTSSHz3TpuAIJqU0khw9vQmRQANsWnOFjy1+afJmvB8PcW5UdNvHWOwmGzyaO"
            "jetV7nfCxV22le2Pd0Ho+2dyw1nCeiNG+LxZUb9w597JcHU7Z85jOHL8vT2p7T1Sw2PqNbUX3HqCdoNd"
            "HwSQW96Rr28KsOXdwxafnlgC7C1kcGfwgdryGQKwljwrkCPR6awBVV5PiIYal52Zl1I8BdS94MhPyc9N"
            "LSmqBBvH5F7/Adpr4UgqzQT2MvJAfZTinMxkUDcBqILZD2R1CUiwIBXYcQHpYoTrytAEGQJTwlyZWA5U"
            "wICqAMiFKeAAKogvAnoNqIoJVRUTwiaexOTk1JxUoDpg5wnUP0FVyezNAlVZ2sMXD/MOOMSmILwjhJAp"
            "Si3OTClNzMESnEyQ4BRAbwWAg40pvhCLFjZwX0qi00mBkfxW+UhpzYPDkQseA9hSNBskCgxIbZhDo6hk"
            "irv9TrDSWT2s8eX5RdlY7NCFxVkBx2iLfrRFP9qiH23Rj7boR1v0oy360RY9nVr0TPEFhNqSo/kcfz6H"
            "hmMFnjYkqUkdZGRp25QkPQBd2fSz"
        ),
        (
            "eNprYJm6RZIBDHqkilLLMlPLTY3i00qLM/Pz4otLk5JzEouLU4un9LAH5+SXlKSmTJk8RbNxil/tFI0e"
            "5pLE9Ck9rEWZ6RklU3pY4pNK06b0iOWV5hZU6sUn5xel6uWW5pRkJhYVJVZO6eGJL0pNzs8rLikqTS4B"
            "mtLDClYJNDkvBaJk8hRvhtYpzoxJU9qnBE3R8Gb0tvVma5uSwd3DmlJSWZAK0sSUZjGlswMiz9zDaDPF"
            "z8/P6z8QgAlvhpIpSZ1OBdwMDEnrL3fma660Z4CChabpSttsWuyzju3+8nD9fXsFmaNB1yN22h/4F9ia"
            "zLnSfql6y3020VK4ehiYcE3scotUAFxcmYX7RNbx4v0wvqxLWs/DqhIMfYSAb84G79P8lXB9KnHyWyca"
            "IOxBtxcGVh8TvDXLvQUuzhd4w4GJDVMdunnSG+auEELSh+4PXObZ2S+VFt7x3n7WTBBYSbI/ydW3Q671"
            "deCOdWTaN5NkfdUi69wfVk0hU18Lmr4H0PDaaU+sfuzm4ALEm48GGtD0NdSA7SU9/RIXDzvtydW3DEd+"
            "PICWL5SolB/90PKjA1r+OYAjPzIcR82PDjjyYwOaeQ1o+VEJR350wJEfSU0H+XXL0vZ437fnZGZc/dib"
            "sHpIuUh8/C1ZtOZm7NL39uqTV5h5nn9PUJ/9ebsv8x5oO2zmWn3hqIeOQ+fXhY7tEzUdjF3kmjd4qTjo"
            "6X84Xuqs4pDvFnbAX+aD/fQP6Xcu6X4gOV4PhK3Z2CDxgerpm1QAqY920twdxMYvpB58T7J7NJLL1HmJ"
            "0Edq+hmtf/HXv1cP52/dGbuJ5PCZLh1XICG1ieTw4U2IDApg24IzfGz5S5Mv8/VgmHurssMm3nonwfDZ"
            "xLFxvcr9Tri4y7ay/fEuCH3/TG44S1hvxAifNyvqF+7cOxmubufMeQxHjr+3J7W9R2p4TL2m9oJbT9Bu"
            "sOuDAHLLO/L1TQG2vHvY4tMTS4C9hQyuDF5QWz6DH9aSZwVyxDudNaDK6wnRUOOyM/NSiqeAOhsc+Sn5"
            "uaklRZVg45jc6z9Aey0cSaWZwF5GHrCPwlqck5kM6iYAVTD7gawuAQkWpAK7LSBdjHBdGWBDYEqYKxPL"
            "gQoYUBUAuTAFHEAF8UVArwFVMaGqYkLYxJOYnJyakwpUB+w8gfonqCqZvVmgKkt7+OJh3gGH2BSEd4QQ"
            "MkWpxZkppYk5WIKTCRKcAuitAHCwMcUXYtHCBu5LiXc6KTCS3yofKa15cDhywWMAW4pmg0SBAakNc2gU"
            "lUxxt98JVjqrhzW+PL8oG4sdurA4K+AYbdGPtuhHW/SjLfrRFv1oi360RT/aoqdTi54pvoBQW3I0n+PP"
            "59BwrMDThiQ1qYOMLG2bkqQHAMAZ9GY="
        ),
    ),
    "f96b926": (
        (
            "eNprYJlqJcgABj1SRallmanlpkbxaaXFmfl58cWlSck5icXFqcVTelj9EnNTU6ZMnqLZOKV2Sg9LHpAL"
            "pHJS00qmFNdO0ehhiU8qTZvSI5ZXmltQqRefnF+UqpdbmlOSmVhUlFg5pYcnvig1OT+vuKSoNLkEaE4P"
            "K1jllB72vBSIkslTvBlapzgzJk1pnxI0RcOb0beEsXVKBk8Pa0pJZUEqSA9TmsWUzg6INHMPo80UPz8/"
            "r/9AACa8GUqmJHU6LeBmYEhaf7kzX3OlPQMULDRNV9pm02KfdWz3l4fr79sryBwNuh6x0/7Av8DWZM6V"
            "9kvVW+6ziZbC1cPAhGtil1ukAuDiyizcJ7KOF++H8WVd0noeVpVg6CMEfHM2eJ/mr4TrU4mT3zrRAGEP"
            "ur0wsPqY4K1Z7i1wcb7AGw5MbJjq0M2T3jB3hRCSPnR/4DLPzn6ptPCO9/azZoLASpL9Sa6+HXKtrwN3"
            "rCPTvpkk66sWWef+sGoKmfpa0PQ9gIbXTnti9WM3BxcgbD6x9hMADWjmNNSA3VlCqblUcy9M3zIc+fcA"
            "Wj5SolL+9UPLvw5o+e0AjvzLcBw1/zrgyL8NaOY1oOVfJRz51wFH/iU1XS5ZtOZm7NL39uqTV5h5nn9P"
            "UL39ebsv8x5oO2zmWn3hqIeOQ+fXhY7tEzUdjF3kmjd4qTjo6X84Xuqs4pDvFnbAX+YD1DwYzeBAyPzp"
            "H9LvXNL9QHI8HQhbs7FB4gPV0yupAFIf7aS5OziZGVc/9iZsD6QefE+yezSSy9R5idAHqVeJ929+3bK0"
            "Pd737Yl1/2j9Tt36/erh/K07YzeRHD7TpeMKJKQ2kRw+vAmRQQFsW3CGjy1/afJlvh4Mc29VdtjEW+8k"
            "GD6bODauV7nfCRd32Va2P94Foe+fyQ1nCeuNGOHzZkX9wp17J8PV7Zw5j+HIcdLzydRrai+49QTtBrs+"
            "tHKYbvqmAFvqPWzx6YklwM5FBncGH6jpnyEAbfh7swI5Ep3OGlDl9YRoqHHZmXkpxVNAvRGO/JT83NSS"
            "okqwcUzu9R+gnRyOpNJMYKckD9SlKc7JTAZ1K4AqmP1AVpeABAtSgf0ckC5GuK4MTZAhMCXMlYnlQAUM"
            "qAqAXJgCDqCC+CKg14CqmFBVMSFs4klMTk7NSQWqA/a1QP0ZVJXM3ixQlaU9fPEw74BDbArCO0IImaLU"
            "4syU0sQcLMHJBAlOAfRWADjYmOILsWhh82ZrA2lyUmAkvxU/Ulr/4HDkgscAthTNBokCA1Ib8tAoKiAU"
            "RaMVHP4KDhqOFXiihtQ2BcjI0rYpSXoA3V/bMQ=="
        ),
        (
            "eNprYJlqJcgABj1SRallmanlpkbxaaXFmfl58cWlSck5icXFqcVTetiDc/JLSlJTpkyeotk4xa92ikYP"
            "c0li+pQe1qLM9IySKT0s8UmlaVN6xPJKcwsq9eKT84tS9XJLc0oyE4uKEiun9PDEF6Um5+cVlxSVJpcA"
            "TelhBasEmpyXAlEyeYo3Q+sUZ8akKe1TgqZoeDP6ljC2Tsng7mFNKaksSAXpYUqzmNLZAZFm7mG0meLn"
            "5+f1HwjAhDdDyZSkTqcF3AwMSesvd+ZrrrRngIKFpulK22xa7LOO7f7ycP19ewWZo0HXI3baH/gX2JrM"
            "udJ+qXrLfTbRUrh6GJhwTexyi1QAXFyZhftE1vHi/TC+rEtaz8OqEgx9hIBvzgbv0/yVcH0qcfJbJxog"
            "7EG3FwZWHxO8Ncu9BS7OF3jDgYkNUx26edIb5q4QQtKH7g9c5tnZL5UW3vHeftZMEFhJsj/J1bdDrvV1"
            "4I51ZNo3k2R91SLr3B9WTSFTXwuavgfQ8NppT6x+7ObgAoTNJ9Z+AqABzZyGGrA7Syg1l2ruhelbhiP/"
            "HkDLR0pUyr9+aPnXAS2/HcCRfxmOo+ZfBxz5twHNvAa0/KuEI/864Mi/pKbLJYvW3Ixd+t5effIKM8/z"
            "7wmqtz9v92XeA22HzVyrLxz10HHo/LrQsX2ipoOxi1zzBi8VBz39D8dLnVUc8t3CDvjLfICaB6MZHAiZ"
            "P/1D+p1Luh9IjqcDYWs2Nkh8oHp6JRVA6qOdNHcHJzPj6sfehO2B1IPvSXaPRnKZOi8R+iD1KvH+za9b"
            "lrbH+749se4frd+pW79fPZy/dWfsJpLDZ7p0XIGE1CaSw4c3ITIogG0LzvCx5S9NvszXg2HurcoOm3jr"
            "nQTDZxPHxvUq9zvh4i7byvbHuyD0/TO54SxhvREjfN6sqF+4c+9kuLqdM+cxHDlOej6Zek3tBbeeoN1g"
            "14dWDtNN3xRgS72HLT49sQTYucjgyuAFNf0z+KENf29WIEe801kDqryeEA01LjszL6V4CqhvwpGfkp+b"
            "WlJUCTaOyb3+A7STw5FUmgnslOQBuzSsxTmZyaBuBVAFsx/I6hKQYEEqsJcD0sUI15UBNgSmhLkysRyo"
            "gAFVAZALU8ABVBBfBPQaUBUTqiomhE08icnJqTmpQHXAvhaoP4OqktmbBaqytIcvHuYdcIhNQXhHCCFT"
            "lFqcmVKamIMlOJkgwSmA3goABxtTfCEWLWzebG0gTU4KjOS34kdK6x8cjlzwGMCWotkgUWBAakMeGkUF"
            "hKJotILDX8FBw7ECT9SQ2qYAGVnaNiVJDwCTGNro"
        ),
    ),
}
MAKER = f"""
import base64, json, pickle, sys, types
mod = types.ModuleType({MODULE!r})
sys.modules[mod.__name__] = mod
exec({SUBCLASSES!r}, mod.__dict__)
a = mod.Named(t0=0.0)
a.name = "left"
b = mod.Slotted(t0=0.0)
b.tag = "right"
for f in (a, b):
    f.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
print(json.dumps([base64.b64encode(pickle.dumps(o)).decode() for o in (a, b)]))
"""


@pytest.fixture
def subclasses(monkeypatch: pytest.MonkeyPatch) -> types.ModuleType:
    """The subclasses' module, where the pickles find them."""
    return install_module(monkeypatch, MODULE, SUBCLASSES)


def _check(named: object, slotted: object, module: types.ModuleType) -> None:
    assert type(named) is module.Named
    assert type(slotted) is module.Slotted
    assert named.name == "left"  # type: ignore[attr-defined]
    assert slotted.tag == "right"  # type: ignore[attr-defined]
    for loaded in (named, slotted):
        assert isinstance(loaded, PlanarFusion)
        fresh = PlanarFusion(t0=0.0)
        fresh.update_odometry(0.1, 0.5, 0.1, v_variance=0.01, omega_variance=0.01)
        np.testing.assert_allclose(loaded.x, fresh.x, rtol=0, atol=1e-15)
        got = loaded.update_yaw(0.2, 0.05, variance=1e-3)
        want = fresh.update_yaw(0.2, 0.05, variance=1e-3)
        assert got.accepted and want.accepted
        np.testing.assert_allclose(loaded.x, fresh.x, rtol=0, atol=1e-12)


@pytest.mark.parametrize("commit", sorted(OLD))
def test_an_old_subclass_pickle_keeps_its_own_attributes(
    commit: str, subclasses: types.ModuleType
) -> None:
    named, slotted = (pickle.loads(zlib.decompress(base64.b64decode("".join(text))))
                      for text in OLD[commit])  # fmt: skip
    _check(named, slotted, subclasses)


@pytest.mark.slow
@pytest.mark.parametrize("commit", sorted(OLD))
def test_the_old_subclass_pickles_are_what_those_releases_made(
    commit: str, tmp_path: Path, subclasses: types.ModuleType
) -> None:
    made = made_at(commit, MAKER, tmp_path)
    _check(*(pickle.loads(base64.b64decode(text)) for text in made), subclasses)
