# SPDX-FileCopyrightText: Copyright (c) PointSurfaces contributors
# SPDX-License-Identifier: BSD-3-Clause
"""What the benchmark scripts share: their rows as CSV, to a file and to stdout."""
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
