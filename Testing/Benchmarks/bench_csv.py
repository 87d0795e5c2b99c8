# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What the benchmark scripts share: their rows as CSV, to a file and to stdout, and
--fitter-option NAME VALUE pairs."""
import csv
import sys


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
