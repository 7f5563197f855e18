"""The scene's JSON Schema (`solver/scene.schema.json`, made from the scene's types by
`impact schema`; its being up to date, its descriptions and units, and the scene files'
modelines are checked in solver/tests/scene_schema.rs) against the repository's scene files,
judged by the reference implementation of JSON Schema in Python (`jsonschema`, pinned in
scripts/requirements.txt):
- the schema is a valid schema of its draft;
- every scene file of the repository validates (a YAML file whose document is a mapping with
  `plate`, `material` and `load`; case files, uncertainty declarations and the bad-input list
  are not scenes), and each folder that holds scenes holds at least one;
- the schema refuses what the reader refuses: an unknown key, an element not allowed;
- the text `Scene::to_yaml` writes of each scene the reader accepts (what another code's
  adapter reads, adapters/README.md) validates too.
Fails for a key the reader accepts and the schema does not know (or the reverse), a word
missing from an enumeration, and a key `to_yaml` writes under another name than the reader's.
"""
from __future__ import annotations

import copy
import json
import re
from pathlib import Path

import jsonschema
import pytest
import yaml

from impact import _impact

ROOT = Path(__file__).resolve().parents[2]
SCHEMA = json.loads((ROOT / "solver" / "scene.schema.json").read_text())
SCENE_DIRS = [
    "verification/scenes/",
    "verification/cases/",
    "scripts/ci-scenes/",
    "scripts/examples/",
    "reference-data/independent/scenes/",
    "solver/tests/scenes/",
    "verification/bad-inputs/base/",
]


class Yaml12Loader(yaml.SafeLoader):
    """PyYAML reads YAML 1.1, where `1e-3` (no dot) is a string; the solver reads YAML 1.2,
    where it is a number. This loader reads such numbers as floats."""


Yaml12Loader.add_implicit_resolver(
    "tag:yaml.org,2002:float",
    re.compile(r"^[-+]?(?:[0-9][0-9_]*)(?:\.[0-9_]*)?[eE][-+]?[0-9]+$"),
    list("-+0123456789"),
)


def yaml_files(folder: Path):
    for p in sorted(folder.iterdir()):
        if p.is_dir():
            if not (p.name.startswith(".") or p.name in ("target", "node_modules")):
                yield from yaml_files(p)
        elif p.suffix in (".yaml", ".yml"):
            yield p


def scene_files() -> list[tuple[str, dict]]:
    """The repository's scene files (paths relative to the root) with their documents."""
    out = []
    for p in yaml_files(ROOT):
        if p.name == "case.yaml":
            continue
        try:
            doc = yaml.load(p.read_text(), Loader=Yaml12Loader)
        except yaml.YAMLError:
            continue  # the bad-input cases include files that are not YAML
        if isinstance(doc, dict) and all(k in doc for k in ("plate", "material", "load")):
            out.append((p.relative_to(ROOT).as_posix(), doc))
    return out


SCENES = scene_files()


@pytest.fixture(scope="module")
def v():
    """The validator of the schema's own draft."""
    return jsonschema.validators.validator_for(SCHEMA)(SCHEMA)


def test_the_schema_is_a_valid_schema_of_its_draft(v):
    v.check_schema(SCHEMA)
    assert v.META_SCHEMA["$schema"] == SCHEMA["$schema"]


@pytest.mark.parametrize("folder", SCENE_DIRS)
def test_each_folder_of_scenes_holds_one(folder: str):
    assert any(path.startswith(folder) for path, _ in SCENES), f"no scene file found under {folder}"


def test_every_scene_file_validates_against_the_schema(v):
    invalid = [
        f"{path}: {e.message} at {'/'.join(map(str, e.absolute_path))}"
        for path, doc in SCENES
        for e in v.iter_errors(doc)
    ]
    assert not invalid, "scene files the schema refuses:\n" + "\n".join(invalid)
    assert len(SCENES) > 60, f"only {len(SCENES)} scene files found"


def test_the_schema_refuses_an_unknown_key_and_an_element_not_allowed(v):
    doc = copy.deepcopy(SCENES[0][1])
    assert v.is_valid(doc)
    doc["plate"]["colour"] = "red"
    assert not v.is_valid(doc), "an unknown key passes"
    doc = copy.deepcopy(SCENES[0][1])
    doc.setdefault("mesh", {})["element"] = "q8"
    assert not v.is_valid(doc), "an unknown element passes"


def test_the_resolved_text_of_every_scene_validates(v):
    resolved, wrong = 0, []
    for path, _ in SCENES:
        try:
            text = _impact.resolved_scene(str(ROOT / path))
        except _impact.SceneError:
            continue  # the bad-input bases and the refused examples
        doc = yaml.load(text, Loader=Yaml12Loader)
        wrong += [f"{path}: {e.message} at {list(e.absolute_path)}" for e in v.iter_errors(doc)]
        resolved += 1
    assert not wrong, "resolved texts the schema refuses:\n" + "\n".join(wrong)
    assert resolved > 60, f"only {resolved} scenes resolved"
