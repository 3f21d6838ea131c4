#!/usr/bin/env python3
"""Tables (stdout, Markdown) and a plot for docs/scenes.md from bench_environment's JSON.

Usage: bench_environment --benchmark_repetitions=3 --benchmark_display_aggregates_only=true \
           --benchmark_out=environment.json --benchmark_out_format=json
       python3 bench/environment_plot.py environment.json [docs/environment.png]

Benchmarks are named <query>/<scene>/<path>/<variant>. Per query, the figure is the
counter median_ns (each pose's median time over the sweeps, then the median over the
path's poses) and p99_ns; with repetitions, the median aggregate of those over the
repetitions; without, the single run. Sweep: Google Benchmark's CPU time per
iteration (one sweep of the path). A disk run that failed its brute-force check
(SkipWithError) has no figures and is marked "check failed".
Needs matplotlib (Debian: python3-matplotlib) only for the plot; Agg backend.
"""
import argparse
import json
import sys

QUERIES = ["distance", "collide"]
SCENES = {
    "distance": ["mesh_obbrss", "mesh_rss", "mesh_obb", "mesh_aabb", "octree"],
    "collide": ["mesh_obbrss", "mesh_rss", "mesh_obb", "mesh_aabb", "octree"],
}
PATHS = ["skim", "slalom", "crossing", "open"]
VARIANTS = ["disk", "sphere", "cylinder"]
TO_MS = {"ns": 1e-6, "us": 1e-3, "ms": 1.0, "s": 1e3}


def load(path):
    """{(query, scene, path, variant): run}, median aggregates if present."""
    with open(path) as f:
        data = json.load(f)
    medians, singles = {}, {}
    for run in data["benchmarks"]:
        parts = run["run_name"].split("/")
        if len(parts) != 4:
            continue
        key = tuple(parts)
        if run.get("run_type") == "aggregate":
            if run.get("aggregate_name") == "median":
                medians[key] = run
        else:
            # Keep an errored repetition's message; a good one replaces it.
            if key not in singles or singles[key].get("error_occurred"):
                singles[key] = run
    runs = dict(singles)
    runs.update(medians)
    for run in runs.values():
        if not run.get("error_occurred") and "cpu_time" in run:
            run["sweep_ms"] = run["cpu_time"] * TO_MS[run["time_unit"]]
    return runs, data.get("context", {})


def ok(run):
    return run is not None and not run.get("error_occurred") and "median_ns" in run


def ns(value):
    """Three significant figures, thousands separated."""
    if value >= 100:
        return f"{float(f'{value:.3g}'):,.0f}"
    return f"{value:.3g}"


def failure(run):
    """Why a run has no figures: not run, FCL answered nothing, or a failed check."""
    if run is None:
        return "not run"
    if run.get("error_message", "").startswith("no answer"):
        return "no answer"
    return "check failed"


def cell(run, field="median_ns"):
    return ns(run[field]) if ok(run) else failure(run)


def ratio(a, b):
    return f"{a['median_ns'] / b['median_ns']:.3g}" if ok(a) and ok(b) else "-"


def check_status(run):
    if run is None:
        return "not run"
    if run.get("error_occurred"):
        return "FAILED: " + run.get("error_message", "")[:60]
    failures = run.get("check_failures")
    if failures is None:
        return "-"
    return "ok" if failures == 0 else f"{failures:.0f} failures (kept)"


def tables(runs):
    get = runs.get
    print("\n#### The whole flight (800 poses: the four paths back to back), ns per query\n")
    print("| query | environment | disk | sphere | cylinder (GJK) | disk / sphere | "
          "cylinder / disk | disk p99 | sweep, ms: disk / sphere / cylinder | disk check |")
    print("|---|---|---:|---:|---:|---:|---:|---:|---:|---|")
    for query in QUERIES:
        for scene in SCENES[query]:
            d, s, c = (get((query, scene, "all", v)) for v in VARIANTS)
            sweep = " / ".join(f"{r['sweep_ms']:.3g}" if ok(r) else "-" for r in (d, s, c))
            print(f"| {query} | {scene} | {cell(d)} | {cell(s)} | {cell(c)} | {ratio(d, s)} | "
                  f"{ratio(c, d)} | {cell(d, 'p99_ns')} | {sweep} | {check_status(d)} |")

    print("\n#### Per path, ns per query (median over the path's 200 poses)\n")
    print("| query | environment | path | disk | sphere | cylinder (GJK) | disk / sphere | "
          "cylinder / disk | clearance min / median (mm) | poses in contact |")
    print("|---|---|---|---:|---:|---:|---:|---:|---:|---:|")
    for query in QUERIES:
        for scene in SCENES[query]:
            for path in PATHS:
                d, s, c = (get((query, scene, path, v)) for v in VARIANTS)
                ref = next((r for r in (d, s, c) if r and "exact_min_mm" in r), None)
                clearance = (f"{ref['exact_min_mm']:.0f} / {ref['exact_median_mm']:.0f}"
                             if ref else "-")
                contact = f"{100 * ref['exact_contact']:.0f}%" if ref else "-"
                print(f"| {query} | {scene} | {path} | {cell(d)} | {cell(s)} | {cell(c)} | "
                      f"{ratio(d, s)} | {ratio(c, d)} | {clearance} | {contact} |")

    print("\n#### Agreement: FCL's answers on the same poses\n")
    print("| query | environment | sphere: poses in contact | exact (disk) | "
          "cylinder: max \\|d - d_exact\\| (um) or verdict mismatches |")
    print("|---|---|---:|---:|---:|")
    for query in QUERIES:
        for scene in SCENES[query]:
            d, s, c = (get((query, scene, "all", v)) for v in VARIANTS)
            ref = next((r for r in (d, s, c) if r and "exact_contact" in r), None)
            sphere = f"{100 * s['contact']:.0f}%" if ok(s) else "-"
            exact = f"{100 * ref['exact_contact']:.0f}%" if ref else "-"
            if ok(c) and query == "distance":
                cyl = f"{1e6 * c['max_abs_diff_vs_exact']:.3g}"
            elif ok(c):
                cyl = f"{c['verdict_mismatches']:.0f}"
            else:
                cyl = "-"
            print(f"| {query} | {scene} | {sphere} | {exact} | {cyl} |")


def plot(runs, png, title):
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    colours = {"disk": "tab:blue", "sphere": "tab:green", "cylinder": "tab:red"}
    labels = {"disk": "fcl_disk::Disk(r)", "sphere": "fcl::Sphere(r) (FCL)",
              "cylinder": "fcl::Cylinder(r, 0) (FCL's GJK)"}
    markers = {"skim": "v", "slalom": "s", "crossing": "x", "open": "^"}
    widths = [len(SCENES[q]) for q in QUERIES]
    fig, axes = plt.subplots(1, 2, figsize=(14, 5.4), dpi=110,
                             gridspec_kw={"width_ratios": widths})
    bar = 0.26
    for ax, query in zip(axes, QUERIES):
        scenes = SCENES[query]
        for i, scene in enumerate(scenes):
            for j, variant in enumerate(VARIANTS):
                x = i + (j - 1) * bar
                run = runs.get((query, scene, "all", variant))
                if not ok(run):
                    ax.text(x, 0.02, failure(run), rotation=90, ha="center", va="bottom",
                            fontsize=7, color=colours[variant],
                            transform=ax.get_xaxis_transform())
                    continue
                ax.bar(x, run["median_ns"], bar * 0.92, color=colours[variant], alpha=0.8,
                       zorder=2)
                ax.plot([x, x], [run["median_ns"], run["p99_ns"]], color="0.2",
                        linewidth=0.9, zorder=3)
                ax.plot(x, run["p99_ns"], marker="_", color="0.2", markersize=7, zorder=3)
                for path in PATHS:
                    per_path = runs.get((query, scene, path, variant))
                    if ok(per_path):
                        ax.plot(x, per_path["median_ns"], marker=markers[path],
                                color="black", markersize=4, linestyle="none", zorder=4,
                                markerfacecolor="none" if markers[path] != "x" else None)
        ax.set_yscale("log")
        ax.set_xticks(range(len(scenes)))
        ax.set_xticklabels(scenes)
        ax.set_title(f"fcl::{query}")
        ax.grid(True, axis="y", which="major", alpha=0.3, zorder=0)
        ax.grid(True, axis="y", which="minor", alpha=0.08, zorder=0)
        ax.set_ylabel("time per query [ns]")
    handles = [Patch(color=colours[v], alpha=0.8, label=labels[v]) for v in VARIANTS]
    handles.append(Line2D([], [], color="0.2", marker="_", label="whisker: p99 over the poses"))
    handles += [Line2D([], [], marker=m, color="black", linestyle="none", markersize=5,
                       markerfacecolor="none" if m != "x" else None,
                       label=f"median on path '{p}'") for p, m in markers.items()]
    fig.legend(handles=handles, loc="lower center", ncol=4, fontsize=8, frameon=False)
    fig.suptitle(title)
    fig.tight_layout(rect=(0, 0.1, 1, 1))
    fig.savefig(png)


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("json", help="bench_environment --benchmark_out=... (JSON)")
    parser.add_argument("png", nargs="?", help="output PNG (omit for the tables only)")
    parser.add_argument("--title", default="A disk (r = 12 cm) flying through a 30,140-triangle "
                        "mesh and a 5 cm octomap: bars = median over the 800 poses of the "
                        "flight")
    args = parser.parse_args(argv)
    runs, _ = load(args.json)
    tables(runs)
    if args.png:
        plot(runs, args.png, args.title)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
