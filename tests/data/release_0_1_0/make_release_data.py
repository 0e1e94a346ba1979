"""Writes this folder's golden data from owsim 0.1.0: for each bundled example, a short flight with
every default output, digested by tests/oracles/run_digest.py (the deterministic files' SHA-256,
summary.json's counts), the same for --threads 1 and 2. For fog_bank also the digest of 0.1.0's
outputs with the fog corner corrected (issue 44 item 6), made here from 0.1.0's own files and
SENSOR-SPEC §10, not by a later owsim.

    /usr/bin/python3 tests/data/release_0_1_0/make_release_data.py OWSIM_0_1_0 [EXAMPLE_NAME...]

The fog corner: a solid met while the fog's echo is still above the threshold merges into the fog's
return (§10), but 0.1.0 reported the ground under fog_bank's bank as return 2 on some pulses whose
ground lies inside the busy interval. Those pulses are found on a --no-noise flight (exact ranges;
the selection of returns does not depend on the range noise) as a fog return with a solid behind
it, inside the bank, closer than ln(e0 / T) / (2α), e0 = π·κ·α·L·T_atm. On the flight with noise
each such pulse keeps its fog return alone, as return 1: its solid row, LAS and PLY record go, the
headers' counts follow, its word's counters become the fog's and the timeout, and summary.json's
counts lose the solid's return.
"""

import json
import math
import pathlib
import re
import struct
import subprocess
import sys
import tempfile

HERE = pathlib.Path(__file__).resolve().parent
SOURCE = HERE.parents[2]
sys.path.insert(0, str(SOURCE / "tests" / "oracles"))
import run_digest  # noqa: E402

import yaml  # noqa: E402

# (name, example, frames): single_span and fog_bank whole (the span at 15 s, the bank at 11 s).
EXAMPLES = [
    ("single_span", "examples/single_span.yaml", 45),
    ("pylon_line", "examples/pylon_line.yaml", 60),
    ("corridor", "examples/corridor.yaml", 60),
    ("hellsim_flight", "examples/hellsim_flight.yaml", 60),
    ("real_corridor", "examples/real_corridor.yaml", 60),
    ("fog_bank", "examples/fog_bank.yaml", 45),
    ("hellas_5mm_approach", "examples/campaigns/hellas_5mm_approach.yaml", 60),
]
PULSES_PER_FRAME = 20352
PULSE_LENGTH_M = 0.75  # L = c·5 ns / 2 (SENSOR-SPEC §10)
INSIDE_M = 1e-3  # a point of a 4-decimal points.csv on the fog's boundary is inside it
TIMEOUT_COUNTS = 2066  # a missing return's counter (SENSOR-SPEC §1, §8; fog_bank keeps the default)


def fly(owsim, example, frames, out, *options):
    subprocess.run([owsim, "run", str(SOURCE / example), "--frames", str(frames), "--out",
                    str(out), "--quiet", *options], check=True)


def points_rows(path):
    """points.csv's header line and its rows as lists of cells."""
    lines = path.read_text().splitlines()
    return lines[0], [line.split(",") for line in lines[1:]]


def busy_length_m(scenario, fog):
    """How far past its entry the fog's echo stays above the threshold (SENSOR-SPEC §10)."""
    alpha = 3.912 / fog["visibility_m"]
    kappa = scenario["weather"]["backscatter_ratio_sr"]
    t_atm = scenario["atmosphere"]["transmission"]
    echo = math.pi * kappa * alpha * PULSE_LENGTH_M * t_atm
    return math.log(echo / scenario["sensor"]["threshold"]) / (2 * alpha)


def inside(box, east, north, up):
    return all(low - INSIDE_M <= x <= high + INSIDE_M
               for x, (low, high) in zip((east, north, up), (box["e"], box["n"], box["u"])))


def fog_corner_pulses(owsim, example, frames, work):
    """(frame, pulse) of every pulse whose solid lies inside the bank's busy interval."""
    scenario = yaml.safe_load((SOURCE / example).read_text())
    (fog,) = scenario["weather"]["fog"]
    busy = busy_length_m(scenario, fog)
    fly(owsim, example, frames, work / "exact", "--no-noise", "--outputs", "csv")
    header, rows = points_rows(work / "exact" / "points.csv")
    col = {name: i for i, name in enumerate(header.split(","))}
    by_pulse = {}
    for row in rows:
        by_pulse.setdefault((int(row[col["frame"]]), int(row[col["pulse"]])), []).append(row)
    corner = []
    for key, returns in sorted(by_pulse.items()):
        fogs = [r for r in returns if r[col["class"]] == "fog"]
        for solid in (r for r in returns if r[col["class"]] != "fog"):
            position = [float(solid[col[c]]) for c in ("e_m", "n_m", "u_m")]
            behind = [float(solid[col["range_m"]]) - float(f[col["range_m"]]) for f in fogs]
            if any(0 < d < busy for d in behind) and inside(fog["box"], *position):
                corner.append(key)
    return corner, busy


def write_las_extent(las, records):
    """The LAS header's max and min x, y, z from the records' scaled integers."""
    scale = struct.unpack_from("<3d", las, 131)
    offset = struct.unpack_from("<3d", las, 155)
    for axis in range(3):
        values = [struct.unpack_from("<i", r, 4 * axis)[0] for r in records]
        struct.pack_into("<2d", las, 179 + 16 * axis, offset[axis] + max(values) * scale[axis],
                         offset[axis] + min(values) * scale[axis])


def corrected_points(run, corner, out):
    """0.1.0's points.csv, LAS, PLY and words of `run` with the corner pulses' solids gone."""
    header, rows = points_rows(run / "points.csv")
    col = {name: i for i, name in enumerate(header.split(","))}
    corner = set(corner)
    dropped, kept, fog_rows, fog_counter = [], [], [], {}
    for index, row in enumerate(rows):
        key = (int(row[col["frame"]]), int(row[col["pulse"]]))
        if key in corner:
            assert row[col["class"]] in ("fog", "ground"), row
            if row[col["class"]] != "fog":
                dropped.append(index)
                continue
            row = row.copy()
            row[col["return"]] = "1"
            fog_rows.append(len(kept))
            fog_counter[key] = int(row[col["counter"]])
        kept.append(row)
    assert len(dropped) == len(corner) == len(fog_counter), (dropped, corner)
    dropped_set = set(dropped)
    (out / "points.csv").write_text(header + "\n" + "".join(",".join(r) + "\n" for r in kept))

    las = bytearray((run / "points.las").read_bytes())
    start = struct.unpack_from("<I", las, 96)[0]
    size = struct.unpack_from("<H", las, 105)[0]
    records = [las[start + i * size:start + (i + 1) * size] for i in range((len(las) - start) // size)]
    assert len(records) == len(rows)
    original = bytes(las)
    write_las_extent(las, records)
    assert bytes(las) == original, "the LAS extent is not recomputed as owsim wrote it"
    assert all(records[i][16] == 2 for i in dropped)  # LAS class 2: the ground
    records = [r for i, r in enumerate(records) if i not in dropped_set]
    for i in fog_rows:
        records[i][14] = 0x11  # return 1 of 1
    struct.pack_into("<Q", las, 247, len(records))
    by_return_2 = struct.unpack_from("<Q", las, 263)[0]
    struct.pack_into("<Q", las, 263, by_return_2 - len(dropped))
    write_las_extent(las, records)
    (out / "points.las").write_bytes(bytes(las[:start]) + b"".join(records))

    ply = (run / "points.ply").read_bytes()
    end = ply.index(b"end_header\n") + len(b"end_header\n")
    count = re.search(rb"( *)\nelement vertex (\d+)\n", ply[:end])
    assert int(count.group(2)) == len(rows)
    new_count = str(len(kept)).encode()
    padding = b" " * (len(count.group(1)) + len(count.group(2)) - len(new_count))
    head = ply[:count.start()] + padding + b"\nelement vertex " + new_count + ply[count.end() - 1:end]
    vertices = [ply[end + i * 29:end + (i + 1) * 29] for i in range(len(rows))]
    assert all(vertices[i][28] == 3 for i in dropped)  # PLY class 3: the ground
    (out / "points.ply").write_bytes(
        head + b"".join(v for i, v in enumerate(vertices) if i not in dropped_set))

    words = bytearray((run / "flight.d64").read_bytes())
    for (frame, pulse), counter in fog_counter.items():
        at = 8 * (frame * PULSES_PER_FRAME + pulse)
        word = struct.unpack_from("<Q", words, at)[0]
        counters = {word & 0xFFF, word >> 16 & 0xFFF}
        assert counter in counters and TIMEOUT_COUNTS not in counters, (frame, pulse, hex(word))
        word = word & ~0x0FFF0FFF | counter | TIMEOUT_COUNTS << 16
        struct.pack_into("<Q", words, at, word)
    (out / "flight.d64").write_bytes(bytes(words))
    return len(dropped)


def corrected_summary(facts, count):
    """summary.json's counts without the corner pulses' ground returns (their second returns)."""
    facts = json.loads(json.dumps(run_digest.summary_facts(facts)))
    facts["returns"]["ground"] -= count
    facts["second_returns"] -= count
    return facts


def example_data(owsim, name, example, frames, work):
    data = {"example": example, "frames": frames, "threads_compared": [1, 2]}
    digests = []
    for threads in (1, 2):
        run = work / f"{name}_{threads}"
        fly(owsim, example, frames, run, "--threads", str(threads))
        digests.append(run_digest.run_digest(run))
    assert digests[0] == digests[1], f"{name}: --threads 1 and 2 differ"
    data.update(digests[1])
    if name == "fog_bank":
        corner, busy = fog_corner_pulses(owsim, example, frames, work)
        fixed = work / "fog_corner_corrected"
        fixed.mkdir()
        count = corrected_points(work / f"{name}_2", corner, fixed)
        for kept in ("truth.csv", "trajectory.csv"):  # the ground is in neither
            (fixed / kept).write_bytes((work / f"{name}_2" / kept).read_bytes())
        corrected = run_digest.run_digest(fixed)
        corrected.update(corrected_summary(digests[1], count))
        corrected.update({"busy_length_m": round(busy, 6), "count": count,
                          "pulses": [list(key) for key in corner]})
        data["fog_corner_corrected"] = corrected
    return data


def main(owsim, names):
    with tempfile.TemporaryDirectory(prefix="owsim_release_0_1_0_") as folder:
        for name, example, frames in EXAMPLES:
            if names and name not in names:
                continue
            work = pathlib.Path(folder) / name
            work.mkdir()
            data = example_data(owsim, name, example, frames, work)
            (HERE / f"{name}.json").write_text(json.dumps(data, indent=1, sort_keys=True) + "\n")
            print(name, frames, "frames", data.get("fog_corner_corrected", {}).get("count", ""))


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2:])
