"""The transcribed Taylor impact experiments of `reference-data/experiments/taylor/`: the
three shot files, the digitised outlines and the Johnson-Cook table pass every consistency
check of `check_taylor_data.py` (units in every header, source keys listed in PROVENANCE.md,
unique shot ids, Lf < L0, Dm > D0, Xf <= Lf, speeds inside the ranges and shot counts stated
in PROVENANCE.md, SI lengths equal to the printed values of the source file, outlines
belonging to existing shots), and each check fails on a copy with one typical transcription
slip. Reference: the MATLAB arrays of bbanerjee/HighRateExptData at commit e936876 as
described in PROVENANCE.md, and Johnson & Cook (1983) for the copper constants."""
from __future__ import annotations

import copy
import importlib.util
import subprocess
import sys
from pathlib import Path

import pytest

ROOT = Path(__file__).resolve().parents[2]
HERE = ROOT / "reference-data" / "experiments" / "taylor"


def _module():
    spec = importlib.util.spec_from_file_location("check_taylor_data", HERE / "check_taylor_data.py")
    mod = importlib.util.module_from_spec(spec)
    spec.loader.exec_module(mod)
    return mod


check = _module()
DATA = check.load(HERE)


def row(data, shot_id):
    for _, (_, rows) in data["shots"].items():
        for r in rows:
            if r["shot_id"] == shot_id:
                return r
    raise KeyError(shot_id)


def test_every_check_passes_on_the_transcription():
    assert check.run(DATA) == {name: [] for name in check.CHECKS}


def test_the_counts_match_the_files():
    n = {name: len(rows) for name, (_, rows) in DATA["shots"].items()}
    assert n == {"ofhc-copper.csv": 45, "etp-copper.csv": 26, "al-6061-t6.csv": 59}
    assert len(DATA["profiles"]) == 12


def test_the_script_runs_and_exits_zero():
    done = subprocess.run([sys.executable, str(HERE / "check_taylor_data.py")], capture_output=True, text=True)
    assert done.returncode == 0, done.stdout + done.stderr
    assert "All checks passed." in done.stdout


# one slip per check: (check name, what the slip does)
def _unit_dropped(d):
    h, rows = d["shots"]["ofhc-copper.csv"]
    h[h.index("impact_speed_m_s")] = "impact_speed"
    for r in rows:
        r["impact_speed"] = r.pop("impact_speed_m_s")


def _source_misspelt(d):
    row(d, "wg73-cu-2")["source"] = "wg37"


def _id_repeated(d):
    row(d, "house95-al-3")["shot_id"] = "house95-al-2"


def _lf_above_l0(d):          # Lf and L0 swapped
    r = row(d, "gust82-cu-4")
    r["final_length_m"], r["initial_length_m"] = r["initial_length_m"], r["final_length_m"]


def _dm_below_d0(d):          # foot diameter typed as a radius
    r = row(d, "house95-cu-5")
    r["foot_diameter_m"] = str(float(r["foot_diameter_m"]) / 2)


def _xf_above_lf(d):          # Xf and Lf swapped
    r = row(d, "house95-cu-1")
    r["undeformed_length_m"], r["final_length_m"] = r["final_length_m"], r["undeformed_length_m"]


def _speed_digit_added(d):
    row(d, "wg73-cu-2")["impact_speed_m_s"] = "1230"


def _row_lost(d):
    d["shots"]["al-6061-t6.csv"][1].pop(10)


def _digits_transposed(d):    # 0.835*L0 entered as 0.853*L0 in SI
    row(d, "wg73-cu-2")["final_length_m"] = f"{0.853 * 23.47e-3:.10g}"


def _profile_of_missing_shot(d):
    d["profiles"]["profiles/wg73-cu-60.csv"] = d["profiles"].pop("profiles/wg73-cu-6.csv")


def _profile_in_cm(d):        # outline heights scaled wrongly
    for p in d["profiles"]["profiles/jc83-cu-2.csv"][1]:
        p["z_m"] = str(float(p["z_m"]) * 1.1)
        p["printed_z_mm"] = str(float(p["printed_z_mm"]) * 1.1)


def _jc_constant_slip(d):
    for r in d["constants"][1]:
        if r["material"] == "OFHC copper" and r["parameter"] == "B":
            r["value"] = "2.29e8"


SLIPS = [
    ("units", _unit_dropped),
    ("sources", _source_misspelt),
    ("ids", _id_repeated),
    ("geometry", _lf_above_l0),
    ("geometry", _dm_below_d0),
    ("geometry", _xf_above_lf),
    ("ranges", _speed_digit_added),
    ("counts", _row_lost),
    ("printed", _digits_transposed),
    ("printed", _lf_above_l0),
    ("profiles", _profile_of_missing_shot),
    ("profiles", _profile_in_cm),
    ("constants", _jc_constant_slip),
]


@pytest.mark.parametrize("name,slip", SLIPS, ids=[f"{n}-{s.__name__.strip('_')}" for n, s in SLIPS])
def test_each_check_catches_its_slip(name, slip):
    data = copy.deepcopy(DATA)
    slip(data)
    assert check.CHECKS[name](data) != []


def test_a_printed_value_is_evaluated_in_mm():
    assert check.evaluate_printed("0.895*L0", l0=23.47) == pytest.approx(21.00565, rel=1e-12)
    assert check.evaluate_printed("1.5*D0", d0=7.595) == pytest.approx(11.3925, rel=1e-12)
    assert check.evaluate_printed("0.516*30.9") == pytest.approx(15.9444, rel=1e-12)
    with pytest.raises(ValueError):
        check.evaluate_printed("-1.0")
