#!/usr/bin/env python3
"""Markdown tables for docs/scenes.md from bench_scenes' JSON output.

Usage: bench_scenes --benchmark_repetitions=5 --benchmark_out=scenes.json \
           --benchmark_out_format=json
       python3 bench/scenes_table.py scenes.json

Every figure is the median aggregate over the repetitions, CPU time.
"""
import json
import sys

SCENES = ["coins", "plates", "rotors"]
VARIANTS = ["disk_tight", "disk_default", "thin_cylinder"]
KINDS = ["build", "collide", "nearest"]
SIZES = [100, 1000, 10000, 100000]
TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load(path):
    medians = {}
    with open(path) as f:
        for run in json.load(f)["benchmarks"]:
            if run.get("aggregate_name") != "median" or run.get("error_occurred"):
                continue
            kind, scene, variant, n = run["run_name"].split("/")
            run["cpu_ms"] = run["cpu_time"] * TO_MS[run["time_unit"]]
            medians[(kind, scene, variant, int(n))] = run
    return medians


def ms(value):
    return f"{value:.3g}" if value < 1000 else f"{value:,.0f}"


def main():
    medians = load(sys.argv[1])
    get = lambda *key: medians.get(key)
    for scene in SCENES:
        print(f"\n### {scene}\n")
        print("| N | " + " | ".join(f"{k} {v}" for k in KINDS for v in VARIANTS) + " |")
        print("|---:|" + "---:|" * (len(KINDS) * len(VARIANTS)))
        for n in SIZES:
            cells = []
            for kind in KINDS:
                for variant in VARIANTS:
                    run = get(kind, scene, variant, n)
                    cells.append(ms(run["cpu_ms"]) if run else "skipped")
            print(f"| {n:,} | " + " | ".join(cells) + " |")
    print("\n### per object (CPU us), collide and nearest\n")
    print("| scene | N | " + " | ".join(f"{k} {v}" for k in KINDS[1:] for v in VARIANTS) + " |")
    print("|---|---:|" + "---:|" * 6)
    for scene in SCENES:
        for n in SIZES:
            cells = []
            for kind in KINDS[1:]:
                for variant in VARIANTS:
                    run = get(kind, scene, variant, n)
                    cells.append(f"{run['per_object'] * 1e6:.3g}" if run else "skipped")
            print(f"| {scene} | {n:,} | " + " | ".join(cells) + " |")
    print("\n### pruning: candidate pairs per object, colliding pairs, speed-ups\n")
    print("| scene | N | collide candidates tight | default | nearest candidates tight | "
          "default | colliding pairs | thickness mismatches | collide default/tight | "
          "collide thin_cylinder/tight | nearest thin_cylinder/tight |")
    print("|---|---:|" + "---:|" * 9)
    for scene in SCENES:
        for n in SIZES:
            ct, cd, cc = (get("collide", scene, v, n) for v in VARIANTS)
            nt, nd, nc = (get("nearest", scene, v, n) for v in VARIANTS)
            if not (ct and cd and cc and nt and nd):
                continue
            nearest_ratio = f"{nc['cpu_ms'] / nt['cpu_ms']:.1f}x" if nc else "skipped"
            print(f"| {scene} | {n:,} | {ct['candidates_per_object']:.3g} | "
                  f"{cd['candidates_per_object']:.3g} | {nt['candidates_per_object']:.3g} | "
                  f"{nd['candidates_per_object']:.3g} | {ct['colliding']:.0f} | "
                  f"{cc['thickness_mismatches']:.0f} | {cd['cpu_ms'] / ct['cpu_ms']:.1f}x | "
                  f"{cc['cpu_ms'] / ct['cpu_ms']:.1f}x | {nearest_ratio} |")


if __name__ == "__main__":
    main()
