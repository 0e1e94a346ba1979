"""What fog costs per pulse, measured in one sitting (issue 21): `owsim bench` on the corridor
(examples/corridor.yaml) in clear air and with a fog layer every pulse crosses (visibility 25 m,
5 m thick, between the helicopter and the ground, so every pulse gets the layer's echo as return 1
and the path through it attenuates what lies behind), alternately, each figure the best of its
rounds.

    /usr/bin/python3 bench/fog_layer.py [--owsim build/owsim] [--rounds 3]
"""
import argparse
import os
import re
import subprocess
import tempfile

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
CORRIDOR = os.path.join(ROOT, "examples", "corridor.yaml")
FOG = "weather:\n  fog:\n    - {id: deck, visibility_m: 25, layer: {base_m: 40, top_m: 45}}\n"


def bench(owsim, scenario):
    out = subprocess.run([owsim, "bench", scenario, "--quiet"], capture_output=True, text=True,
                         check=True)
    text = out.stdout + out.stderr
    figures = {}
    for name in ("end-to-end", "single thread"):
        figures[name] = float(re.search(rf"{name}\s+(\d+) pulses/s", text).group(1))
    return figures


def main():
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("--owsim", default=os.path.join(ROOT, "build", "owsim"))
    parser.add_argument("--rounds", type=int, default=3)
    args = parser.parse_args()
    with tempfile.TemporaryDirectory(prefix="owsim_fog_bench_") as folder:
        foggy = os.path.join(folder, "corridor_fog.yaml")
        with open(CORRIDOR, encoding="utf-8") as f, open(foggy, "w", encoding="utf-8") as g:
            g.write(f.read() + FOG)
        best = {"clear": {}, "fog": {}}
        for _ in range(args.rounds):
            for name, scenario in (("clear", CORRIDOR), ("fog", foggy)):
                for key, value in bench(args.owsim, scenario).items():
                    best[name][key] = max(best[name].get(key, 0.0), value)
        print("| corridor | end-to-end pulses/s (2 threads) | single thread pulses/s |")
        print("|---|---|---|")
        for name in ("clear", "fog"):
            print(f"| {name} | {best[name]['end-to-end'] / 1e6:.2f} M | "
                  f"{best[name]['single thread'] / 1e6:.2f} M |")
        for key in ("end-to-end", "single thread"):
            cost = best["clear"][key] / best["fog"][key] - 1.0
            print(f"{key}: fog costs {100.0 * cost:.0f} % more per pulse")


if __name__ == "__main__":
    main()
