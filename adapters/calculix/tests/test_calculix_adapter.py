"""Tests of the CalculiX adapter: the deck of a tiny scene, a refusal, a missing or broken
ccx, and one physical check (the plane-strain P-wave speed) against its closed form.

Runs under pytest or `python3 -m unittest discover -s adapters/calculix/tests`. The tests that
run ccx skip, saying why, when `ccx` is not on PATH; each ccx run takes about a second.
"""

import json
import math
import os
import shutil
import signal
import stat
import subprocess
import sys
import tempfile
import time
import unittest

HERE = os.path.dirname(os.path.abspath(__file__))
ADAPTER = os.path.dirname(HERE)
sys.path.insert(0, ADAPTER)

import deck  # noqa: E402
import nose  # noqa: E402
import scene as scene_io  # noqa: E402
from mesh import PlateMesh  # noqa: E402

HAVE_CCX = shutil.which("ccx") is not None
NO_CCX = "ccx (CalculiX) is not on PATH: install calculix-ccx to run the adapter's ccx tests"

E, NU, RHO = 207.0e9, 0.3, 7850.0


def pulse_scene():
    """A tiny clamped half plate (4 x 2 q4-full) under a 1 kN pulse, elastic."""
    return {"plate": {"length": 0.2, "width": 0.2, "thickness": 0.02},
            "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": NU},
            "mesh": {"nx": 4, "ny": 2, "element": "q4-full", "model": "half"},
            "load": {"pulse": {"force": 1000.0, "duration": 1.0e-5}},
            "time": {"end": 2.0e-5, "dt": {"cfl": 0.5}},
            "output": {"every": 1.0e-6, "probes": {"A": {"x": 0.1, "y": 0.0}}}}


def bar_scene(ny=16):
    """The wave-speed bar: one q4-full element wide, roller ends, a 1 MPa normal traction step
    on the top, to t = 2.5 h / c_P (verification/cases/wave-speed/strip/bar.yaml)."""
    c = p_wave_speed()
    return {"plate": {"length": 0.2, "width": 0.2, "thickness": 0.02, "ends": "roller"},
            "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": NU},
            "mesh": {"nx": 1, "ny": ny, "element": "q4-full", "model": "half"},
            "load": {"traction": {"normal": 1.0e6, "duration": 1.0}},
            "time": {"end": 1.4 * 0.02 / c, "dt": {"cfl": 0.9}}}


def contact_scene(end=7.0e-4, every=5.0e-6):
    """The Table 1 elastic impact (18 kg at 10 m/s, R = 12.5 mm) with the rigid nose in surface
    contact, on a 20 x 4 half plate (verification/scenes/paper-elastic-surface.yaml, coarse),
    to just past the contact's end (0.6 ms)."""
    return {"plate": {"length": 0.2, "width": 0.179, "thickness": 0.0188},
            "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": NU},
            "mesh": {"nx": 20, "ny": 4, "element": "q4-sri", "model": "half"},
            "load": {"impactor": {"mass": 18.0, "velocity": 10.0, "nose_radius": 0.0125,
                                  "contact": "surface"}},
            "time": {"end": end, "dt": {"cfl": 0.8}},
            "output": {"every": every, "probes": {"A": {"x": 0.1, "y": 0.0}}}}


def p_wave_speed():
    """Plane-strain P-wave speed sqrt(E (1 - nu) / (rho (1 + nu)(1 - 2 nu))), m/s."""
    return math.sqrt(E * (1 - NU) / (RHO * (1 + NU) * (1 - 2 * NU)))


def run_adapter(scene, out_dir, env=None):
    """Write scene.yaml (a stub) and scene.json into out_dir and run the adapter there."""
    with open(os.path.join(out_dir, "scene.json"), "w") as f:
        json.dump(scene, f)
    with open(os.path.join(out_dir, "scene.yaml"), "w") as f:
        f.write("# the scene is scene.json\n")
    return subprocess.run([sys.executable, os.path.join(ADAPTER, "run.py"),
                           os.path.join(out_dir, "scene.yaml"), out_dir],
                          cwd=ADAPTER, capture_output=True, text=True, env=env, timeout=300)


def outputs_present(out_dir):
    """Which of the contract's three files exist in out_dir."""
    return [n for n in ("history.csv", "summary.json", "adapter.json")
            if os.path.exists(os.path.join(out_dir, n))]


def read_json(path):
    """A JSON file's content."""
    with open(path) as f:
        return json.load(f)


def read_history(out_dir):
    """history.csv as a list of {column: float}."""
    with open(os.path.join(out_dir, "history.csv")) as f:
        lines = f.read().split()
    cols = lines[0].split(",")
    return [dict(zip(cols, map(float, l.split(",")))) for l in lines[1:]]


class Tmp(unittest.TestCase):
    """A fresh OUT_DIR per test."""

    def setUp(self):
        self.out = tempfile.mkdtemp(prefix="ccx-adapter-")

    def tearDown(self):
        shutil.rmtree(self.out, ignore_errors=True)


class DeckTest(Tmp):
    def test_tiny_pulse_deck(self):
        s = scene_io.settings(pulse_scene())
        mesh = PlateMesh(s)
        info = deck.write(s, mesh, {"A": (3, 2)}, os.path.join(self.out, "job.inp"), 1e-7, 10)
        with open(os.path.join(self.out, "job.inp")) as f:
            lines = f.read().splitlines()
        self.assertEqual(info["ccx_type"], "CPE4")
        self.assertEqual(info["substitutions"], [])
        nodes = lines[lines.index("*NODE, NSET=NALL") + 1:lines.index(
            "*ELEMENT, TYPE=CPE4, ELSET=EALL")]
        self.assertEqual(len(nodes), 5 * 3)
        self.assertEqual(nodes[4], "5, 0.1, 0.0")  # node (4, 0): mid-span, bottom
        self.assertIn("1, 1, 1, 0.", lines)  # the clamped end x = 0 holds u_x ...
        self.assertIn("1, 2, 2, 0.", lines)  # ... and u_y
        self.assertIn("5, 1, 1, 0.", lines)  # symmetry plane: u_x only
        self.assertNotIn("5, 2, 2, 0.", lines)
        # half model: half the force, down, on the top mid-span node (4, 2) = number 15
        self.assertIn("15, 2, -500.0", lines)
        section = lines.index("*SOLID SECTION, ELSET=EALL, MATERIAL=PLATE")
        self.assertEqual(lines[section + 1], "0.2")  # the width: whole-width forces
        self.assertIn("207000000000.0, 0.3", lines)
        self.assertIn("*DYNAMIC, EXPLICIT", lines)
        self.assertIn("*EL PRINT, ELSET=EPROBE, FREQUENCY=10", lines)

    def test_linear_hardening_is_the_plastic_modulus(self):
        m = {"youngs_modulus": 200e9, "poisson_ratio": 0.3, "density": 7850.0,
             "plasticity": {"yield_stress": 250e6, "hardening": {"linear": 20e9}}}
        (s0, e0), (s1, e1) = deck.flow_curve(m)
        self.assertEqual((s0, e0), (250e6, 0.0))
        self.assertAlmostEqual((s1 - s0) / e1, 200e9 * 20e9 / (200e9 - 20e9), delta=1.0)


class ContactDeckTest(Tmp):
    """The rigid nose's deck (nose.py): its geometry, mass, velocity and contact pair. Fails
    for a nose placed off the top surface, the whole impactor's mass on the half plate, a
    nose left at rest, or an explicit step (which ccx 2.20 stops on with a contact pair)."""

    def test_the_nose_touches_the_top_at_mid_span_and_carries_half_the_mass(self):
        s = scene_io.settings(contact_scene())
        mesh = PlateMesh(s)
        path = os.path.join(self.out, "job.inp")
        info = nose.write_contact(s, mesh, {}, path)
        with open(path) as f:
            lines = f.read().splitlines()
        ring = info["nose"]
        coords = {n: (x, y) for n, x, y, _ in ring.coordinates()}
        cx, cy = 0.1, 0.0188 + 0.0125
        outer = [coords[ring.node(k, 0, 0)] for k in range(len(ring.angles()))]
        for x, y in outer:
            self.assertAlmostEqual(math.hypot(x - cx, y - cy), 0.0125, delta=1e-15)
        self.assertEqual(outer[0], (0.1, 0.0188))  # the lowest point on the top at mid-span
        self.assertAlmostEqual(outer[-1][0], cx - 0.0125, delta=1e-15)  # the quarter circle
        mass = lines.index("*MASS, ELSET=EMASS")
        self.assertEqual(float(lines[mass + 1]), 9.0)  # 18 kg over the half plate's width
        velocity = lines.index("*INITIAL CONDITIONS, TYPE=VELOCITY")
        moving = lines[velocity + 1:velocity + 2 + len(coords)]
        self.assertTrue(all(l.endswith(", 2, -10.0") for l in moving), moving[:3])
        self.assertIn("SPLATE, SNOSE", lines)
        self.assertIn("*DYNAMIC", lines)
        self.assertNotIn("*DYNAMIC, EXPLICIT", lines)
        self.assertEqual(info["dt"], 5.0e-6)  # output.every: rows on k every


class RefusalTest(Tmp):
    def test_nodal_contact_is_not_expressible(self):
        s = pulse_scene()
        s["load"] = {"impactor": {"mass": 18.0, "velocity": 10.0, "nose_radius": 0.0125,
                                  "youngs_modulus": 207e9, "poisson_ratio": 0.3,
                                  "contact_law": {"paper": {"length_unit": 0.001}}}}
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 3, r.stderr)
        last = r.stderr.strip().splitlines()[-1]
        self.assertTrue(last.startswith("not expressible: load.impactor.contact: nodal: "), last)
        self.assertEqual(outputs_present(self.out), [])

    def test_spherical_nose_is_not_expressible(self):
        s = contact_scene()
        s["geometry"] = "axisymmetric"
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("not expressible: load.impactor.contact: surface: in the axisymmetric",
                      r.stderr.strip().splitlines()[-1])

    def test_wall_friction_is_not_expressible(self):
        """The adapter's wall is a boundary condition that slides freely: a scene with
        Coulomb friction on the wall is refused, never run frictionless in silence."""
        s = pulse_scene()
        s["plate"]["ends"] = "free"
        s["load"] = {"wall": {"velocity": 100.0, "friction": 0.1}}
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("not expressible: load.wall.friction: ",
                      r.stderr.strip().splitlines()[-1])
        self.assertEqual(outputs_present(self.out), [])

    def test_rate_law_is_not_expressible(self):
        s = pulse_scene()
        s["material"]["plasticity"] = {"yield_stress": 176e6, "hardening": {"linear": 4.14e9},
                                       "rate": {"cowper_symonds": {"D": 40.0, "q": 5.0}}}
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 3, r.stderr)
        self.assertIn("not expressible: material.plasticity.rate.cowper_symonds",
                      r.stderr.strip().splitlines()[-1])


class BrokenCcxTest(Tmp):
    def fake_ccx(self, body):
        """A PATH whose `ccx` is a shell script with body (and python3's own folder)."""
        bin_dir = os.path.join(self.out, "bin")
        os.makedirs(bin_dir)
        path = os.path.join(bin_dir, "ccx")
        with open(path, "w") as f:
            f.write("#!/bin/sh\n" + body + "\n")
        os.chmod(path, os.stat(path).st_mode | stat.S_IEXEC)
        return dict(os.environ, PATH=bin_dir + os.pathsep + os.path.dirname(sys.executable))

    def assert_failed_cleanly(self, r, *fragments):
        self.assertEqual(r.returncode, 1, r.stderr)
        lines = r.stderr.strip().splitlines()
        self.assertEqual(len(lines), 1, r.stderr)
        self.assertIn(os.path.join(self.out, "scene.yaml"), lines[0])
        for fragment in fragments:
            self.assertIn(fragment, lines[0])
        self.assertEqual(outputs_present(self.out), [])

    def test_missing_ccx(self):
        env = dict(os.environ, PATH=os.path.join(self.out, "empty"))
        r = run_adapter(pulse_scene(), self.out, env)
        self.assert_failed_cleanly(r, "ccx not found on PATH")

    def test_rejected_deck(self):
        env = self.fake_ccx("echo ' *ERROR reading *DYNAMIC. Card image:'; exit 201")
        r = run_adapter(pulse_scene(), self.out, env)
        self.assert_failed_cleanly(r, "exit status 201", "*ERROR reading *DYNAMIC")

    def test_crash_without_output(self):
        env = self.fake_ccx("echo ' SELECTED time increment:1e-7'; echo 'Segmentation fault'")
        r = run_adapter(pulse_scene(), self.out, env)
        self.assert_failed_cleanly(r, "job.dat")

    def test_sigterm_reaches_ccx(self):
        """SIGTERM to the adapter stops its ccx (no stray process) and writes nothing."""
        pid_file = os.path.join(self.out, "ccx.pid")
        env = self.fake_ccx(f"echo $$ > {pid_file}; exec {shutil.which('sleep')} 60")
        s = pulse_scene()
        with open(os.path.join(self.out, "scene.json"), "w") as f:
            json.dump(s, f)
        child = subprocess.Popen([sys.executable, os.path.join(ADAPTER, "run.py"),
                                  os.path.join(self.out, "scene.yaml"), self.out],
                                 cwd=ADAPTER, env=env, stderr=subprocess.PIPE, text=True)
        for _ in range(200):
            if os.path.exists(pid_file) and open(pid_file).read().strip():
                break
            time.sleep(0.05)
        with open(pid_file) as f:
            ccx_pid = int(f.read())
        child.send_signal(signal.SIGTERM)
        _, err = child.communicate(timeout=30)
        self.assertNotEqual(child.returncode, 0)
        self.assertIn("killed by signal", err)
        time.sleep(0.2)
        with self.assertRaises(ProcessLookupError):
            os.kill(ccx_pid, 0)  # gone (reaped by the adapter)
        self.assertEqual(outputs_present(self.out), [])

    @unittest.skipUnless(HAVE_CCX, NO_CCX)
    def test_deck_rejected_by_the_real_ccx(self):
        s = pulse_scene()
        s["material"]["youngs_modulus"] = -1.0  # ccx refuses a negative modulus
        s["time"]["dt"] = {"fixed": 1.0e-7}  # (no wave speed to estimate the step from)
        r = run_adapter(s, self.out)
        self.assert_failed_cleanly(r, "exit status 201", "*ERROR reading *ELASTIC")


@unittest.skipUnless(HAVE_CCX, NO_CCX)
class PhysicsTest(Tmp):
    def test_pulse_scene_writes_the_contract(self):
        r = run_adapter(pulse_scene(), self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_history(self.out)
        self.assertEqual(rows[0]["time_s"], 0.0)
        self.assertAlmostEqual(rows[10]["time_s"], 1.0e-5, delta=1e-12)
        summary = read_json(os.path.join(self.out, "summary.json"))
        self.assertLess(summary["max_plate_displacement_m"], 0.0)
        self.assertEqual(summary["peak_contact_force_N"], 1000.0)
        self.assertIn("A", summary["max_von_mises_Pa"])
        adapter = read_json(os.path.join(self.out, "adapter.json"))
        self.assertEqual(adapter["code"], "calculix")
        self.assertEqual(adapter["input"], ["probe.inp", "job.inp"])

    def test_nose_momentum_is_the_contact_impulse(self):
        """The nose's momentum change m (v0 - v_f) equals the impulse of the contact force read
        from ccx's CF (trapezoid of the rows): measured 3.3e-4 of m v0 here (5 us steps; 1.5e-4
        with 2 us), within 2e-3 (the trapezoid on the rows where ccx cuts its step back). A
        force not doubled for the half model, or the whole mass on the half plate, misses by
        50 %; a sign slip by 200 %. The contact ends before the run does."""
        r = run_adapter(contact_scene(), self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        summary = read_json(os.path.join(self.out, "summary.json"))
        m, v0 = 18.0, 10.0
        change = m * (v0 - summary["final_impactor_velocity_mps"])
        self.assertAlmostEqual((summary["impulse_Ns"] - change) / (m * v0), 0.0, delta=2e-3)
        self.assertLess(summary["final_impactor_velocity_mps"], 0.0)  # the nose rebounds
        self.assertLess(summary["contact_duration_s"], 7.0e-4)
        rows = read_history(self.out)
        self.assertEqual(rows[-1]["contact_force_N"], 0.0)
        self.assertGreater(summary["peak_contact_force_N"], 0.0)

    def test_plane_strain_p_wave_speed(self):
        """Behind the front the mid-plane node moves as u = -(sigma / (rho c)) (t - h / 2c)
        (d'Alembert, before the reflection from the free bottom returns at 3h / 2c): the
        line fitted over [0.8, 1.3] h / c gives c twice, each within 1 % of the closed form
        (a 4 % error in the modulus moves c by 2 %)."""
        r = run_adapter(bar_scene(), self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        c, h, sigma = p_wave_speed(), 0.02, 1.0e6
        pts = [(row["time_s"], row["mid_uy_m"]) for row in read_history(self.out)
               if 0.8 * h / c <= row["time_s"] <= 1.3 * h / c]
        self.assertGreater(len(pts), 5)
        n = len(pts)
        mt, mu = sum(p[0] for p in pts) / n, sum(p[1] for p in pts) / n
        slope = (sum((p[0] - mt) * (p[1] - mu) for p in pts)
                 / sum((p[0] - mt) ** 2 for p in pts))
        t0 = mt - mu / slope
        self.assertAlmostEqual(h / (2 * t0) / c, 1.0, delta=0.01)
        self.assertAlmostEqual(sigma / (RHO * -slope) / c, 1.0, delta=0.01)

    def test_bar_on_the_wall(self):
        """An elastic bar (nu = 0, free ends) landing at V on the wall in plane strain: until
        the front reaches the top at h / c the wall force is rho c V L W (1-D waves,
        c = sqrt(E / rho)) and the top still moves at -V."""
        h, length, width, v = 0.1, 0.02, 0.2, 1.0
        c = math.sqrt(E / RHO)
        s = {"plate": {"length": length, "width": width, "thickness": h, "ends": "free"},
             "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": 0.0},
             "mesh": {"nx": 2, "ny": 20, "element": "q4-full", "model": "half"},
             "load": {"wall": {"velocity": v}},
             "time": {"end": 0.9 * h / c, "dt": {"cfl": 0.5}},
             "output": {"every": 0.05 * h / c}}
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_history(self.out)
        window = [row["contact_force_N"] for row in rows if 0.3 <= row["time_s"] * c / h <= 0.8]
        self.assertGreater(len(window), 5)
        mean = sum(window) / len(window)
        self.assertAlmostEqual(mean / (RHO * c * v * length * width), 1.0, delta=0.03)
        top = [row for row in rows if abs(row["time_s"] * c / h - 0.5) < 0.01][0]
        self.assertAlmostEqual(top["top_uy_m"] / (-v * top["time_s"]), 1.0, delta=0.01)
        summary = read_json(os.path.join(self.out, "summary.json"))
        self.assertAlmostEqual(summary["wall"]["final_length_m"], rows[-1]["bar_length_m"])

    def test_round_bar_on_the_wall(self):
        """The same in the axisymmetric geometry (the hand-built wedge): a round bar of radius
        R, nu = 0, lands at V; until h / c the wall force is rho c V pi R^2 and the top moves
        at -V; the first row's kinetic energy is that of the part still moving, (1 - c t / h) of
        m V^2 / 2 (the ring factor of the wedge)."""
        h, radius, v = 0.1, 0.01, 1.0
        c = math.sqrt(E / RHO)
        s = {"geometry": "axisymmetric",
             "plate": {"length": 2 * radius, "width": 1.0, "thickness": h, "ends": "free"},
             "material": {"density": RHO, "youngs_modulus": E, "poisson_ratio": 0.0},
             "mesh": {"nx": 4, "ny": 40, "element": "q4-full"},
             "load": {"wall": {"velocity": v}},
             "time": {"end": 0.9 * h / c, "dt": {"cfl": 0.5}},
             "output": {"every": 0.05 * h / c}}
        r = run_adapter(s, self.out)
        self.assertEqual(r.returncode, 0, r.stderr)
        rows = read_history(self.out)
        window = [row["contact_force_N"] for row in rows if 0.3 <= row["time_s"] * c / h <= 0.8]
        mean = sum(window) / len(window)
        self.assertAlmostEqual(mean / (RHO * c * v * math.pi * radius ** 2), 1.0, delta=0.03)
        top = [row for row in rows if abs(row["time_s"] * c / h - 0.5) < 0.01][0]
        self.assertAlmostEqual(top["top_uy_m"] / (-v * top["time_s"]), 1.0, delta=0.01)
        mass = RHO * math.pi * radius ** 2 * h
        moving = 1.0 - rows[0]["time_s"] * c / h
        self.assertAlmostEqual(rows[0]["plate_kinetic_J"] / (moving * mass * v ** 2 / 2), 1.0,
                               delta=0.02)


if __name__ == "__main__":
    unittest.main()
