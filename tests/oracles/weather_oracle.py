"""Closed-form check of fog returns (SENSOR-SPEC §10) for rays from above through a fog layer.

    weather_oracle.py FOG CLEAR DECODED BASE TOP VISIBILITY KAPPA TRANSMISSION THRESHOLD
        FOG      points.csv of a run with the layer (--no-noise)
        CLEAR    points.csv of the same run without it
        DECODED  points.csv that `owsim decode` made of FOG's words
    prints "ok <fog returns> <hard returns behind> <hidden>" or fails with the first difference.

Every pulse's ray comes down through the layer from the sensor above it, so by §10:
  - its first return is the layer's echo at the entry point, on the layer's top, with energy
    e = π·κ·α·L·T_atm (α = 3.912 / V, L = 0.75 m, the path in fog still 0);
  - the receiver is busy for ln(e / threshold) / (2α) past the entry;
  - the hard echo the clear run saw on the same pulse (a wire or the ground, below the layer) is
    attenuated by exp(−2·α·D), D = (top − base) / |dz| the path through the layer along the ray
    (the ray's direction from the fog point to the hard point); it is the second return when
    that energy reaches the threshold, else no return;
  - the words hold those ranges: the decoded counters equal the points' counters.
"""
import csv
import math
import sys


def read(path):
    with open(path, newline="") as f:
        return {(int(r["frame"]), int(r["pulse"]), int(r["return"])): r for r in csv.DictReader(f)}


def main(fog_path, clear_path, decoded_path, base, top, visibility, kappa, transmission, threshold):
    fog, clear, decoded = read(fog_path), read(clear_path), read(decoded_path)
    alpha = 3.912 / visibility
    echo = math.pi * kappa * alpha * 0.75 * transmission
    busy = math.log(echo / threshold) / (2.0 * alpha)
    fog_returns = behind = hidden = 0
    for (frame, pulse, number), row in fog.items():
        if number != 1:
            continue
        if row["class"] != "fog":
            sys.exit(f"frame {frame} pulse {pulse}: return 1 is {row['class']}, not the fog")
        if abs(float(row["u_m"]) - top) > 1e-3:
            sys.exit(f"frame {frame} pulse {pulse}: fog return at u {row['u_m']}, not on top {top}")
        if abs(float(row["energy_rel"]) - echo) > 1e-8:
            sys.exit(f"frame {frame} pulse {pulse}: fog energy {row['energy_rel']} vs {echo}")
        fog_returns += 1
        hard = clear.get((frame, pulse, 1))
        second = fog.get((frame, pulse, 2))
        if hard is None:
            if second is not None:
                sys.exit(f"frame {frame} pulse {pulse}: a second return the clear run lacks")
            continue
        p1 = [float(row[k]) for k in ("e_m", "n_m", "u_m")]
        p2 = [float(hard[k]) for k in ("e_m", "n_m", "u_m")]
        length = math.dist(p1, p2)
        dz = abs(p2[2] - p1[2]) / length
        path = (top - base) / dz if p2[2] <= base else (top - p2[2]) / dz
        energy = float(hard["energy_rel"]) * math.exp(-2.0 * alpha * path)
        range_hard = float(hard["range_m"])
        seen = energy >= threshold and range_hard >= float(row["range_m"]) + max(busy, 0.75)
        if not seen:
            hidden += 1
            if second is not None:
                sys.exit(f"frame {frame} pulse {pulse}: {second['class']} seen behind the fog with "
                         f"{second['energy_rel']}; the oracle's energy is {energy}")
            continue
        if second is None:
            sys.exit(f"frame {frame} pulse {pulse}: {hard['class']} of energy {energy} missing "
                     "behind the fog")
        if second["object"] != hard["object"] or abs(float(second["range_m"]) - range_hard) > 1e-3:
            sys.exit(f"frame {frame} pulse {pulse}: return 2 is {second['object']} at "
                     f"{second['range_m']}, expected {hard['object']} at {range_hard}")
        # The points hold positions to 0.1 mm and energies to 9 digits: D is good to ~1e-6.
        if abs(float(second["energy_rel"]) - energy) > 1e-9 + 2e-5 * energy:
            sys.exit(f"frame {frame} pulse {pulse}: return 2 energy {second['energy_rel']}, "
                     f"expected {energy}")
        behind += 1
    for key, row in fog.items():
        word = decoded.get(key)
        if word is None or word["counter"] != row["counter"]:
            sys.exit(f"{key}: the words hold {None if word is None else word['counter']}, the "
                     f"points {row['counter']}")
    if len(decoded) != len(fog):
        sys.exit(f"the words decode to {len(decoded)} returns, the points hold {len(fog)}")
    print(f"ok {fog_returns} {behind} {hidden}")


if __name__ == "__main__":
    main(sys.argv[1], sys.argv[2], sys.argv[3], *[float(x) for x in sys.argv[4:10]])
