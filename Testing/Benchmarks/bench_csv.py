# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What the benchmark scripts share: their rows as CSV, to a file and to stdout,
--fitter-option NAME VALUE pairs, the inputs they read (committed data, or
full-size files in a --data folder), a process's peak memory, and the JSON a
benchmark's child process prints."""
import csv
import glob
import json
import os
import subprocess
import sys

ROOT = os.path.normpath(os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", ".."))
TEST_DATA = os.path.join(ROOT, "Testing", "Data")  # small inputs a clean clone has
IO_DATA = os.path.join(ROOT, "IO", "Testing", "Data")
# vtkAlgebraicSplatFitter's ToleranceUnit values by index, as the CSVs name them.
TOLERANCE_UNITS = ("spacing", "noise", "absolute", "automatic")


def find_input(folder, name, what):
    """The path of the file `name` in `folder` (or in a folder one level below it), or
    None after one line on stderr saying that `what` is skipped and why."""
    for path in [os.path.join(folder, name)] + sorted(glob.glob(os.path.join(folder, "*", name))):
        if os.path.isfile(path):
            return path
    skip(what, "no %s in %s" % (name, folder))
    return None


def skip(what, why):
    """The one line a benchmark prints for an input it skips."""
    print("%s: skipped %s: %s" % (os.path.basename(sys.argv[0]), what, why), file=sys.stderr)


def skip_unreadable(path, error):
    """skip() for a file that cannot be read (error: a ScanReadError, which names it)."""
    text = str(error)
    skip(path, text[len(path) + 2:] if text.startswith(path + ": ") else text)


def write_rows(path, rows, fields=None):
    """Writes `rows` (dicts) to `path` and to stdout, columns `fields` (default: the first
    row's keys)."""
    fields = fields or list(rows[0].keys())
    with open(path, "w", newline="") as f:
        writer = csv.DictWriter(f, fieldnames=fields)
        writer.writeheader()
        writer.writerows(rows)
    writer = csv.DictWriter(sys.stdout, fieldnames=fields)
    writer.writeheader()
    writer.writerows(rows)


def fitter_options(parser, pairs, cls):
    """The (NAME, number) pairs of --fitter-option NAME VALUE, each checked to name a
    SetNAME of `cls`; an integer where VALUE has no decimal point."""
    options = []
    for name, value in pairs:
        if not hasattr(cls, "Set" + name):
            parser.error("--fitter-option: %s has no Set%s" % (cls.__name__, name))
        try:
            number = float(value)
        except ValueError:
            parser.error("--fitter-option %s: %r is not a number" % (name, value))
        options.append((name, int(number) if number.is_integer() and "." not in value else number))
    return options


def scatter_time_vs_rmse(rows, methods, png, title, ylabel, xlabel="frame time (ms, median)",
                         note=None, size=(6.5, 4)):
    """One plot of each row's rmse against its frame_ms (log scale), a marker per
    (method, marker) of `methods`; note(row) labels a point (None or "": no label)."""
    import matplotlib
    matplotlib.use("Agg")
    import matplotlib.pyplot as plt
    fig, ax = plt.subplots(figsize=size)
    for method, marker in methods:
        sel = [r for r in rows if r["method"] == method]
        if not sel:
            continue
        ax.scatter([float(r["frame_ms"]) for r in sel], [float(r["rmse"]) for r in sel],
                   marker=marker, label=method)
        for r in sel:
            text = note(r) if note else None
            if text:
                ax.annotate(text, (float(r["frame_ms"]), float(r["rmse"])), fontsize=6)
    ax.set_xscale("log")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(ylabel)
    ax.set_title(title)
    ax.grid(True, alpha=0.3)
    ax.legend(fontsize=7)
    fig.tight_layout()
    fig.savefig(png, dpi=100)
    plt.close(fig)
    print("# wrote " + png)


def peak_resident_gib():
    """This process's peak resident set since it started its program (Linux's
    VmHWM; getrusage's ru_maxrss would also count the parent's pages that a
    child shares until exec), in GiB."""
    try:
        with open("/proc/self/status") as status:
            for line in status:
                if line.startswith("VmHWM:"):
                    return int(line.split()[1]) / 1024.0 / 1024.0
    except OSError:
        pass
    import resource
    return resource.getrusage(resource.RUSAGE_SELF).ru_maxrss / 1024.0 / 1024.0


def run_json_child(command, what):
    """Runs `command` (a benchmark's child process, which prints its results as JSON on its last
    line of output) and returns them; RuntimeError naming `what` when it fails."""
    done = subprocess.run(command, stdout=subprocess.PIPE, text=True)
    if done.returncode != 0:
        raise RuntimeError("%s failed (status %d)" % (what, done.returncode))
    return json.loads(done.stdout.strip().splitlines()[-1])
