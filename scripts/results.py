#!/usr/bin/env python3
# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""Write docs/results.md from its template and the benchmarks' CSVs.

Usage: scripts/results.py [--results DIR] [--check]

docs/results.md.in is Markdown with placeholders, each on a line of its own:

    {{table FILE.csv}}                          the whole CSV as a table
    {{table FILE.csv cols=a,b,c}}               those columns, in that order
    {{table FILE.csv cols=a,b where=k:v,k2:v2}} only the rows where column k is v ...
    {{plot FILE.png Alt text}}                  the picture, with its alt text

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
import sys

ROOT = os.path.dirname(os.path.dirname(os.path.abspath(__file__)))
TEMPLATE = os.path.join(ROOT, "docs", "results.md.in")
OUTPUT = os.path.join(ROOT, "docs", "results.md")
PLACEHOLDER = re.compile(r"^\{\{\s*(table|plot)\s+(\S+)\s*(.*?)\s*\}\}\s*$")


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


def table(results, name, options, where_line):
    path = os.path.join(results, name)
    if not os.path.isfile(path):
        raise TemplateError("%s: no such CSV: %s" % (where_line, path))
    with open(path, newline="", encoding="utf-8") as f:
        rows = [r for r in csv.reader(f) if r and not r[0].startswith("#")]
    if not rows:
        raise TemplateError("%s: %s is empty" % (where_line, name))
    header, body = rows[0], rows[1:]
    columns = list(range(len(header)))
    for option in options:
        key, _, value = option.partition("=")
        if key == "cols":
            wanted = [c for c in value.split(",") if c]
            missing = [c for c in wanted if c not in header]
            if missing:
                raise TemplateError("%s: %s has no column %s (it has: %s)" % (
                    where_line, name, ", ".join(missing), ", ".join(header)))
            columns = [header.index(c) for c in wanted]
        elif key == "where":
            for condition in value.split(","):
                column, _, match = condition.partition(":")
                if column not in header:
                    raise TemplateError("%s: %s has no column %s" % (where_line, name, column))
                i = header.index(column)
                body = [r for r in body if i < len(r) and r[i] == match]
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


def plot(results, name, alt, where_line):
    path = os.path.join(results, name)
    if not os.path.isfile(path):
        raise TemplateError("%s: no such picture: %s" % (where_line, path))
    return ["![%s](%s)" % (alt or name, os.path.relpath(path, os.path.dirname(OUTPUT)))]


def render(results):
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
        if kind == "table":
            out += table(results, name, rest.split(), where_line)
        else:
            out += plot(results, name, rest, where_line)
    return "\n".join(out).rstrip("\n") + "\n"


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--results", default=os.path.join(ROOT, "Testing", "Benchmarks", "results"))
    parser.add_argument("--check", action="store_true",
                        help="exit 1 when docs/results.md is out of date; write nothing")
    args = parser.parse_args()
    try:
        made = render(os.path.abspath(args.results))
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
