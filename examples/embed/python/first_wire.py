"""Frames of a scenario in numpy, and the first wire each conductor was seen at:
    PYTHONPATH=build/python /usr/bin/python3 examples/embed/python/first_wire.py examples/pylon_line.yaml
No per-point Python loop: each frame's returns are a structured array."""
import sys

import numpy as np

import owsim


def main(path):
    sim = owsim.Simulation(path)
    wire = owsim.CLASS_NAMES.index("wire")
    first = {}
    for frame in sim:  # the GIL is released while each frame is simulated
        hits = frame.returns[frame.returns["class"] == wire]
        for obj in np.unique(hits["object"]):
            if obj not in first:
                at = hits[hits["object"] == obj][0]
                first[obj] = (at["time_s"], at["range_m"])
    print(f"{sim.name}: {sim.frame_count} frames, {len(first)} conductors seen")
    for obj, (time_s, range_m) in sorted(first.items(), key=lambda item: item[1]):
        print(f"  {sim.object_ids[obj]:12s} first seen at {time_s:7.3f} s from {range_m:7.1f} m")
    return 0 if first else 1


if __name__ == "__main__":
    sys.exit(main(sys.argv[1]))
