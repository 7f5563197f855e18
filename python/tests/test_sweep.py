"""`impact.sweep`: 16 runs of a small scene under overrides, serially, on a local thread
pool and on a Dask LocalCluster(n_workers=2): the same rows bit for bit (wall-clock keys
aside), each equal to `impact.simulate` with the same overrides, and a refused override
recorded as that row's error without stopping the sweep."""
from __future__ import annotations

import math

import pandas
import pytest
from helpers import without_timing

import impact

# 16 runs: yield stress x impactor speed (Pa, m/s).
OVERRIDES = [
    {"material.plasticity.yield_stress": sy, "load.impactor.velocity": v}
    for sy in (1.8e8, 2.2e8, 2.6e8, 3.0e8)
    for v in (5.0, 7.5, 10.0, 12.5)
]
TIMING = set(impact.TIMING_KEYS)


def comparable(frame: pandas.DataFrame) -> list[dict]:
    return [without_timing(r) for r in frame.to_dict("records")]


@pytest.fixture(scope="module")
def serial(small_scene) -> pandas.DataFrame:
    return impact.sweep(small_scene, OVERRIDES, jobs=1)


def test_rows_hold_the_overrides_and_every_summary_key(serial, small_scene):
    assert len(serial) == 16
    summary = impact.simulate(small_scene, overrides=OVERRIDES[5]).summary
    assert list(serial.columns) == [*OVERRIDES[0], *summary, "error"]
    row = serial.iloc[5].to_dict()
    assert pandas.isna(row["error"])
    assert without_timing({k: row[k] for k in summary}) == without_timing(summary)
    # The sweep is not flat: speed and yield stress move the impulse.
    assert serial["impulse_Ns"].nunique() == 16


def test_a_local_pool_equals_serial(serial, small_scene):
    pooled = impact.sweep(small_scene, OVERRIDES, jobs=2)
    assert comparable(pooled) == comparable(serial)


def test_a_failed_run_is_a_row_with_its_error(small_scene):
    frame = impact.sweep(small_scene, [{"material.density": 7000.0},
                                       {"material.density": -1.0},
                                       {}], jobs=2)
    assert list(frame["error"].isna()) == [True, False, True]
    assert "material.density" in frame["error"].iloc[1]
    assert math.isnan(frame["impulse_Ns"].iloc[1])
    assert math.isnan(frame["material.density"].iloc[2])


def test_a_nan_override_is_a_row_with_its_error(small_scene):
    # JSON has no NaN: json.dumps wrote the word NaN, the solver raised ValueError ("overrides:
    # expected value at line 1 column 22") and the whole sweep stopped (bad-input suite).
    frame = impact.sweep(small_scene, [{"material.density": math.nan},
                                       {"material.density": 7000.0},
                                       {"material.plasticity": {"yield_stress": math.inf}}], jobs=2)
    assert list(frame["error"].isna()) == [False, True, False]
    assert "override material.density = nan: must be a finite number" in frame["error"].iloc[0]
    assert "override material.plasticity" in frame["error"].iloc[2]
    with pytest.raises(impact.SceneError, match="override material.density = inf"):
        impact.simulate(small_scene, overrides={"material.density": math.inf})


def test_a_dask_local_cluster_equals_serial(serial, small_scene):
    distributed = pytest.importorskip("distributed")
    with distributed.LocalCluster(n_workers=2, threads_per_worker=1, processes=True,
                                  dashboard_address=None) as cluster, \
            distributed.Client(cluster) as client:
        on_dask = impact.sweep(small_scene, OVERRIDES, client=client)
        by_address = impact.sweep(small_scene, OVERRIDES[:2], client=cluster.scheduler_address)
    assert comparable(on_dask) == comparable(serial)
    assert comparable(by_address) == comparable(serial.iloc[:2])
    with pytest.raises(ValueError, match="jobs"):
        impact.sweep(small_scene, OVERRIDES[:1], client="tcp://127.0.0.1:1", jobs=2)
