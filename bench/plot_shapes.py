#!/usr/bin/env python3
"""Plot fcl_disk_report's disk-vs-shape section: time per query against error, log-log.

Usage: plot_shapes.py SHAPES_CSV OUT_PNG [--title TITLE]

Reads shapes.csv (one row per shape, as fcl_disk_report writes it) and draws, per
shape (colour) and query (marker): a filled marker at (median ns/query, max error
relative to scale) and a hollow one at (median ns/query, median error), a
horizontal whisker from the median to the p99 time. Queries: disk (Disk(r)
against the shape through fcl::distance), disk_float (the same in float, whose
error is float's rounding), gjk_libccd / gjk_indep (FCL on
Cylinder(r, 0), the same disk), sphere_libccd / sphere_indep (FCL's Sphere(r):
time only, no reference, drawn in the "time only" strip at the bottom, as are
queries whose error was not computed). Errors of zero and below 1e-17 are drawn
on the 1e-17 floor. Queries not measured (skipped by the report) are absent.
Needs matplotlib (Debian: python3-matplotlib); Agg backend, no display needed.
"""

import argparse
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402
from matplotlib.lines import Line2D  # noqa: E402

ERROR_FLOOR = 1e-17
STRIP_Y = 1e-19  # where time-only points go
BOUND = 1e-12

QUERIES = [
    # (column prefix, marker, label, has error)
    ("disk", "o", "Disk(r) - X (fcl::distance)", True),
    ("disk_float", "P", "Disk(r) - X in float (fcl::distance)", True),
    ("gjk_libccd", "^", "FCL GJK libccd on Cylinder(r, 0)", True),
    ("gjk_indep", "v", "FCL GJK indep on Cylinder(r, 0)", True),
    ("sphere_libccd", "s", "FCL Sphere(r) - X, libccd (time only)", False),
    ("sphere_indep", "D", "FCL Sphere(r) - X, indep (time only)", False),
]


def number(text):
    return float(text) if text not in ("", None) else None


def main(argv):
    parser = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    parser.add_argument("csv", help="shapes.csv written by fcl_disk_report")
    parser.add_argument("png", help="output PNG")
    parser.add_argument("--title", default="Disk against other FCL shapes: time per query "
                        "against error (all through fcl::distance)")
    args = parser.parse_args(argv)

    with open(args.csv, newline="") as f:
        rows = list(csv.DictReader(f))
    shapes = [r["shape"] for r in rows]
    palette = plt.get_cmap("tab20").colors
    colours = {s: palette[(2 * i) % 20 if i < 10 else (2 * (i - 10) + 1) % 20]
               for i, s in enumerate(shapes)}

    fig, ax = plt.subplots(figsize=(12, 7.5), dpi=110)
    any_error = False
    xs = []
    for row in rows:
        colour = colours[row["shape"]]
        for prefix, marker, _, has_error in QUERIES:
            x = number(row.get(prefix + "_median_ns"))
            if x is None:
                continue
            xs.append(x)
            p99 = number(row.get(prefix + "_p99_ns"))
            y_max = number(row.get(prefix + "_max_rel_err")) if has_error else None
            y_med = number(row.get(prefix + "_median_rel_err")) if has_error else None
            if y_max is None:
                y_max = y_med = STRIP_Y
            else:
                any_error = True
                y_max, y_med = max(y_max, ERROR_FLOOR), max(y_med, ERROR_FLOOR)
            if p99 is not None and p99 > x:
                xs.append(p99)
                ax.plot([x, p99], [y_max, y_max], color=colour, linewidth=0.8, alpha=0.6,
                        zorder=1)
            if y_med != y_max:
                ax.plot([x, x], [y_med, y_max], color=colour, linewidth=0.8, alpha=0.5,
                        zorder=1)
                ax.plot(x, y_med, marker=marker, markerfacecolor="none", markeredgecolor=colour,
                        markersize=7, linestyle="none", zorder=2)
            ax.plot(x, y_max, marker=marker, color=colour, markersize=9, linestyle="none",
                    markeredgecolor="black" if prefix == "disk" else colour, zorder=3)

    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("time per query [ns]: marker at the median over the cases, whisker to p99")
    ax.set_ylabel("|d - d_ref| / (r + R_S + |c_D - c_S|)")
    ax.set_title(args.title)
    ax.grid(True, which="major", alpha=0.3)
    ax.grid(True, which="minor", alpha=0.08)
    ax.set_ylim(STRIP_Y / 10, 1.0)
    if xs:
        ax.set_xlim(min(xs) / 1.5, max(xs) * 1.5)
    ax.axhspan(STRIP_Y / 10, STRIP_Y * 10, color="0.9", zorder=0)
    ax.text(ax.get_xlim()[1] / 1.05, STRIP_Y * 3,
            "time only: FCL's Sphere(r)" + ("" if any_error else
                                            "; no reference in this run, so no errors"),
            fontsize=8, color="0.3", va="center", ha="right")
    ax.axhline(ERROR_FLOOR, color="0.5", linewidth=0.8, linestyle=":", zorder=0)
    ax.text(ax.get_xlim()[0] * 1.05, ERROR_FLOOR * 1.6,
            "floor 1e-17: errors of 0 and below are drawn here", fontsize=8, color="0.3",
            va="bottom")
    ax.axhline(BOUND, color="tab:red", linewidth=0.8, linestyle="--", zorder=0)
    ax.text(ax.get_xlim()[0] * 1.05, BOUND * 1.6, "1e-12 of scale", fontsize=8,
            color="tab:red", va="bottom")

    query_handles = [Line2D([], [], marker=m, color="0.3", linestyle="none", markersize=8,
                            label=label) for _, m, label, _ in QUERIES]
    query_handles += [
        Line2D([], [], marker="o", color="0.3", linestyle="none", markersize=7,
               label="filled: max error"),
        Line2D([], [], marker="o", markerfacecolor="none", markeredgecolor="0.3",
               linestyle="none", markersize=6, label="hollow: median error"),
    ]
    shape_handles = [Line2D([], [], marker="o", color=colours[s], linestyle="none",
                            markersize=8, label=s) for s in shapes]
    legend1 = ax.legend(handles=query_handles, title="query (marker)", loc="upper left",
                        bbox_to_anchor=(1.01, 1.0), fontsize=8, title_fontsize=9)
    ax.add_artist(legend1)
    legend2 = ax.legend(handles=shape_handles, title="shape X (colour)", loc="lower left",
                        bbox_to_anchor=(1.01, 0.0), fontsize=8, title_fontsize=9)
    note = fig.text(0.01, 0.01,
                    "Per shape: median time per query (x; whisker to p99) against the max "
                    "(filled) and median (hollow) error of the disk's distance relative to "
                    "r + R_S + |c_D - c_S|, vs a long-double reference.\nQueries the report "
                    "skipped (crashes, pairs FCL does not support) are absent; shapes.csv "
                    "names them.",
                    fontsize=8, color="0.25", va="bottom")
    fig.tight_layout(rect=(0, 0.05, 1, 1))
    fig.savefig(args.png, bbox_inches="tight", bbox_extra_artists=[legend1, legend2, note])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
