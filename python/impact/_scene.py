"""A scene given as a path, YAML text or a dict, turned into (YAML text, source name)."""
from __future__ import annotations

import json
import math
import os
from typing import Any, Mapping, Union

from . import _impact

SceneLike = Union[str, "os.PathLike[str]", Mapping[str, Any]]


def scene_text(scene: SceneLike) -> tuple[str, str]:
    """The scene's YAML text and the name its error messages use.

    - a path (``str`` or ``os.PathLike``): the file's text, named by the path;
    - a ``str`` with a line break or opening with ``{``: YAML text, named ``<string>``;
    - a mapping with the scene's keys: written as JSON (a subset of YAML, one key per line,
      so messages point at a line), named ``<dict>``.
    """
    if isinstance(scene, Mapping):
        return _yaml_json(scene), "<dict>"
    if isinstance(scene, os.PathLike):
        path = os.fspath(scene)
        return _impact.read_scene(path), path
    if isinstance(scene, str):
        if "\n" in scene or scene.lstrip().startswith("{"):
            return scene, "<string>"
        return _impact.read_scene(scene), scene
    raise TypeError(
        f"scene must be a path, YAML text or a dict of the scene's keys, not {type(scene).__name__}"
    )


def overrides_json(overrides: Mapping[str, Any] | None, source: str = "<overrides>") -> str | None:
    """Overrides (dotted scene keys -> values) as the JSON text the solver reads, or None.

    A NaN or infinity (JSON has none) is refused here with the solver's words for an override
    (``SceneError``: ``source: override key = nan: must be a finite number``)."""
    if not overrides:
        return None
    if not isinstance(overrides, Mapping):
        raise TypeError("overrides must be a dict of dotted scene keys, e.g. {'time.dt.cfl': 0.5}")
    for key, value in overrides.items():
        if not isinstance(key, str):
            raise TypeError(f"override key {key!r} is not a dotted scene key (str)")
        if _non_finite(_marked(value)):
            raise _impact.SceneError(f"{source}: override {key} = {value!r}: must be a finite number")
    return json.dumps(dict(overrides), default=_plain)


def _non_finite(value: Any) -> bool:
    """Whether a marked value (see _marked) holds a NaN or an infinity."""
    if isinstance(value, str):
        return value.startswith(_MARK)
    if isinstance(value, Mapping):
        return any(_non_finite(v) for v in value.values())
    if isinstance(value, list):
        return any(_non_finite(v) for v in value)
    return False


# JSON has no NaN or infinity: json.dumps writes the bare words NaN and Infinity, which YAML
# reads as strings ("expected a number"). Non-finite floats are written as YAML's own .nan,
# .inf and -.inf, so that the scene's rules refuse them by name ("must be a finite number").
_NON_FINITE = {"nan": ".nan", "inf": ".inf", "-inf": "-.inf"}
_MARK = "\x00impact-non-finite:"


def _yaml_json(scene: Mapping[str, Any]) -> str:
    """The mapping as JSON text (one key per line), non-finite floats as YAML's .nan/.inf."""
    text = json.dumps(_marked(scene), indent=2, default=_plain)
    for word, yaml_word in _NON_FINITE.items():
        text = text.replace(json.dumps(_MARK + word), yaml_word)
    return text


def _marked(value: Any) -> Any:
    """``value`` with each non-finite float replaced by a marker string."""
    if isinstance(value, float) and not math.isfinite(value):
        return _MARK + ("nan" if math.isnan(value) else "inf" if value > 0 else "-inf")
    if isinstance(value, Mapping):
        return {k: _marked(v) for k, v in value.items()}
    if isinstance(value, (list, tuple)):
        return [_marked(v) for v in value]
    if hasattr(value, "tolist"):
        return _marked(value.tolist())
    return value


def _plain(value: Any) -> Any:
    """numpy scalars and arrays (``np.int64(8)``, ``np.array([...])``) as plain numbers/lists."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{value!r} ({type(value).__name__}) is not a scene value")
