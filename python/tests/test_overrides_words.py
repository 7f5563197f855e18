"""Overrides whose dotted key goes through a word of the scene (defect reported by a user:
`impact.sweep` could not set `load.impactor.contact.surface.enforcement` on the shipped scene
verification/scenes/paper-elastic-surface.yaml, which writes `contact: surface`, a word). The
word becomes the map it is short for (solver/scene.schema.json: `surface` is
`{surface: ~}`, the surface coupling with its defaults), so each row equals, bit for bit (wall
times aside), the run of the same scene written with that map; a key through a word that is
no such short form is refused with the forms the scene allows and the override to write
instead; a value the scene refuses is named with the key as given."""
from __future__ import annotations

import pytest
from helpers import ROOT, without_timing

import impact

SURFACE = ROOT / "verification" / "scenes" / "paper-elastic-surface.yaml"
ELASTIC = ROOT / "verification" / "scenes" / "paper-elastic.yaml"
SMALL = {"mesh.nx": 20, "mesh.ny": 4}
WORD = "    contact: surface\n"


def written_as(contact: str) -> str:
    """paper-elastic-surface.yaml's text with `contact: surface` written as ``contact``."""
    text = SURFACE.read_text()
    assert text.count(WORD) == 1
    return text.replace(WORD, f"    contact: {contact}\n")


def test_a_key_through_a_word_sets_the_map_it_is_short_for():
    rows = impact.sweep(SURFACE, [
        {**SMALL, "load.impactor.contact.surface.enforcement": "penalty"},
        {**SMALL, "load.impactor.contact.surface.enforcement": "penalty",
         "load.impactor.contact.surface.penalty_scale": 0.2},
        {**SMALL, "load.impactor.contact.surface.enforcement": "kinematic"},
    ], jobs=2)
    assert rows["error"].isna().all(), list(rows["error"])
    assert list(rows["contact_law"]) == ["surface(penalty, penalty_scale=0.1)",
                                         "surface(penalty, penalty_scale=0.2)", "surface(kinematic)"]
    for i, contact in enumerate(["{surface: {enforcement: penalty}}",
                                 "{surface: {enforcement: penalty, penalty_scale: 0.2}}",
                                 "{surface: {enforcement: kinematic}}"]):
        as_map = impact.simulate(written_as(contact), threads=1, overrides=SMALL).summary
        row = {k: rows.iloc[i][k] for k in as_map}
        assert without_timing(row) == without_timing(as_map)


def test_a_key_through_another_word_says_how_to_write_it():
    nodal = ELASTIC.read_text().replace("    contact_law:", "    contact: nodal\n    contact_law:", 1)
    with pytest.raises(impact.SceneError) as e:
        impact.simulate(nodal, overrides={"load.impactor.contact.surface.enforcement": "penalty"})
    assert str(e.value).startswith(
        '<string>: override load.impactor.contact.surface.enforcement = "penalty": '
        "`load.impactor.contact` is the word `nodal` in this scene, which holds no keys: to set "
        "`load.impactor.contact.surface.enforcement`, set `load.impactor.contact` whole, e.g. "
        '{"load.impactor.contact":{"surface":{"enforcement":"penalty"}}} (load.impactor.contact: '
        "How the nose meets the plate"), str(e.value)
    assert "`{surface: {enforcement, penalty_scale}}`" in str(e.value)


def test_a_value_refused_through_a_word_names_the_key_as_given():
    rows = impact.sweep(SURFACE, [{"load.impactor.contact.surface.enforcement": "bogus"}], jobs=1)
    assert rows["error"][0].startswith(
        f'{SURFACE}: override load.impactor.contact.surface.enforcement = "bogus": '
        "load.impactor.contact.surface.enforcement: unknown variant `bogus`, expected one of "
        "kinematic, penalty"), rows["error"][0]
