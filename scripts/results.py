#!/usr/bin/python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Write docs/results.md from its template and the benchmarks' CSVs.

Usage: scripts/results.py [--results DIR] [--check]

docs/results.md.in is Markdown with placeholders, each on a line of its own:

    {{table FILE.csv}}                          the whole CSV as a table
    {{table FILE.csv cols=a,b,c}}               those columns, in that order
    {{table FILE.csv cols=a,b where=k:v,k2:v2}} only the rows where column k is v ...
    {{plot FILE.png Alt text}}                  the picture, with its alt text
    {{bars FILE.csv group=g series=s value=v [where=...] [logy] Alt text}}
                                                a bar chart of column v, one bar
                                                per series value in each group
                                                (FILE_v.png beside the CSV)

Options with spaces are quoted ("where=setting:step 0.1, 10 bisections");
where= takes conditions k:v joined by commas, and v may list alternatives
a|b|c (an empty alternative matches an empty cell).

FILE is a name in the results folder (default Testing/Benchmarks/results,
where scripts/bench.sh writes). Each table is followed by a link to its
CSV, so a figure in the docs is always the figure of a committed CSV.
--check writes nothing and exits 1 (with a diff) when docs/results.md is
not what the template and the CSVs make: the test PointSurfacesDocs-ResultsTables.
A missing file, column or row is an error, never an empty table.
"""
import argparse
import csv
import difflib
import os
import re
import shlex
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TEMPLATE = os.path.join(ROOT, "docs", "results.md.in")
OUTPUT = os.path.join(ROOT, "docs", "results.md")
PLACEHOLDER = re.compile(r"^\{\{\s*(table|plot|bars)\s+(\S+)\s*(.*?)\s*\}\}\s*$")


class TemplateError(Exception):
    pass


def number(text):
    """A CSV cell as the docs show it: integers whole, other numbers to 4 digits."""
    value = text.strip()
    try:
        if re.fullmatch(r"[+-]?\d+", value):
            return value
        x = float(value)
    except ValueError:
        return value.replace("|", "\\|")
    if x != x or x in (float("inf"), float("-inf")):
        return value
    if x == 0:
        return "0"
    if 1e-3 <= abs(x) < 1e6:
        return ("%.4g" % x)
    return "%.3g" % x


def read_csv(results, name, where_line):
    path = os.path.join(results, name)
    if not os.path.isfile(path):
        raise TemplateError("%s: no such CSV: %s" % (where_line, path))
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        raise TemplateError("%s: %s is empty" % (where_line, name))
    return path, rows[0], rows[1:]


def column(header, name, wanted, where_line):
    if wanted not in header:
        raise TemplateError("%s: %s has no column %s (it has: %s)" % (
            where_line, name, wanted, ", ".join(header)))
    return header.index(wanted)


def filtered(header, body, name, value, where_line):
    """The rows that meet every condition k:a|b of `value`."""
    for condition in re.split(r",(?=[\w.+-]+:)", value):
        key, _, match = condition.partition(":")
        i = column(header, name, key, where_line)
        accepted = match.split("|")
        body = [r for r in body if (r[i] if i < len(r) else "") in accepted]
    return body


def table(results, name, options, where_line):
    path, header, body = read_csv(results, name, where_line)
    columns = list(range(len(header)))
    for option in options:
        key, _, value = option.partition("=")
        if key == "cols":
            columns = [column(header, name, c, where_line) for c in value.split(",") if c]
        elif key == "where":
            body = filtered(header, body, name, value, where_line)
        else:
            raise TemplateError("%s: unknown option %r (cols=, where=)" % (where_line, option))
    if not body:
        raise TemplateError("%s: no rows of %s are left to show" % (where_line, name))
    lines = ["| " + " | ".join(header[i] for i in columns) + " |",
             "|" + "|".join("---" for _ in columns) + "|"]
    for r in body:
        lines.append("| " + " | ".join(number(r[i]) if i < len(r) else "" for i in columns)
                     + " |")
    link = os.path.relpath(path, os.path.dirname(OUTPUT))
    lines.append("")
    lines.append("<sub>From [%s](%s).</sub>" % (name, link))
    return lines


def bars(results, name, options, where_line, draw):
    """A grouped bar chart of one column; drawn (matplotlib) unless `draw` is off."""
    path, header, body = read_csv(results, name, where_line)
    keys, alt, logy = {}, [], False
    for option in options:
        key, equals, value = option.partition("=")
        if equals and key in ("group", "series", "value", "where"):
            keys[key] = value
        elif option == "logy":
            logy = True
        else:
            alt.append(option)
    missing = [k for k in ("group", "series", "value") if k not in keys]
    if missing:
        raise TemplateError("%s: bars needs %s=" % (where_line, "=, ".join(missing)))
    if "where" in keys:
        body = filtered(header, body, name, keys["where"], where_line)
    g, s, v = (column(header, name, keys[k], where_line) for k in ("group", "series", "value"))
    groups, series, values = [], [], {}
    for r in body:
        if (r[g], r[s]) in values:
            raise TemplateError("%s: %s has two rows for %s=%s, %s=%s: narrow where=" % (
                where_line, name, keys["group"], r[g], keys["series"], r[s]))
        try:
            values[(r[g], r[s])] = float(r[v])
        except ValueError:
            continue  # an empty cell: no bar
        groups += [r[g]] if r[g] not in groups else []
        series += [r[s]] if r[s] not in series else []
    if not values:
        raise TemplateError("%s: no values of %s are left to draw" % (where_line, keys["value"]))
    picture = os.path.splitext(path)[0] + "_" + re.sub(r"\W", "_", keys["value"]) + ".png"
    if draw:
        import matplotlib
        matplotlib.use("Agg")
        import matplotlib.pyplot as plt
        # Each group shows the series it has, side by side and centred;
        # a series keeps its colour in every group.
        present = {group: [label for label in series if (group, label) in values]
                   for group in groups}
        width = 0.8 / max(len(labels) for labels in present.values())
        fig, ax = plt.subplots(figsize=(max(6.0, 0.9 * len(groups) * max(1, len(series) / 3)), 4.5))
        colours = plt.rcParams["axes.prop_cycle"].by_key()["color"]
        for k, label in enumerate(series):
            xs, ys = [], []
            for i, group in enumerate(groups):
                if (group, label) in values:
                    at = present[group].index(label)
                    xs.append(i + (at - (len(present[group]) - 1) / 2) * width)
                    ys.append(values[(group, label)])
            ax.bar(xs, ys, width, color=colours[k % len(colours)],
                   label="%s=%s" % (keys["series"], label or "-"))
        ax.set_xticks(range(len(groups)))
        ax.set_xticklabels(groups, rotation=30 if len(groups) > 3 else 0, ha="right"
                           if len(groups) > 3 else "center")
        ax.set_ylabel(keys["value"])
        if logy:
            ax.set_yscale("log")
        ax.legend(fontsize="small", ncol=2)
        ax.set_title(os.path.basename(path))
        fig.tight_layout()
        fig.savefig(picture, dpi=90)
        plt.close(fig)
    elif not os.path.isfile(picture):
        raise TemplateError("%s: no %s: run scripts/results.py" % (where_line, picture))
    link = os.path.relpath(path, os.path.dirname(OUTPUT))
    return ["![%s](%s)" % (" ".join(alt) or name, os.path.relpath(picture, os.path.dirname(OUTPUT))),
            "", "<sub>Drawn from [%s](%s).</sub>" % (name, link)]


def plot(results, name, alt, where_line):
    path = os.path.join(results, name)
    if not os.path.isfile(path):
        raise TemplateError("%s: no such picture: %s" % (where_line, path))
    return ["![%s](%s)" % (alt or name, os.path.relpath(path, os.path.dirname(OUTPUT)))]


def render(results, draw):
    with open(TEMPLATE, encoding="utf-8") as f:
        template = f.read().split("\n")
    out = ["<!-- Made by scripts/results.py from docs/results.md.in and the CSVs of",
           "     Testing/Benchmarks/results: edit those, not this file. -->", ""]
    for number_, line in enumerate(template, 1):
        m = PLACEHOLDER.match(line)
        if not m:
            if "{{" in line and "}}" in line:
                raise TemplateError("docs/results.md.in:%d: a placeholder must be a line of its "
                                    "own: %s" % (number_, line.strip()))
            out.append(line)
            continue
        kind, name, rest = m.groups()
        where_line = "docs/results.md.in:%d" % number_
        if kind == "plot":
            out += plot(results, name, rest, where_line)
            continue
        try:
            options = shlex.split(rest)
        except ValueError as e:
            raise TemplateError("%s: %s" % (where_line, e)) from None
        if kind == "table":
            out += table(results, name, options, where_line)
        else:
            out += bars(results, name, options, where_line, draw)
    return "\n".join(out).rstrip("\n") + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", default=os.path.join(ROOT, "Testing", "Benchmarks", "results"))
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when docs/results.md is out of date; write nothing")
    args = parser.parse_args()
    try:
        made = render(os.path.abspath(args.results), draw=not args.check)
    except (TemplateError, OSError) as e:
        print("results.py: %s" % e, file=sys.stderr)
        return 1
    if args.check:
        try:
            with open(OUTPUT, encoding="utf-8") as f:
                current = f.read()
        except OSError:
            current = ""
        if current != made:
            sys.stdout.writelines(difflib.unified_diff(
                current.splitlines(True), made.splitlines(True), "docs/results.md (committed)",
                "docs/results.md (from the template and the CSVs)"))
            print("results.py: docs/results.md is out of date: run scripts/results.py",
                  file=sys.stderr)
            return 1
        print("docs/results.md matches docs/results.md.in and the CSVs")
        return 0
    with open(OUTPUT, "w", encoding="utf-8") as f:
        f.write(made)
    print("wrote %s" % os.path.relpath(OUTPUT, ROOT))
    return 0


if __name__ == "__main__":
    sys.exit(main())
