"""A scene given as a path, YAML text or a dict, turned into (YAML text, source name)."""
from __future__ import annotations

import json
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
        return json.dumps(scene, indent=2, default=_plain), "<dict>"
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


def overrides_json(overrides: Mapping[str, Any] | None) -> str | None:
    """Overrides (dotted scene keys -> values) as the JSON text the solver reads, or None."""
    if not overrides:
        return None
    if not isinstance(overrides, Mapping):
        raise TypeError("overrides must be a dict of dotted scene keys, e.g. {'time.dt.cfl': 0.5}")
    for key in overrides:
        if not isinstance(key, str):
            raise TypeError(f"override key {key!r} is not a dotted scene key (str)")
    return json.dumps(dict(overrides), default=_plain)


def _plain(value: Any) -> Any:
    """numpy scalars and arrays (``np.int64(8)``, ``np.array([...])``) as plain numbers/lists."""
    if hasattr(value, "tolist"):
        return value.tolist()
    raise TypeError(f"{value!r} ({type(value).__name__}) is not a scene value")
