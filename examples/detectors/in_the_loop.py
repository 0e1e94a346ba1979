#!/usr/bin/python3
"""Bring your own detector: owsim's frames through your detector and the reference one, in the
loop, each scored by `owsim score` (docs/embedding.md "Your detector in the loop").

    in_the_loop.py SCENARIO OUT_DIR [FRAMES]

Flies SCENARIO (its first FRAMES frames, default all) once with `Simulation.run` for the ground
truth `owsim score` needs (OUT_DIR/run: summary.json, truth.csv, scenario.yaml), then frame by
frame through the module: each frame's returns go to `my_detector` — here the numpy baseline of
elevated_returns.py, on the frame's times and positions only, never its class or object columns —
and the frame itself to owsim.FrameDetector, the reference detector, which reads the words and the
navigation. Writes OUT_DIR/mine.csv and OUT_DIR/reference.csv (the latter byte for byte what
`owsim run --outputs detections` writes) and prints the two `owsim score` commands to compare them.
Replace `my_detector` with yours: it gets the frame's returns (a numpy structured array, columns
of points.csv) and returns rows of time_s, e_m, n_m, u_m, class.
"""
import os
import sys

import numpy as np

import owsim

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import elevated_returns  # noqa: E402  (the numpy baseline, one frame at a time here)


def my_detector(returns):
    """One frame's returns -> rows (time_s, e_m, n_m, u_m, class)."""
    points = np.stack([returns["frame"].astype(float), returns["time_s"], returns["e_m"],
                       returns["n_m"], returns["u_m"]], axis=1)
    return elevated_returns.detect(points)


def main(scenario, out, frames=None):
    sim = owsim.Simulation(scenario, frames=frames)
    sim.run(os.path.join(out, "run"), outputs="summary,truth")
    reference = owsim.FrameDetector(sim)
    mine = []
    with open(os.path.join(out, "reference.csv"), "w", newline="") as ref:
        ref.write(owsim.FrameDetector.csv_header)
        for frame in sim:
            mine.extend(my_detector(frame.returns))
            reference.add_frame(frame)
            ref.write(reference.csv_rows())
    elevated_returns.write(os.path.join(out, "mine.csv"), sorted(mine))
    run = os.path.join(out, "run")
    for name in ("mine", "reference"):
        print(f"owsim score {run} --detections {os.path.join(out, name + '.csv')} "
              f"--out {os.path.join(out, 'score_' + name)}")
    return 0


if __name__ == "__main__":
    if len(sys.argv) not in (3, 4):
        print(__doc__.strip().splitlines()[3], file=sys.stderr)
        sys.exit(2)
    sys.exit(main(sys.argv[1], sys.argv[2], int(sys.argv[3]) if len(sys.argv) == 4 else None))
