#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""docs/testing.md's table of the baseline tests' bounds is the tests' own.

Usage: CheckDocumentedBounds.py DOCS_TESTING_MD MAPPER_TEST_SOURCE_DIR

The table after the marker `<!-- bounds table: ... -->` has one row per baseline test:
`| TestName | rmse / bound | share % / bound % | mirror / bound | notes |`. For every row the
bounds must equal the test source's `c.ReferenceBound`, `c.ReferenceOffBound` (a fraction; the
table shows per cent) and `c.MirrorBound`, and every measured figure must lie below its bound.
Every TestSinglePassAMR*.cxx that sets `c.ReferenceBound` must have a row. The check then shows
that it rejects the table with one bound changed and with one row removed. Prints ok/FAIL lines,
PASS at the end; exits 1 on any failure.
"""
import os
import re
import sys

MARKER = "<!-- bounds table:"
PAIR = re.compile(r"^\s*([\d.]+)\s*%?\s*/\s*([\d.]+)\s*%?\s*$")


def table_rows(text):
    """{test: (rmse, rmse bound, share %, share bound %, mirror, mirror bound)} of the table."""
    lines = text[text.index(MARKER):].splitlines()[1:]
    rows = {}
    for line in lines[2:]:
        if not line.startswith("|"):
            break
        cells = [c.strip() for c in line.strip().strip("|").split("|")]
        values = []
        for cell in cells[1:4]:
            m = PAIR.match(cell)
            if not m:
                raise ValueError(f"row {cells[0]}: '{cell}' is not 'measured / bound'")
            values += [float(m.group(1)), float(m.group(2))]
        rows[cells[0]] = tuple(values)
    return rows


def source_bounds(source_dir):
    """{test: (reference bound, off bound in per cent, mirror bound)} from the test sources."""
    found = {}
    for name in sorted(os.listdir(source_dir)):
        if not (name.startswith("TestSinglePassAMR") and name.endswith(".cxx")):
            continue
        text = open(os.path.join(source_dir, name), encoding="utf-8").read()
        get = lambda key: re.search(r"\bc\." + key + r"\s*=\s*([\d.]+)\s*;", text)
        ref, off, mirror = get("ReferenceBound"), get("ReferenceOffBound"), get("MirrorBound")
        if ref:
            found[name[:-4]] = (float(ref.group(1)), 100.0 * float(off.group(1)) if off else 5.0,
                                float(mirror.group(1)) if mirror else 1.0)
    return found


def problems(rows, bounds):
    out = []
    for test in sorted(set(bounds) - set(rows)):
        out.append(f"{test} sets bounds but has no row in the table")
    for test in sorted(set(rows) - set(bounds)):
        out.append(f"the table's row {test} names no test source with bounds")
    for test in sorted(set(rows) & set(bounds)):
        rmse, rmse_bound, share, share_bound, mirror, mirror_bound = rows[test]
        ref, off, mir = bounds[test]
        for what, documented, actual in (("reference RMSE bound", rmse_bound, ref),
                                         ("share bound (%)", share_bound, off),
                                         ("mirror RMSE bound", mirror_bound, mir)):
            if abs(documented - actual) > 1e-9:
                out.append(f"{test}: the table's {what} is {documented}, the test's {actual:g}")
        for what, measured, bound in (("reference RMSE", rmse, rmse_bound),
                                      ("share", share, share_bound), ("mirror RMSE", mirror, mirror_bound)):
            if not measured < bound:
                out.append(f"{test}: measured {what} {measured} is not below its bound {bound}")
    return out


def main(argv):
    docs, source_dir = argv[1], argv[2]
    text = open(docs, encoding="utf-8").read()
    rows = table_rows(text)
    bounds = source_bounds(source_dir)
    failures = problems(rows, bounds)
    for f in failures:
        print("FAIL: " + f)
    if not failures:
        print(f"ok: {len(rows)} rows, each bound the test's own and each measured figure below it")
    # the check rejects a changed bound and a missing row
    if rows:
        first = sorted(rows)[0]
        changed = dict(rows)
        values = list(changed[first])
        values[1] += 0.5
        changed[first] = tuple(values)
        missing = dict(rows)
        del missing[first]
        for what, variant in (("a reference bound changed by 0.5", changed),
                              ("a row removed", missing)):
            if problems(variant, bounds):
                print(f"ok: the check rejects the table with {what} ({first})")
            else:
                print(f"FAIL: the check does not reject the table with {what}")
                failures.append(what)
    if len(rows) < 10:
        print(f"FAIL: only {len(rows)} rows found after the marker")
        failures.append("rows")
    print("PASS" if not failures else "FAIL: the bounds table and the tests disagree")
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
