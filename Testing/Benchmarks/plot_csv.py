#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Plot a benchmark CSV: plot_csv.py data.csv out.png X Y [Y ...] [--logx] [--logy]."""
import csv
import sys

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt  # noqa: E402


def main(argv):
    flags = {a for a in argv if a.startswith("--")}
    args = [a for a in argv if not a.startswith("--")]
    if len(args) < 4:
        print(__doc__)
        return 2
    data, out, x, ys = args[0], args[1], args[2], args[3:]
    with open(data) as f:
        rows = [r for r in csv.DictReader(f)]
    if not rows:
        print("plot_csv.py: no rows in " + data)
        return 1
    fig, ax = plt.subplots(figsize=(6, 4))
    for y in ys:
        ax.plot([float(r[x]) for r in rows], [float(r[y]) for r in rows], marker="o", label=y)
    ax.set_xlabel(x)
    if "--logx" in flags:
        ax.set_xscale("log")
    if "--logy" in flags:
        ax.set_yscale("log")
    ax.grid(True, alpha=0.3)
    ax.legend()
    fig.tight_layout()
    fig.savefig(out, dpi=100)
    print("plot_csv.py: wrote " + out)
    return 0


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
