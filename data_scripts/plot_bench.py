#!/usr/bin/env python3
"""plot_bench.py DIR: speed against error from an oitbench run.

Reads DIR/results.json (written by oitbench) and writes DIR/speed_vs_error.png:
median ms per frame against mean rmse versus the Embree reference, log-log,
one marker per method, with the Pareto front (no other method both faster
and more exact) drawn as a line. Methods that could not run are listed in the
caption. Exact methods can reach rmse 0 on easy views; the log axis then
plots them at a floor below the smallest positive rmse, and says so.
Needs python3 and matplotlib (data_scripts only; no test depends on it).
"""
import json
import os
import sys


def load(dir_):
    with open(os.path.join(dir_, "results.json"), encoding="utf-8") as f:
        return json.load(f)


def points(run):
    """(name, ms, rmse) of the methods that rendered, and (name, reason) of the rest."""
    ok, skipped = [], []
    for m in run["methods"]:
        if m["ms_median"] is not None and m["rmse_mean"] is not None:
            ok.append((m["name"], float(m["ms_median"]), float(m["rmse_mean"])))
        else:
            skipped.append((m["name"], m["reason"]))
    return ok, skipped


def pareto_front(pts):
    """Points not dominated by another (<= in both ms and rmse, < in one), by ms."""
    front = []
    for name, ms, err in sorted(pts, key=lambda p: (p[1], p[2])):
        if not front or err < front[-1][2]:
            front.append((name, ms, err))
    return front


def plot(run, dir_):
    try:
        import matplotlib
    except ImportError:
        sys.exit("plot_bench.py: needs matplotlib (apt-get install python3-matplotlib)")
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    pts, skipped = points(run)
    if not pts:
        sys.exit("plot_bench.py: no method in %s/results.json rendered anything" % dir_)
    positive = [e for _, _, e in pts if e > 0]
    floor = min(positive) / 10 if positive else 1e-9
    shown = [(n, ms, e if e > 0 else floor) for n, ms, e in pts]

    fig, ax = plt.subplots(figsize=(7, 5))
    markers = "osD^v<>pPX*h"
    for i, (name, ms, err) in enumerate(shown):
        ax.scatter(ms, err, marker=markers[i % len(markers)], s=60, label=name, zorder=3)
        ax.annotate(name, (ms, err), textcoords="offset points", xytext=(6, 4), fontsize=9)
    front = pareto_front(shown)
    ax.plot([p[1] for p in front], [p[2] for p in front], "k--", lw=1, zorder=2,
            label="Pareto front")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("median ms per frame")
    ax.set_ylabel("mean rmse vs reference")
    ax.set_title("%s, %dx%d, %d views (%s)" % (os.path.basename(run["model"]), run["width"],
                                               run["height"], run["views"], run["renderer"]),
                 fontsize=9)
    notes = []
    if any(e == 0 for _, _, e in pts):
        notes.append("rmse 0 plotted at %.1e" % floor)
    notes += ["%s not run: %s" % s for s in skipped]
    if notes:
        fig.text(0.01, 0.01, "\n".join(notes), fontsize=7, va="bottom")
        fig.subplots_adjust(bottom=0.12 + 0.03 * len(notes))
    ax.grid(True, which="both", alpha=0.3)
    ax.legend(fontsize=8)
    out = os.path.join(dir_, "speed_vs_error.png")
    fig.savefig(out, dpi=120)
    print("wrote", out)


def main(argv):
    if len(argv) != 2 or argv[1] in ("-h", "--help"):
        print(__doc__.strip())
        return 0 if len(argv) == 2 else 2
    plot(load(argv[1]), argv[1])
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
