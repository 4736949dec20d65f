#!/usr/bin/env python3
"""feltd's measuring commands checked from outside, with their own reader (Python's csv and XML
parsers, not feltd's writers) and against closed forms:

- `feltd run --trace`: the CSV's energies add up, its gravitational energy, bounding box and
  centre of mass agree with the positions of the VTK frames, the frames sit at the CSV's times,
  and two runs give the same state hashes;
- `feltd compare` of a scene against itself reports zero error;
- `feltd compare` and `feltd sweep` of RK4 on a particle on an anchor spring report the position
  error and the energy drift that RK4's amplification factor gives;
- `feltd sweep --search` brackets RK4's stability limit on a stiff anchor spring, ωh = 2√2.

Environment: FELTD (the binary), FELT_SCENE_DIR (scenes/)."""

import cmath
import csv
import json
import math
import os
import subprocess
import sys
import tempfile
import unittest
import xml.etree.ElementTree as ET

FELTD = os.environ["FELTD"]
SCENES = os.environ["FELT_SCENE_DIR"]


def feltd(*args):
    done = subprocess.run([FELTD, *args], capture_output=True, text=True, timeout=120)
    if done.returncode != 0:
        raise AssertionError(f"feltd {' '.join(args)}: exit {done.returncode}\n{done.stderr}")
    return done.stdout


def read_vtp_points(path):
    """Every piece's points of a VTK PolyData file: {name: [(x, y, z), ...]}."""
    pieces = {}
    for piece in ET.parse(path).getroot().iter("Piece"):
        values = [float(v) for v in piece.find("Points/DataArray").text.split()]
        pieces[piece.get("Name")] = [tuple(values[i:i + 3]) for i in range(0, len(values), 3)]
    return pieces


# The oscillator: particle 0 of a 2 x 2 grid (the others pinned, every spring off, no gravity
# and no drag) on an anchor spring; it starts X0 from its target, at rest.
MASS = 0.1     # kg per particle
K = 40.0       # N/m
X0 = -0.01     # m
OMEGA = math.sqrt(K / MASS)
H = 0.01       # s: omega h = 0.2
DURATION = 1.0


def oscillator_scene(directory, stiffness=K, health=None):
    scene = {
        "name": "anchor_oscillator", "time_step": H, "gravity": [0, 0, 0],
        "bodies": [{
            "type": "cloth", "name": "particle",
            "grid": {"width": 1, "height": 1, "nx": 2, "ny": 2, "center": [0, 0, 0],
                     "plane": "xy"},
            "mass": 4 * MASS, "drag": 0, "integrator": "rk4", "pin": [1, 2, 3],
            "springs": {kind: {"enabled": False} for kind in ("structural", "shear", "bend")},
            # particle 0 is at (-0.5, 0.5, 0)
            "anchors": [{"particle": 0, "target": [-0.5 - X0, 0.5, 0], "stiffness": stiffness,
                         "damping": 0}],
        }],
    }
    if health is not None:
        scene["health"] = health
    path = os.path.join(directory, "oscillator.json")
    with open(path, "w") as f:
        json.dump(scene, f)
    return path


def rk4_factor(h):
    """RK4's amplification of u = x + i v/omega, for which u' = -i omega u: R(z), z = -i omega h."""
    z = -1j * OMEGA * h
    return 1 + z + z * z / 2 + z ** 3 / 6 + z ** 4 / 24


def rk4_displacement(h, t):
    """x − target after t / h RK4 steps of h from rest at X0."""
    return (rk4_factor(h) ** round(t / h) * X0).real


def rk4_drift(h, t):
    """The mechanical energy's change after t / h steps: |R|² per step on ½ k |u|²."""
    return 0.5 * K * X0 * X0 * (abs(rk4_factor(h)) ** (2 * round(t / h)) - 1)


def expected_errors(h, h_ref, interval, samples):
    """RMS (over the 4 particles, 3 of them pinned) and max distance between RK4 at h and at
    h_ref over the samples, and the distance at the last."""
    d = [abs(rk4_displacement(h, k * interval) - rk4_displacement(h_ref, k * interval))
         for k in range(1, samples + 1)]
    return math.sqrt(sum(x * x for x in d) / (4 * samples)), max(d), d[-1]


class Trace(unittest.TestCase):
    def test_trace_reads_back(self):
        with tempfile.TemporaryDirectory() as tmp:
            steps, every = 40, 10
            for name in ("a", "b"):
                feltd("run", os.path.join(SCENES, "default.json"), "--steps", str(steps),
                      "--trace", os.path.join(tmp, name), "--every", str(every))
            with open(os.path.join(tmp, "a", "trace.csv")) as f:
                rows = list(csv.DictReader(f))
            with open(os.path.join(tmp, "b", "trace.csv")) as f:
                again = list(csv.DictReader(f))
            self.assertEqual(len(rows), steps + 1)  # one body; the start and every step
            self.assertEqual([r["state_hash"] for r in rows], [r["state_hash"] for r in again])
            self.assertEqual(len({r["state_hash"] for r in rows}), steps + 1)
            e0 = float(rows[0]["energy"])
            for n, r in enumerate(rows):
                self.assertEqual(int(r["step"]), n)
                self.assertAlmostEqual(float(r["time"]), n * 0.001, places=12)
                parts = float(r["kinetic"]) + float(r["elastic"]) + float(r["gravitational"])
                self.assertAlmostEqual(float(r["energy"]), parts, places=12)
                self.assertAlmostEqual(float(r["drift"]), float(r["energy"]) - e0, places=12)
                self.assertEqual(r["body"], "curtain")
                self.assertGreaterEqual(float(r["max_strain"]), 0)
            # the curtain falls from rest: it gains kinetic energy and loses height
            self.assertGreater(float(rows[-1]["kinetic"]), 0)
            self.assertLess(float(rows[-1]["com_y"]), float(rows[0]["com_y"]))

            series = ET.parse(os.path.join(tmp, "a", "frames.pvd")).getroot()
            data_sets = list(series.iter("DataSet"))
            self.assertEqual(len(data_sets), steps // every + 1)
            particle_mass = 0.5 / 400  # default.json: 0.5 kg over 20 x 20 particles
            for k, data_set in enumerate(data_sets):
                row = rows[k * every]
                self.assertAlmostEqual(float(data_set.get("timestep")), float(row["time"]),
                                       places=12)
                points = read_vtp_points(os.path.join(tmp, "a", data_set.get("file")))["curtain"]
                self.assertEqual(len(points), 400)
                # float32 positions near 1 m: 1e-6 m
                for axis, name in enumerate("xyz"):
                    coords = [p[axis] for p in points]
                    self.assertAlmostEqual(min(coords), float(row["min_" + name]), delta=1e-6)
                    self.assertAlmostEqual(max(coords), float(row["max_" + name]), delta=1e-6)
                    self.assertAlmostEqual(sum(coords) / 400, float(row["com_" + name]),
                                           delta=1e-6)
                # −Σ m g·x with g = (0, −9.81, 0)
                gravitational = particle_mass * 9.81 * sum(p[1] for p in points)
                self.assertAlmostEqual(gravitational, float(row["gravitational"]), delta=1e-5)


class Compare(unittest.TestCase):
    def test_a_scene_against_itself_has_no_error(self):
        out = json.loads(feltd("compare", os.path.join(SCENES, "default.json"), "--duration",
                               "0.1", "--reference", "time_step=0.001", "--json"))
        self.assertEqual(out["samples"], 100)
        for body in out["bodies"]:
            self.assertEqual((body["rms_error"], body["max_error"], body["end_error"]), (0, 0, 0))
        self.assertEqual(out["run"]["energy_drift"], out["reference"]["energy_drift"])
        self.assertNotEqual(out["run"]["energy_drift"], 0)  # the curtain did move

    def test_rk4_on_an_anchor_spring_errs_as_its_amplification_factor_says(self):
        with tempfile.TemporaryDirectory() as tmp:
            out = json.loads(feltd("compare", oscillator_scene(tmp), "--duration", str(DURATION),
                                   "--json"))
        h_ref = H / 16
        self.assertEqual(out["reference_overrides"],
                         ["bodies.0.integrator=rk4", "time_step=0.000625"])
        self.assertEqual(out["samples"], 100)
        rms, worst, end = expected_errors(H, h_ref, H, 100)
        body = out["bodies"][0]
        # RK4's phase error: a few micrometres here; the formula holds to rounding
        self.assertGreater(worst, 1e-6)
        self.assertAlmostEqual(body["max_error"] / worst, 1, delta=1e-6)
        self.assertAlmostEqual(body["rms_error"] / rms, 1, delta=1e-6)
        self.assertAlmostEqual(body["end_error"] / end, 1, delta=1e-6)
        self.assertAlmostEqual(out["run"]["energy_drift"] / rk4_drift(H, DURATION), 1, delta=1e-6)
        # the reference loses 1e-13 J, within rounding of the 2e-3 J it has
        self.assertAlmostEqual(out["reference"]["energy_drift"], rk4_drift(h_ref, DURATION),
                               delta=1e-15)


class Sweep(unittest.TestCase):
    def test_sweep_tables_the_errors_the_formula_gives(self):
        steps = [0.01, 0.005]
        with tempfile.TemporaryDirectory() as tmp:
            out = json.loads(feltd("sweep", oscillator_scene(tmp), "--integrators",
                                   "rk4,symplectic_euler", "--time-steps", "0.01,0.005",
                                   "--duration", str(DURATION), "--out", tmp, "--json"))
            with open(os.path.join(tmp, "sweep.png"), "rb") as f:
                self.assertEqual(f.read(8), b"\x89PNG\r\n\x1a\n")
            with open(os.path.join(tmp, "sweep.csv")) as f:
                table = list(csv.DictReader(f))
        self.assertEqual(len(out["runs"]), 4)
        self.assertEqual(len(table), 4)
        h_ref = min(steps) / 16
        for run in out["runs"]:
            self.assertTrue(run["stable"])
            if run["integrator"] != "rk4":
                continue
            _, worst, _ = expected_errors(run["time_step"], h_ref, max(steps), 100)
            self.assertAlmostEqual(run["max_error"] / worst, 1, delta=1e-6)
        # symplectic Euler is first order: far worse than RK4 at the same step, and so off
        # the Pareto front; the cheapest run is on it
        by = {(r["integrator"], r["time_step"]): r for r in out["runs"]}
        self.assertGreater(by[("symplectic_euler", 0.005)]["max_error"],
                           100 * by[("rk4", 0.01)]["max_error"])
        self.assertTrue(min(out["runs"], key=lambda r: r["run"]["wall_seconds"])["pareto"])

    def test_search_brackets_rk4s_stability_limit(self):
        # RK4 is stable on an undamped spring up to ωh = 2√2 (its region's reach along the
        # imaginary axis); automatic substeps off, so that a step beyond it grows and is flagged
        stiffness = 40000.0  # ω = 632 /s: the limit is 4.47 ms
        limit = 2 * math.sqrt(2) / math.sqrt(stiffness / MASS)
        with tempfile.TemporaryDirectory() as tmp:
            scene = oscillator_scene(tmp, stiffness, {"auto_substeps": False})
            out = json.loads(feltd("sweep", scene, "--integrators", "rk4", "--time-steps",
                                   "0.1,0.001", "--duration", "1", "--search", "8", "--json"))
        searched = [r for r in out["runs"] if r["searched"]]
        self.assertGreaterEqual(len(searched), 3)
        self.assertLessEqual(len(searched), 8)
        for run in searched:  # steps the samples every 0.1 s still fall on
            self.assertAlmostEqual(0.1 / run["time_step"], round(0.1 / run["time_step"]),
                                   delta=1e-9)
        stable = max(r["time_step"] for r in out["runs"] if r["stable"])
        unstable = min(r["time_step"] for r in out["runs"]
                       if not r["stable"] and r["time_step"] > stable)
        self.assertLessEqual(stable, limit)
        self.assertGreater(unstable, limit)
        self.assertLess(unstable / stable, 1.06)  # from a factor of 100 swept


if __name__ == "__main__":
    unittest.main(verbosity=2)
