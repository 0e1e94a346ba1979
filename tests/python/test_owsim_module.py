"""Protects the Python module `owsim` (python/owsim_module.cpp, INTERFACE.md "Embedding"): for
every bundled example and a HELLAS scenario, Frame.words and Frame.returns equal `owsim run`'s
flight.d64 / flight.hellas bytes and points.csv rows frame for frame (numbers to the decimals
points.csv prints, compared column by column with numpy); co-simulation with pushed poses; input
errors as ValueError, file errors as OSError, frames out of range as IndexError; arrays that keep
their frame alive; run() with a progress callback; FrameDetector's warnings equal the
detections.csv rows `owsim run --outputs detections` writes."""
import json
import os
import subprocess
import sys
import tempfile
import unittest
from pathlib import Path

import numpy as np

import owsim

SOURCE = Path(os.environ["OWSIM_SOURCE_DIR"])
CLI = os.environ["OWSIM_CLI"]
EXAMPLES = SOURCE / "examples"
FRAMES = 3
PULSES_PER_FRAME = 20352
# points.csv columns and the decimals they are printed with (None: an integer or a name)
DECIMALS = {"time_s": 9, "range_m": 4, "e_m": 4, "n_m": 4, "u_m": 4, "lat_deg": 9,
            "lon_deg": 9, "h_m": 4, "incidence_deg": 4}
INTEGERS = ["frame", "pulse", "line", "fiber", "return", "counter"]


def scenarios(folder):
    found = {name: EXAMPLES / f"{name}.yaml"
             for name in ("single_span", "pylon_line", "corridor", "hellsim_flight")}
    text = (EXAMPLES / "single_span.yaml").read_text()
    hellas = folder / "single_span_hellas.yaml"
    hellas.write_text(text.replace("model: milows", "model: hellas")
                          .replace("name: single_span", "name: single_span_hellas"))
    found["single_span_hellas"] = hellas
    return found


def owsim_run(scenario, out):
    subprocess.run([CLI, "run", str(scenario), "--frames", str(FRAMES), "--outputs",
                    "d64,points", "--quiet", "--out", str(out)], check=True)


class ModuleEqualsOwsimRun(unittest.TestCase):
    def test_every_example_and_hellas_frame_for_frame(self):
        with tempfile.TemporaryDirectory() as tmp:
            folder = Path(tmp)
            for name, scenario in scenarios(folder).items():
                with self.subTest(scenario=name):
                    out = folder / name
                    owsim_run(scenario, out)
                    self.check_frames(scenario, out)

    def check_frames(self, scenario, out):
        sim = owsim.Simulation(str(scenario), frames=FRAMES)
        self.assertEqual(sim.frame_count, FRAMES)
        self.assertEqual(len(sim), FRAMES)
        hellas = (out / "flight.hellas").exists()
        recorded = (out / "flight.hellas").read_bytes()[4:] if hellas else \
            (out / "flight.d64").read_bytes()
        table = np.genfromtxt(out / "points.csv", delimiter=",", names=True, dtype=None,
                              encoding="utf-8")
        with open(out / "points.csv", encoding="utf-8") as csv:
            table.dtype.names = csv.readline().strip().split(",")  # genfromtxt renames `return`
        frames = list(sim)  # iteration: frames 0..FRAMES-1
        self.assertEqual([f.index for f in frames], list(range(FRAMES)))
        for k, frame in enumerate(frames):
            words = frame.words
            self.assertEqual(words.dtype, np.uint32 if hellas else np.uint64)
            self.assertEqual(words.shape, (PULSES_PER_FRAME,))
            size = words.nbytes
            self.assertEqual(words.tobytes(), recorded[k * size:(k + 1) * size], f"frame {k}")
            rows = table[table["frame"] == k]
            returns = frame.returns
            self.assertEqual(len(returns), len(rows), f"frame {k}")
            self.assertGreater(len(rows), 0)
            for column in INTEGERS:
                np.testing.assert_array_equal(returns[column], rows[column], err_msg=column)
            for column, decimals in DECIMALS.items():
                # the printed value is the exact one rounded to `decimals`; NaN (a false return's
                # incidence) is the empty cell
                unknown = np.isnan(returns[column])
                np.testing.assert_array_equal(unknown, np.isnan(rows[column]), err_msg=column)
                np.testing.assert_array_less(
                    np.abs(returns[column][~unknown] - rows[column][~unknown]),
                    0.5 * 10.0 ** -decimals * (1 + 1e-6) + 1e-12, err_msg=column)
            np.testing.assert_allclose(returns["energy_rel"], rows["energy_rel"], rtol=5e-9)
            names = np.array(owsim.CLASS_NAMES)[returns["class"]]
            np.testing.assert_array_equal(names, rows["class"])
            # a false return (class noise) has no object: NO_OBJECT, the empty cell
            ids = np.array(list(sim.object_ids) + [""])
            objects = np.where(returns["object"] == owsim.NO_OBJECT, len(ids) - 1,
                               returns["object"])
            np.testing.assert_array_equal(ids[objects], rows["object"])
            self.assertEqual(frame.pulses.shape, (PULSES_PER_FRAME,))
            self.assertEqual(frame.rays["dir_enu"].shape, (PULSES_PER_FRAME, 3))


class Module(unittest.TestCase):
    def setUp(self):
        self.sim = owsim.Simulation(str(EXAMPLES / "single_span.yaml"), frames=5)

    def test_arrays_keep_their_frame_alive_and_are_read_only(self):
        returns = self.sim.frame(2).returns  # the Frame object is gone at once
        words = self.sim.frame(2).words
        self.assertTrue(np.all(returns["frame"] == 2))
        self.assertEqual(words.shape, (PULSES_PER_FRAME,))
        with self.assertRaises(ValueError):
            returns["range_m"][0] = 1.0
        np.testing.assert_allclose(
            np.linalg.norm(self.sim.frame(0).rays["dir_enu"][self.sim.frame(0).pulses["fiber"] != 0],
                           axis=1), 1.0, atol=1e-12)

    def test_pulses_hold_what_their_words_hold(self):
        # A pulse's encoder count (i16), frame gate and line gate are its MilOWS word's bits 47-32,
        # 31 and 30 (SENSOR-SPEC §8), pulse for pulse: the line's last pulses included, whose gate
        # byte lies right after the encoder's two.
        frame = self.sim.frame(1)
        pulses, words = frame.pulses, frame.words
        self.assertEqual(pulses["encoder"].dtype, np.int16)
        in_word = ((words >> np.uint64(32)) & np.uint64(0xFFFF)).astype(np.uint16).view(np.int16)
        np.testing.assert_array_equal(pulses["encoder"], in_word)
        self.assertTrue(np.any(pulses["encoder"] < 0) and np.any(pulses["lg"]))
        np.testing.assert_array_equal(pulses["fg"], (words >> np.uint64(31)) & np.uint64(1) == 1)
        np.testing.assert_array_equal(pulses["lg"], (words >> np.uint64(30)) & np.uint64(1) == 1)
        self.assertEqual(np.count_nonzero(pulses["lg"]), PULSES_PER_FRAME // 128)  # 159 lines

    def test_class_codes_are_the_c_apis(self):
        # OWSIM_CLASS_* of capi/owsim/owsim.h: the code is the index; 255 unknown
        self.assertEqual(owsim.CLASS_NAMES,
                         ("wire", "pole", "tree", "ground", "building", "fog", "noise"))
        self.assertEqual(owsim.UNKNOWN_CLASS, 255)
        self.assertEqual(owsim.NO_OBJECT, 0xFFFFFFFF)

    def test_errors(self):
        with self.assertRaises(IndexError) as caught:
            self.sim.frame(5)
        self.assertEqual(str(caught.exception), "frame 5 is out of range: the flight has frames 0..4")
        with self.assertRaises(OSError) as caught:
            owsim.Simulation("/nonexistent/scenario.yaml")
        self.assertEqual(str(caught.exception), "/nonexistent/scenario.yaml: cannot read the YAML file: no such file")
        with self.assertRaises(ValueError) as caught:
            owsim.Simulation.from_yaml("name: x\norigin: {lat: 95, lon: 0, h: 0}\n", "bad.yaml")
        self.assertTrue(str(caught.exception).startswith("bad.yaml:2: origin"))
        self.assertNotIn("\n", str(caught.exception))
        with self.assertRaises(ValueError) as caught:
            self.sim.run(outputs="d64,bogus")
        with self.assertRaises(ValueError):
            self.sim.frame(1, poses=np.zeros((3, 5)))

    def test_co_simulation_with_pushed_poses(self):
        start, end = self.sim.frame_start_s(3), self.sim.frame_end_s(3)
        t = np.arange(start - 0.05, end + 0.05, 0.01)
        # single_span's own route: east at 40 m/s from e = -600, 60 m up, heading 90°
        poses = np.zeros(len(t), dtype=[(n, "<f8") for n in (
            "time_s", "e_m", "n_m", "u_m", "roll_deg", "pitch_deg", "heading_deg")])
        poses["time_s"], poses["e_m"], poses["u_m"], poses["heading_deg"] = t, -600 + 40 * t, 60, 90
        pushed = self.sim.frame(3, poses=poses)
        own = self.sim.frame(3)
        same = np.count_nonzero(pushed.words == own.words)
        self.assertGreaterEqual(same, 0.999 * PULSES_PER_FRAME)
        table = np.column_stack([poses[n] for n in poses.dtype.names])
        np.testing.assert_array_equal(self.sim.frame(3, poses=table).words, pushed.words)
        with self.assertRaises(ValueError) as caught:
            self.sim.frame(3, poses=table[:10])
        self.assertTrue(str(caught.exception).startswith("poses: cover "))

    def test_run_with_progress(self):
        seen = []
        with tempfile.TemporaryDirectory() as tmp:
            report = self.sim.run(tmp, outputs="d64,summary",
                                  progress=lambda done, total: seen.append((done, total)))
            self.assertEqual(report["frames"], 5)
            self.assertEqual(Path(tmp, "flight.d64").stat().st_size, 5 * PULSES_PER_FRAME * 8)
        self.assertEqual(seen, [(k, 5) for k in range(1, 6)])

        def stop(done, total):
            if done == 2:
                raise KeyboardInterrupt("stop")
        with tempfile.TemporaryDirectory() as tmp:
            with self.assertRaises(KeyboardInterrupt):
                self.sim.run(tmp, outputs="d64", progress=stop)
            self.assertFalse(Path(tmp, "flight.d64").exists())

    def test_view_writes_the_page_of_a_run(self):
        with tempfile.TemporaryDirectory() as tmp:
            self.sim.run(tmp, outputs="csv,summary,trajectory")
            page = owsim.view(tmp, scenario=EXAMPLES / "single_span.yaml", max_frames=3)
            self.assertEqual(page["file"], str(Path(tmp, "report.html")))
            self.assertEqual(page["frames_total"], 5)
            self.assertEqual(page["frames_shown"], 3)
            self.assertEqual(page["points_shown"], page["points_total"])
            self.assertEqual(Path(page["file"]).stat().st_size, page["bytes"])
            self.assertIn("The frame player holds 3 of 5 frames", " ".join(page["notes"]))
        with tempfile.TemporaryDirectory() as empty:
            with self.assertRaisesRegex(ValueError, "not an owsim output folder"):
                owsim.view(empty)
        with self.assertRaises(OSError):
            owsim.view(Path(empty, "gone"))


class Detector(unittest.TestCase):
    def test_warnings_are_the_runs_detections_csv(self):
        approach = SOURCE / "tests/data/detector/approach.yaml"
        with tempfile.TemporaryDirectory() as tmp:
            subprocess.run([CLI, "run", str(approach), "--frames", "40", "--outputs",
                            "detections", "--quiet", "--out", tmp], check=True)
            written = Path(tmp, "detections.csv").read_text()
        sim = owsim.Simulation(str(approach), frames=40)
        detector = owsim.FrameDetector(sim)
        text = owsim.FrameDetector.csv_header
        classes = []
        for frame in sim:
            warnings = detector.add_frame(frame)
            rows = detector.csv_rows()
            self.assertEqual(len(warnings), rows.count("\n"))
            for warning, row in zip(warnings, rows.splitlines()):
                cells = row.split(",")
                self.assertEqual(int(cells[0]), warning["frame"])
                self.assertEqual(int(cells[2]), warning["track"])
                self.assertEqual(cells[3], owsim.OBSTACLE_CLASS_NAMES[warning["class"]])
                np.testing.assert_allclose([float(c) for c in cells[4:7]], warning["enu_m"],
                                           atol=5e-4)
                self.assertEqual(int(cells[11]), warning["points"])
                classes.append(cells[3])
            text += rows
        self.assertEqual(text, written)
        self.assertIn("wire", classes)
        with self.assertRaisesRegex(ValueError, "given after frame"):
            detector.add_frame(sim.frame(39))

    def test_your_detector_in_the_loop_beside_the_reference_scored(self):
        approach = SOURCE / "tests/data/detector/approach.yaml"
        script = SOURCE / "examples/detectors/in_the_loop.py"
        with tempfile.TemporaryDirectory() as tmp:
            done = subprocess.run([sys.executable, str(script), str(approach), tmp, "60"],
                                  check=True, capture_output=True, text=True)
            commands = done.stdout.splitlines()
            self.assertEqual(len(commands), 2)
            subprocess.run([CLI, "run", str(approach), "--frames", "60", "--outputs",
                            "detections", "--quiet", "--out", str(Path(tmp, "inline"))],
                           check=True)
            self.assertEqual(Path(tmp, "reference.csv").read_text(),
                             Path(tmp, "inline", "detections.csv").read_text())
            for command in commands:
                words = command.split()
                self.assertEqual(words[:2], ["owsim", "score"])
                subprocess.run([CLI] + words[1:] + ["--quiet"], check=True)
            score = json.loads(Path(tmp, "score_reference", "score.json").read_text())
            warned = {o["id"]: o["warned_class"] for o in score["objects"] if o["in_view"]}
            self.assertIn("wire", warned.values())
            self.assertTrue(Path(tmp, "score_mine", "score.json").exists())


if __name__ == "__main__":
    unittest.main()
