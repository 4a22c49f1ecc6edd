# Draws a `reeve bench` CSV as a PNG (matplotlib). Run by `reeve bench
# ... --plot FILE`, which pipes this script to `python3 - KIND CSV PNG`;
# by hand: python3 bench/plot.py KIND CSV PNG, KIND table1 | trade | extremes | scaling.
import csv
import math
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def rows(path):
    with open(path, newline="") as f:
        return list(csv.DictReader(f))


def num(text):
    return float(text) if text not in ("", None) else math.nan


def footer(fig, r):
    if r:
        fig.text(0.01, 0.005, f"{r[0]['cpu']}, {r[0]['compiler']}, {r[0]['build_type']}, {r[0]['date']}",
                 fontsize=7, color="0.4")


def table1(r, png):
    # Paper settings only: ours (per solver) against the paper's ms/frame.
    paper = [x for x in r if x["setting"] == "paper"]
    labels = []
    for x in paper:
        label = f"{x['machine']}\n{x['substeps']}x{x['iterations']}"
        if label not in labels:
            labels.append(label)
    solvers = sorted({x["solver"] for x in paper})
    fig, ax = plt.subplots(figsize=(10, 4.5))
    width = 0.8 / (len(solvers) + 1)
    for k, solver in enumerate(solvers + ["paper"]):
        ys = []
        for label in labels:
            match = [x for x in paper if f"{x['machine']}\n{x['substeps']}x{x['iterations']}" == label
                     and (solver == "paper" or x["solver"] == solver)]
            key = "paper_ms" if solver == "paper" else "median_ms"
            ys.append(num(match[0][key]) if match else math.nan)
        xs = [i + (k - len(solvers) / 2) * width for i in range(len(labels))]
        ax.bar(xs, ys, width, label="paper (3.5 GHz Core i7)" if solver == "paper" else f"Reeve, {solver}")
    ax.set_yscale("log")
    ax.set_xticks(range(len(labels)))
    ax.set_xticklabels(labels, fontsize=8)
    ax.set_ylabel("ms per frame (median)")
    ax.set_title("Table 1 at the paper's settings (substeps x iterations)")
    ax.legend(fontsize=8)
    footer(fig, r)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(png, dpi=110, format="png")


def trade(r, png):
    cases = []
    for x in r:
        if x["case"] not in cases:
            cases.append(x["case"])
    cols = min(3, len(cases))
    nrows = math.ceil(len(cases) / cols)
    fig, axes = plt.subplots(nrows, cols, figsize=(5 * cols, 3.8 * nrows), squeeze=False)
    for i, case in enumerate(cases):
        ax = axes[i // cols][i % cols]
        mine = [x for x in r if x["case"] == case]
        for series in sorted({x["series"] for x in mine}):
            pts = [(num(x["ms_per_frame"]), num(x["error"]), x["pareto"] == "1") for x in mine
                   if x["series"] == series and x["error"] != ""]
            pts = [p for p in pts if p[1] > 0]
            if not pts:
                continue
            line = ax.scatter([p[0] for p in pts], [p[1] for p in pts], s=10, alpha=0.6, label=series)
            front = sorted((p[0], p[1]) for p in pts if p[2])
            ax.plot([p[0] for p in front], [p[1] for p in front], color=line.get_facecolor()[0], lw=1.2)
        ax.set_xscale("log")
        ax.set_yscale("log")
        ax.set_title(case, fontsize=9)
        ax.set_xlabel("ms per frame")
        ax.set_ylabel("relative error")
        ax.grid(True, which="major", alpha=0.3)
        ax.legend(fontsize=6)
    for j in range(len(cases), nrows * cols):
        axes[j // cols][j % cols].axis("off")
    fig.suptitle("Error against the closed form vs cost; lines: Pareto fronts")
    footer(fig, r)
    fig.tight_layout(rect=(0, 0.02, 1, 0.97))
    fig.savefig(png, dpi=100, format="png")


def extremes(r, png):
    solvers = sorted({x["solver"] for x in r})
    conds = []
    budgets = []
    for x in r:
        c = f"{x['machine']} {x['condition']}"
        b = f"{num(x['rate_hz']):g} Hz {x['substeps']}x{x['iterations']}"
        if c not in conds:
            conds.append(c)
        if b not in budgets:
            budgets.append(b)
    from matplotlib.colors import ListedColormap
    cmap = ListedColormap(["#d62728", "#2ca02c", "#ffffff"])  # unstable, stable, not run
    fig, axes = plt.subplots(1, len(solvers), figsize=(max(8, 0.28 * len(budgets)) * len(solvers) / 1.4,
                                                        0.25 * len(conds) + 2.5), squeeze=False)
    for k, solver in enumerate(solvers):
        grid = [[2] * len(budgets) for _ in conds]
        stable = total = 0
        for x in r:
            if x["solver"] != solver:
                continue
            i = conds.index(f"{x['machine']} {x['condition']}")
            j = budgets.index(f"{num(x['rate_hz']):g} Hz {x['substeps']}x{x['iterations']}")
            grid[i][j] = 1 if x["stable"] == "1" else 0
            stable += x["stable"] == "1"
            total += 1
        ax = axes[0][k]
        ax.imshow(grid, cmap=cmap, vmin=0, vmax=2, aspect="auto", interpolation="nearest")
        ax.set_yticks(range(len(conds)))
        ax.set_yticklabels(conds if k == 0 else [""] * len(conds), fontsize=6)
        ax.set_xticks(range(len(budgets)))
        ax.set_xticklabels(budgets, rotation=90, fontsize=6)
        ax.set_title(f"{solver}: {stable} of {total} cells stable (green)", fontsize=9)
    footer(fig, r)
    fig.tight_layout(rect=(0, 0.02, 1, 1))
    fig.savefig(png, dpi=100, format="png")

def scaling(r, png):
    # One line per series, solver and budget: ms/frame against K, log-log.
    fig, ax = plt.subplots(figsize=(9, 6))
    lines = []
    for x in r:
        key = (x["series"], x["solver"], x["budget"])
        if key not in lines:
            lines.append(key)
    for series, solver, budget in lines:
        pts = [(num(x["K"]), num(x["ms_per_frame"])) for x in r
               if (x["series"], x["solver"], x["budget"]) == (series, solver, budget) and x["ms_per_frame"] != ""]
        pts = [p for p in pts if p[1] > 0]
        if not pts:
            continue
        ax.plot([p[0] for p in pts], [p[1] for p in pts], marker="o", ms=3, lw=1,
                ls="-" if solver == "direct" else "--", label=f"{series} {solver} {budget}")
    ax.set_xscale("log")
    ax.set_yscale("log")
    ax.set_xlabel("K")
    ax.set_ylabel("ms per frame")
    ax.set_title("Cost against K (solid: direct, dashed: Gauss-Seidel)")
    ax.legend(fontsize=6, ncol=2)
    footer(fig, r)
    fig.tight_layout(rect=(0, 0.03, 1, 1))
    fig.savefig(png, dpi=110, format="png")


if __name__ == "__main__":
    kind, source, target = sys.argv[1:4]
    {"table1": table1, "trade": trade, "extremes": extremes, "scaling": scaling}[kind](rows(source), target)
