"""`impact.simulate` against the `impact simulate` command of the same checkout: the summary
and history bit for bit (wall-clock keys aside), the files written with `out=`, scenes given
as a path, YAML text or a dict, scene errors with the CLI's message, threads, and the GIL
released during a run."""
from __future__ import annotations

import subprocess
import threading
import time

import numpy as np
import pytest
import yaml
from helpers import (assert_same_history, read_history, read_summary,
                     without_timing)

import impact


@pytest.fixture(scope="module")
def cli_run(cli, small_scene, tmp_path_factory):
    out = tmp_path_factory.mktemp("cli")
    subprocess.run([cli, "simulate", small_scene, "--out", out, "--quiet"], check=True)
    return out


def test_summary_and_history_equal_the_cli_bit_for_bit(cli_run, small_scene):
    run = impact.simulate(small_scene)
    cli_summary = read_summary(cli_run / "summary.json")
    assert list(run.summary) == list(cli_summary)
    assert without_timing(run.summary) == without_timing(cli_summary)
    assert run.summary["impulse_Ns"] > 0
    assert_same_history(run.history, read_history(cli_run / "history.csv"))
    assert "time_s" in run.history and "A_von_mises_Pa" in run.history


def test_out_writes_the_cli_files(cli_run, small_scene, tmp_path):
    impact.simulate(str(small_scene), out=tmp_path / "py")
    assert sorted(p.name for p in (tmp_path / "py").iterdir()) == ["history.csv", "summary.json"]
    assert (tmp_path / "py" / "history.csv").read_bytes() == (cli_run / "history.csv").read_bytes()
    assert without_timing(read_summary(tmp_path / "py" / "summary.json")) == without_timing(
        read_summary(cli_run / "summary.json"))


def test_yaml_text_and_dict_scenes_equal_the_file(small_scene):
    text = small_scene.read_text()
    from_file = impact.simulate(small_scene)
    for scene in (text, yaml.safe_load(text)):
        run = impact.simulate(scene)
        assert without_timing(run.summary) == without_timing(from_file.summary)
        assert_same_history(run.history, from_file.history)


def test_to_pandas_has_the_history_columns(small_scene):
    run = impact.simulate(small_scene)
    frame = run.to_pandas()
    assert list(frame.columns) == list(run.history)
    assert np.array_equal(frame["contact_force_N"].to_numpy(), run.history["contact_force_N"])


def test_threads_do_not_change_the_bits(small_scene):
    one = impact.simulate(small_scene, threads=1)
    two = impact.simulate(small_scene, threads=2)
    assert without_timing(one.summary) == without_timing(two.summary)
    assert_same_history(one.history, two.history)
    with pytest.raises(ValueError, match="threads"):
        impact.simulate(small_scene, threads=0)
    # Above 4 x the cores (at most 256): refused at once (10**9 threads never started).
    for n in (10**9, 10**30, -3):
        with pytest.raises(ValueError, match=rf"threads = {n}: must be an integer from 1 to \d+ "):
            impact.simulate(small_scene, threads=n)


def test_a_run_that_falls_back_to_one_thread_keeps_the_bits_and_says_so(monkeypatch):
    """`threads=` reaches the solver's team and its fallback to one thread: forced
    (IMPACT_THREADS_FALLBACK=always, what a busy machine measures), a 4096-element plastic run
    on two threads falls back after its fourth block of 128 steps, tries the team after 8 more
    and falls back again: the one-thread run's bits, and `threads_fallback` says so."""
    from conftest import ROOT

    scene = yaml.safe_load((ROOT / "verification/scenes/example-plastic.yaml").read_text())
    scene["mesh"].update(nx=128, ny=32)
    scene["time"]["end"] = 4e-4
    scene["output"].pop("fields", None)
    scene["output"]["every"] = 1e-5
    one = impact.simulate(scene, threads=1)
    monkeypatch.setenv("IMPACT_THREADS_FALLBACK", "always")
    two = impact.simulate(scene, threads=2)
    assert one.summary["n_steps"] > 13 * 128
    assert "threads_fallback" not in one.summary
    fallback = two.summary["threads_fallback"]
    assert fallback["threads"] == 2 and fallback["steps_on_one_thread"] >= 8 * 128, fallback
    assert without_timing(one.summary) == without_timing(two.summary)
    assert_same_history(one.history, two.history)
    monkeypatch.setenv("IMPACT_THREADS_FALLBACK", "sometimes")
    with pytest.raises(ValueError, match='IMPACT_THREADS_FALLBACK = "sometimes": must be measure'):
        impact.simulate(scene, threads=2)


def test_scene_errors_carry_the_cli_message(cli, small_scene, tmp_path):
    bad = tmp_path / "bad.yaml"
    bad.write_text(small_scene.read_text().replace("density: 7850.0", "density: -7850.0"))
    cli_err = subprocess.run([cli, "simulate", bad, "--out", tmp_path / "o", "--quiet"],
                             capture_output=True, text=True)
    assert cli_err.returncode == 2
    with pytest.raises(impact.SceneError) as e:
        impact.simulate(bad)
    assert cli_err.stderr.strip() == f"error: {e.value}"
    assert str(e.value).startswith(f"{bad}:5:")
    assert "material.density = -7850" in str(e.value)
    assert not (tmp_path / "o").exists()


def test_dict_and_text_errors_name_their_line(small_scene):
    scene = yaml.safe_load(small_scene.read_text())
    scene["material"]["poisson_ratio"] = 0.7
    with pytest.raises(impact.SceneError, match=r"^<dict>:\d+:\d+: material.poisson_ratio = 0.7"):
        impact.simulate(scene)
    text = small_scene.read_text().rstrip("\n") + "\nspeed_of_light: 3.0e8\n"
    line = text.count("\n")
    with pytest.raises(impact.SceneError, match=rf"^<string>:{line}:\d+: .*speed_of_light"):
        impact.simulate(text)
    with pytest.raises(impact.SceneError, match="cannot read the scene"):
        impact.simulate("no/such/scene.yaml")
    with pytest.raises(TypeError):
        impact.simulate(42)


def test_the_gil_is_released_during_a_run(small_scene):
    """Two runs in two threads while this thread counts: with the GIL held by a run, this
    thread would stand still for the whole run; released, it keeps ticking (its longest pause
    is the interpreter's switch interval, 5 ms, plus scheduling), and both runs overlap."""
    scene = yaml.safe_load(small_scene.read_text())
    # A fixed end long enough to watch: 40000 steps, ~0.2 s of a run (5 ms, 10000
    # steps, took 44 ms once the kernels got faster: too short for the check below).
    scene["time"]["end"] = 20.0e-3
    spans: list[tuple[float, float]] = []

    def run():
        t0 = time.perf_counter()
        impact.simulate(scene, threads=1)
        spans.append((t0, time.perf_counter()))

    workers = [threading.Thread(target=run) for _ in range(2)]
    ticks = [time.perf_counter()]
    for w in workers:
        w.start()
    while any(w.is_alive() for w in workers):
        ticks.append(time.perf_counter())
    ticks.append(time.perf_counter())
    shortest = min(e - s for s, e in spans)
    longest_pause = max(np.diff(ticks))
    assert shortest > 0.05, spans
    assert longest_pause < 0.5 * shortest, (longest_pause, spans)
    (s1, e1), (s2, e2) = spans
    assert min(e1, e2) > max(s1, s2), f"runs did not overlap: {spans}"


def test_overrides_equal_the_edited_scene(small_scene):
    text = small_scene.read_text()
    edited = text.replace("yield_stress: 250.0e6", "yield_stress: 2.1e8").replace(
        "mesh: {nx: 20,", "mesh: {nx: 24,")
    assert edited != text
    run = impact.simulate(small_scene, overrides={"material.plasticity.yield_stress": 2.1e8,
                                                  "mesh.nx": np.int64(24)})
    want = impact.simulate(edited)
    assert without_timing(run.summary) == without_timing(want.summary)
    assert_same_history(run.history, want.history)
    assert run.summary["n_elements"] == 24 * 4
    with pytest.raises(impact.SceneError, match="material.density"):
        impact.simulate(small_scene, overrides={"material.density": -1.0})


def test_surface_contact_runs_from_a_dict_scene(small_scene, cli, tmp_path):
    """The surface coupling from Python (a dict scene): the same bits as the CLI, its history
    columns and summary keys, and the nodal coupling's keys refused with it."""
    scene = yaml.safe_load(small_scene.read_text())
    impactor = scene["load"]["impactor"]
    for key in ("youngs_modulus", "poisson_ratio", "contact_law", "indentation_datum", "force_node"):
        impactor.pop(key, None)
    impactor["contact"] = "surface"
    run = impact.simulate(scene)
    assert run.summary["contact_law"] == "surface(kinematic)"
    assert run.summary["max_nodes_in_contact"] >= 1
    assert {"contact_half_width_m", "nodes_in_contact"} <= set(run.history)
    path = tmp_path / "surface.yaml"
    path.write_text(yaml.safe_dump(scene))
    subprocess.run([cli, "simulate", path, "--out", tmp_path / "cli", "--quiet"], check=True)
    assert without_timing(run.summary) == without_timing(read_summary(tmp_path / "cli" / "summary.json"))
    impactor["contact_law"] = {"paper": {"length_unit": 1.0}}
    with pytest.raises(impact.SceneError, match="load.impactor.contact_law"):
        impact.simulate(scene)


def test_rate_laws_run_from_a_dict_scene(small_scene, cli, tmp_path):
    """Cowper-Symonds and Johnson-Cook with heating from Python (a dict scene): the CLI's bits,
    the rate and temperature columns and summary keys, and a bad parameter refused with its
    field."""
    scene = yaml.safe_load(small_scene.read_text())
    plasticity = scene["material"].setdefault(
        "plasticity", {"yield_stress": 250.0e6, "hardening": {"linear": 1.5e9}})
    plasticity["rate"] = {"cowper_symonds": {"D": 40.4, "q": 5}}
    run = impact.simulate(scene)
    assert run.summary["max_plastic_strain_rate_1_s"]["A"] > 0
    assert "A_plastic_strain_rate_1_s" in run.history
    path = tmp_path / "cs.yaml"
    path.write_text(yaml.safe_dump(scene))
    subprocess.run([cli, "simulate", path, "--out", tmp_path / "cli", "--quiet"], check=True)
    assert without_timing(run.summary) == without_timing(read_summary(tmp_path / "cli" / "summary.json"))
    scene["material"]["plasticity"] = {"rate": {"johnson_cook": {
        "A": 250.0e6, "B": 300.0e6, "n": 0.3, "C": 0.0089, "reference_rate": 1.0, "m": 1.1,
        "thermal": {"initial_temperature": 293.15, "melting_temperature": 1813.15,
                    "specific_heat": 473.0, "taylor_quinney": 0.9}}}}
    run = impact.simulate(scene)
    assert run.summary["max_temperature_K"] > 293.15 and run.summary["heat_J"] > 0
    assert "A_temperature_K" in run.history
    scene["material"]["plasticity"]["rate"]["johnson_cook"]["thermal"]["melting_temperature"] = 200.0
    with pytest.raises(impact.SceneError, match="thermal.melting_temperature"):
        impact.simulate(scene)


def test_finite_kinematics_runs_from_a_dict_scene(small_scene, cli, tmp_path):
    """kinematics: finite from Python (a dict scene): the CLI's bits, the summary says so, the
    deflection differs from small kinematics, and a wrong word is refused naming the field."""
    scene = yaml.safe_load(small_scene.read_text())
    small = impact.simulate(scene)
    assert "kinematics" not in small.summary
    scene["kinematics"] = "finite"
    run = impact.simulate(scene)
    assert run.summary["kinematics"] == "finite"
    assert run.summary["max_plate_displacement_m"] != small.summary["max_plate_displacement_m"]
    path = tmp_path / "finite.yaml"
    path.write_text(yaml.safe_dump(scene))
    subprocess.run([cli, "simulate", path, "--out", tmp_path / "cli", "--quiet"], check=True)
    assert without_timing(run.summary) == without_timing(read_summary(tmp_path / "cli" / "summary.json"))
    scene["kinematics"] = "large"
    with pytest.raises(impact.SceneError, match="kinematics"):
        impact.simulate(scene)


@pytest.mark.parametrize("to_folder", [False, True])
def test_ctrl_c_stops_a_run_within_a_second(small_scene, tmp_path, to_folder):
    """A real SIGINT while a long run holds no GIL: KeyboardInterrupt within about a second
    (the loop polls Python's signal handlers every 256 steps), not at the run's end; with
    out=, nothing is left in the folder."""
    import os
    import signal

    scene = yaml.safe_load(small_scene.read_text())
    scene["time"]["end"] = 10.0      # ~1e8 steps: minutes if the interrupt were ignored
    scene["output"] = {"every": 1.0e-3}
    out = tmp_path / "run" if to_folder else None
    timer = threading.Timer(1.0, lambda: os.kill(os.getpid(), signal.SIGINT))
    started = time.monotonic()
    timer.start()
    try:
        with pytest.raises(KeyboardInterrupt):
            impact.simulate(scene, out=out)
    finally:
        timer.cancel()
    assert time.monotonic() - started < 3.0
    assert list(tmp_path.iterdir()) == []
    # The module still works after the interrupt.
    assert impact.simulate(small_scene).summary["n_steps"] > 0


def test_the_rigid_wall_from_a_dict_equals_the_cli(cli, tmp_path):
    """`load: {wall}` (the Taylor bar scene, finite deformation in the ring) given as a dict: the summary with
    its `wall` object and the history (`foot_radius_m`, `bar_length_m`) bit for bit the CLI's;
    a clamped wall scene refused with the CLI's message (field, value, what is allowed)."""
    from conftest import ROOT
    path = ROOT / "verification" / "scenes" / "taylor-bar.yaml"
    subprocess.run([cli, "simulate", path, "--out", tmp_path, "--quiet"], check=True)
    scene = yaml.safe_load(path.read_text())
    run = impact.simulate(scene)
    assert without_timing(run.summary) == without_timing(read_summary(tmp_path / "summary.json"))
    assert_same_history(run.history, read_history(tmp_path / "history.csv"))
    assert run.summary["wall"]["final_length_m"] < 0.0324
    assert "foot_radius_m" in run.history and "bar_length_m" in run.history
    scene["plate"]["ends"] = "clamped"
    with pytest.raises(impact.SceneError, match=r"plate\.ends = clamped: must be `free`"):
        impact.simulate(scene)
