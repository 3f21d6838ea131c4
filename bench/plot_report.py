#!/usr/bin/env python3
"""Plot fcl_disk_report's summary: time per query against error, log-log.

Usage: plot_report.py REPORT_CSV OUT_PNG [--title TITLE] [--include-direct]

Reads report.csv (one row per solver and family, as fcl_disk_report writes it)
and draws, for every (solver, family): a filled marker at (median ns/query, max
relative error) and a hollow one at (median ns/query, median relative error),
joined by a thin line. Marker shape = solver, colour = family; black = all
families pooled. Errors below the floor (1e-17, the reference's own accuracy;
zero errors included) are drawn on the floor. Needs matplotlib (Debian:
python3-matplotlib); uses the Agg backend, so no display is needed.
"""

import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

ERROR_FLOOR = 1e-17
EXACT_BOUND = 1e-12

MARKERS = {
    "exact": "o",
    "almohamad_selim": "s",
    "gjk_libccd_h1e-2": "^",
    "gjk_libccd_h1e-4": "v",
    "gjk_libccd_h1e-6": "D",
    "gjk_indep_h1e-2": "P",
    "gjk_indep_h1e-4": "X",
    "gjk_indep_h1e-6": "*",
    "exact_direct": "h",
    "almohamad_selim_direct": "p",
    "exact_float": "d",
}


def read_rows(path):
    with open(path, newline="") as f:
        rows = list(csv.DictReader(f))
    for row in rows:
        for key in ("median_ns", "p99_ns", "median_rel_err", "max_rel_err"):
            row[key] = float(row[key])
    return rows


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="report.csv written by fcl_disk_report")
    parser.add_argument("png", help="output PNG")
    parser.add_argument("--title", default="fcl_disk: time per query against error "
                        "(all through fcl::distance)")
    parser.add_argument("--include-direct", action="store_true",
                        help="also plot the solvers called directly (not through fcl::distance)")
    args = parser.parse_args(argv)

    rows = read_rows(args.csv)
    if not args.include_direct:
        rows = [r for r in rows if r["path"] != "direct"]
    solvers = list(dict.fromkeys(r["solver"] for r in rows))
    families = [f for f in dict.fromkeys(r["family"] for r in rows) if f != "all"]
    palette = plt.get_cmap("tab20").colors
    colours = {f: palette[(2 * i) % 20 if i < 10 else (2 * (i - 10) + 1) % 20]
               for i, f in enumerate(families)}
    colours["all"] = "black"

    def clamp(e):
        return max(e, ERROR_FLOOR)

    fig, ax = plt.subplots(figsize=(12, 7.5), dpi=110)
    for row in rows:
        solver, family = row["solver"], row["family"]
        marker = MARKERS.get(solver, "o")
        colour = colours.get(family, "grey")
        pooled = family == "all"
        size = 11 if pooled else 7
        x = row["median_ns"]
        y_max, y_med = clamp(row["max_rel_err"]), clamp(row["median_rel_err"])
        ax.plot([x, x], [y_med, y_max], color=colour, linewidth=0.8, alpha=0.5, zorder=1)
        ax.plot(x, y_max, marker=marker, color=colour, markersize=size, linestyle="none",
                markeredgecolor="black" if pooled else colour, alpha=0.9, zorder=3)
        ax.plot(x, y_med, marker=marker, markerfacecolor="none", markeredgecolor=colour,
                markersize=size * 0.8, linestyle="none", alpha=0.8, zorder=2)

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median time per query [ns] (per family; lower is faster)")
    ax.set_ylabel("|d - d_ref| / (r1 + r2 + |c1 - c2|)")
    ax.set_title(args.title)
    ax.grid(True, which="major", alpha=0.3)
    ax.grid(True, which="minor", alpha=0.08)
    y_top = max(clamp(r["max_rel_err"]) for r in rows) * 5
    ax.set_ylim(ERROR_FLOOR / 4, max(y_top, 1e-2))
    ax.axhspan(ERROR_FLOOR / 4, ERROR_FLOOR, color="0.85", alpha=0.5, zorder=0)
    ax.axhline(ERROR_FLOOR, color="0.5", linewidth=0.8, linestyle=":", zorder=0)
    ax.text(ax.get_xlim()[1] / 1.05, ERROR_FLOOR * 0.55,
            "floor 1e-17: errors of 0 and below the reference's accuracy are drawn here",
            fontsize=8, color="0.3", va="center", ha="right")
    ax.axhline(EXACT_BOUND, color="tab:red", linewidth=0.8, linestyle="--", zorder=0)
    ax.text(ax.get_xlim()[0] * 1.05, EXACT_BOUND * 1.6, "1e-12: the exact solver's bound",
            fontsize=8, color="tab:red", va="bottom")

    solver_handles = [Line2D([], [], marker=MARKERS.get(s, "o"), color="0.3", linestyle="none",
                             markersize=8, label=s) for s in solvers]
    solver_handles += [
        Line2D([], [], marker="o", color="0.3", linestyle="none", markersize=7,
               label="filled: max error"),
        Line2D([], [], marker="o", markerfacecolor="none", markeredgecolor="0.3",
               linestyle="none", markersize=6, label="hollow: median error"),
    ]
    family_handles = [Line2D([], [], marker="o", color=colours[f], linestyle="none",
                             markersize=8, label=f) for f in families]
    family_handles.append(Line2D([], [], marker="o", color="black", linestyle="none",
                                 markersize=10, label="all families pooled"))
    legend1 = ax.legend(handles=solver_handles, title="solver (marker)", loc="upper left",
                        bbox_to_anchor=(1.01, 1.0), fontsize=8, title_fontsize=9)
    ax.add_artist(legend1)
    ax.legend(handles=family_handles, title="family (colour)", loc="lower left",
              bbox_to_anchor=(1.01, 0.0), fontsize=8, title_fontsize=9)
    fig.text(0.01, 0.01,
             "Each solver and configuration family: median time per query (x) against the "
             "median (hollow) and max (filled) error relative to scene size, vs a long-double "
             "reference.\nErrors below 1e-17, including exact zeros, are clamped to 1e-17 "
             "(shaded band). GJK runs on Cylinder(r, h), so its error includes the thickness h.",
             fontsize=8, color="0.25", va="bottom")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(args.png)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
