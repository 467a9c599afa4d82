#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""Testing.CoverageMatrix: docs/testing.md's coverage matrix says what this configuration runs.

Usage: CheckCoverageMatrix.py DOCS_TESTING_MD CONFIG BUILD_DIR CONFIGS_SH

The table after the marker `<!-- coverage matrix` has one row per feature:
`| feature | differs by | pass | tests | <one column per configuration> |`.
- `tests`: shell-style patterns of ctest test names (`Core.KdTree.*`), separated by spaces, or the
  word `package` (scripts/test-package.sh's checks, which are not ctest tests);
- `pass`: `any` (the union of the configuration's backend passes) or one backend (`glx`, `egl`,
  `osmesa`): the tests of that pass only;
- a cell starts with `full`, `smoke` or `—`, then its reasons as legend codes: **B** …
  (the legend list right above the table defines them; a smoke or untested cell needs one);
- `differs by`: `—` when the code is the same in every configuration, else what differs (VTK,
  ParaView, window system, …): such a row may be untested only where it does not exist (code N)
  or where the same build is tested fully in another configuration (code S).

Against the tests this configuration runs (for each backend pass: `ctest -N` with the selection
scripts/configs.sh's `amrsp_ctest_selection` gives scripts/run-tests.sh) it checks:
- `full`: the row matches at least one test of the pass, and every registered test it matches runs;
- `smoke`: the row matches at least one test that runs;
- `—`: the row matches no test that runs;
- every registered test belongs to a row; every row is `full` somewhere; the legend and columns.
Then it shows that the check rejects the matrix when a row's tests are renamed away, when a
registered test is left out of every row, and when a cell says `—` for tests that run.
Prints ok/FAIL lines and PASS at the end; exits 1 on a failure, 125 (SKIPPED) when the build folder
is none of the scripts' configurations, unless AMRSP_REQUIRE_GPU=1 (CI), where that fails.
"""
import fnmatch
import json
import os
import re
import subprocess
import sys

MARKER = "<!-- coverage matrix"
STATUSES = ("full", "smoke", "—")
PASSES = ("any", "glx", "egl", "osmesa")
NOT_THERE = "N"  # the legend code of a cell whose code does not exist in that configuration
SAME_BUILD = "S"  # the legend code of a cell whose build is tested fully in another configuration


def split_row(line):
    """The cells of a Markdown table row; `\\|` is a literal bar."""
    cells = re.split(r"(?<!\\)\|", line.strip().strip("|"))
    return [c.strip().replace("\\|", "|") for c in cells]


class Matrix:
    def __init__(self, text):
        at = text.index(MARKER)
        before, after = text[:at], text[at:].splitlines()[1:]
        # the legend: the "- **X**: ..." items between the section's heading and the marker
        section = before[before.rfind("\n## "):]
        self.legend = set(re.findall(r"^- \*\*([A-Z])\*\*", section, re.M))
        header = split_row(after[0])
        if header[:4] != ["feature", "differs by", "pass", "tests"]:
            raise ValueError("the header must start with feature | differs by | pass | tests, "
                             "not %s" % header[:4])
        self.configs = header[4:]
        self.rows = []
        for line in after[2:]:
            if not line.startswith("|"):
                break
            cells = split_row(line)
            if len(cells) != len(header):
                raise ValueError("row '%s' has %d cells, the header %d"
                                 % (cells[0], len(cells), len(header)))
            self.rows.append({"feature": cells[0], "differs": cells[1], "pass": cells[2],
                              "tests": cells[3].replace("`", "").split(),
                              "cells": dict(zip(self.configs, cells[4:]))})


def cell_status(cell):
    """(status, reason codes) of a cell such as 'smoke: B, V' or '— N'."""
    for status in STATUSES:
        if cell.startswith(status):
            return status, re.findall(r"\b([A-Z])\b", cell[len(status):])
    return None, []


def matches(row, names):
    return {n for n in names if any(fnmatch.fnmatchcase(n, p) for p in row["tests"])}


def check(matrix, config, known_configs, registered, passes, packaged):
    """The problems of `matrix` for `config`: registered = every ctest test of the build;
    passes = {backend: the tests that backend's pass runs}; packaged = whether the configuration
    has a package test."""
    problems = []
    if sorted(matrix.configs) != sorted(known_configs):
        problems.append("the columns %s are not the configurations %s"
                        % (matrix.configs, known_configs))
    if config not in matrix.configs:
        return problems + ["no column for %s" % config]
    running = set().union(*passes.values()) if passes else set()
    claimed = set()
    for row in matrix.rows:
        name = row["feature"]
        statuses = [cell_status(c) for c in row["cells"].values()]
        for (status, reasons), (column, cell) in zip(statuses, row["cells"].items()):
            if status is None:
                problems.append("%s, %s: '%s' starts with none of %s" % (name, column, cell,
                                                                         STATUSES))
            elif status != "full" and not reasons:
                problems.append("%s, %s: a %s cell must say why (a legend code)"
                                % (name, column, status))
            unknown = [r for r in reasons if r not in matrix.legend]
            if unknown:
                problems.append("%s, %s: %s not in the legend" % (name, column, unknown))
            if (status == "—" and row["differs"] not in ("—", "")
                    and not {NOT_THERE, SAME_BUILD} & set(reasons)):
                problems.append("%s differs by %s: it must be tested in %s, where its code exists"
                                " (or say %s or %s)" % (name, row["differs"], column, NOT_THERE,
                                                        SAME_BUILD))
        if not any(s == "full" for s, _ in statuses):
            problems.append("%s: no configuration tests it fully" % name)
        if row["pass"] not in PASSES:
            problems.append("%s: pass '%s' is none of %s" % (name, row["pass"], PASSES))
            continue
        status, _ = cell_status(row["cells"][config])
        if row["tests"] == ["package"]:
            if (status in ("full", "smoke")) != packaged:
                problems.append("%s: the %s cell says %s, but the package test %s here"
                                % (name, config, status, "runs" if packaged else "does not run"))
            continue
        claimed |= matches(row, registered)
        if row["pass"] == "any":
            runs = running
        else:
            runs = passes.get(row["pass"], set())
        run_here = matches(row, runs)
        if status in ("full", "smoke") and not run_here:
            problems.append("%s: the %s cell says %s, but none of %s runs in the %s pass"
                            % (name, config, status, row["tests"], row["pass"]))
        if status == "full":
            left_out = matches(row, registered) - run_here
            if row["pass"] != "any" and row["pass"] not in passes:
                left_out = set()
            if left_out:
                problems.append("%s: the %s cell says full, but %s are registered and do not run"
                                % (name, config, sorted(left_out)[:5]))
        if status == "—" and run_here:
            problems.append("%s: the %s cell says —, but %s run" % (name, config,
                                                                     sorted(run_here)[:5]))
    unclaimed = sorted(registered - claimed)
    if unclaimed:
        problems.append("%d registered tests belong to no row: %s" % (len(unclaimed),
                                                                      unclaimed[:8]))
    return problems


def ctest_names(build, arguments):
    out = subprocess.run(["ctest", "--show-only=json-v1"] + arguments, cwd=build, check=True,
                         stdout=subprocess.PIPE, universal_newlines=True).stdout
    return {t["name"] for t in json.loads(out)["tests"]}


def shell_lines(configs_sh, function, *arguments):
    out = subprocess.run(["bash", "-c", '. "$0"; "$@"', configs_sh, function] + list(arguments),
                         stdout=subprocess.PIPE, universal_newlines=True)
    if out.returncode != 0:
        return None
    return [line for line in out.stdout.splitlines() if line]


def main():
    doc, config, build, configs_sh = sys.argv[1:5]
    known = subprocess.run(["bash", "-c", '. "$0"; echo "$AMRSP_ALL_CONFIGS"', configs_sh],
                           stdout=subprocess.PIPE, universal_newlines=True).stdout.split()
    if config not in known:
        message = ("the build folder '%s' is none of the scripts' configurations (%s): the matrix "
                   "has no column for it" % (config, " ".join(known)))
        if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
            print("FAIL: required here (AMRSP_REQUIRE_GPU=1): " + message)
            return 1
        print("SKIPPED: " + message)
        return 125
    matrix = Matrix(open(doc, encoding="utf-8").read())
    registered = ctest_names(build, [])
    passes = {}
    for backend in shell_lines(configs_sh, "amrsp_config_backends", config)[0].split():
        selection = shell_lines(configs_sh, "amrsp_ctest_selection", config, backend) or []
        passes[backend] = ctest_names(build, selection)
    packaged = shell_lines(configs_sh, "amrsp_config_packaged", config) is not None
    failures = 0

    def report(ok, message):
        nonlocal failures
        print("%s %s" % ("ok  " if ok else "FAIL:", message))
        failures += 0 if ok else 1

    problems = check(matrix, config, known, registered, passes, packaged)
    for p in problems:
        report(False, p)
    running = set().union(*passes.values())
    report(not problems, "%s: %d rows, %d registered tests, %s run (%s), package test: %s"
           % (config, len(matrix.rows), len(registered),
              " + ".join(str(len(passes[b])) for b in passes), ", ".join(passes), packaged))

    # The controls: each broken matrix (or build) must be rejected, for the reason it was broken.
    tested = [r for r in matrix.rows if r["tests"] != ["package"]
              and cell_status(r["cells"][config])[0] in ("full", "smoke")
              and matches(r, running)]

    def alone_in(row, rows):
        """The registered tests of `row` that no other row of `rows` matches."""
        others = [r for r in rows if r["feature"] != row["feature"] and r["tests"] != ["package"]]
        return matches(row, registered) - set().union(*(matches(r, registered) for r in others))

    # the controls' row: tested here, with tests of its own (dropping it must orphan them)
    tested = [r for r in tested if alone_in(r, matrix.rows)]
    if not tested:
        report(False, "no row is tested here with tests no other row names: the controls need one")
        return 1
    row = tested[0]

    def rejects(found, phrase):
        new = [p for p in found if phrase in p and p not in problems]
        return new[0] if new else None

    mine = matches(row, registered)
    renamed = {("Renamed." + n if n in mine else n) for n in registered}
    renamed_passes = {b: {("Renamed." + n if n in mine else n) for n in s}
                      for b, s in passes.items()}
    found = check(matrix, config, known, renamed, renamed_passes, packaged)
    gone, orphans = rejects(found, "none of"), rejects(found, "belong to no row")
    report(gone is not None and orphans is not None,
           "rejects the matrix when the %d tests of '%s' are renamed away: %s; %s"
           % (len(mine), row["feature"], gone, orphans))
    dropped = Matrix(open(doc, encoding="utf-8").read())
    alone = alone_in(row, dropped.rows)
    dropped.rows = [r for r in dropped.rows if r["feature"] != row["feature"]]
    found = rejects(check(dropped, config, known, registered, passes, packaged),
                    "belong to no row")
    report(bool(alone) and found is not None,
           "rejects the matrix without the row '%s' (%d of its tests in no other row): %s"
           % (row["feature"], len(alone), found))
    lying = Matrix(open(doc, encoding="utf-8").read())
    for r in lying.rows:
        if r["feature"] == row["feature"]:
            r["cells"][config] = "— " + NOT_THERE
    found = rejects(check(lying, config, known, registered, passes, packaged), "cell says —, but")
    report(found is not None, "rejects a '—' cell for '%s', whose tests run here: %s"
           % (row["feature"], found))
    if failures:
        print("FAIL: %d check(s) failed" % failures)
        return 1
    print("PASS: the coverage matrix is what %s runs" % config)
    return 0


if __name__ == "__main__":
    sys.exit(main())
