#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""docs/command-line.md documents every option `amrsp COMMAND --help` prints.

Usage: CheckCommandLineDocs.py AMRSP DOCS_COMMAND_LINE_MD

Reads the commands from `amrsp --help` (the lines under "commands:"), then every `--option`
token each command's `--help` prints, and requires each of them in the page as the same token
(`--plot-size`, not only `--plot`). The check then shows that it rejects the page with one
documented option taken out. Prints ok/FAIL lines, PASS at the end; exits 1 on any failure.
"""
import re
import subprocess
import sys

OPTION = re.compile(r"(?<![\w-])(--[a-z][a-z0-9-]*)")


def help_text(amrsp, *args):
    run = subprocess.run([amrsp, *args, "--help"], capture_output=True, text=True, timeout=60)
    return run.stdout + run.stderr


def commands(amrsp):
    """The command words of `amrsp --help`: indented lines after "commands:"."""
    words, inside = [], False
    for line in help_text(amrsp).splitlines():
        if line.strip() == "commands:":
            inside = True
        elif inside and re.match(r"^  [a-z]+ ", line):
            words.append(line.split()[0])
        elif inside:
            break
    return words


def undocumented(options, page):
    documented = set(OPTION.findall(page))
    return sorted(set(options) - documented)


def main():
    amrsp, doc = sys.argv[1], sys.argv[2]
    page = open(doc, encoding="utf-8").read()
    names = commands(amrsp)
    ok = len(names) >= 4
    print("%s: amrsp --help lists the commands %s" % ("ok" if ok else "FAIL", ", ".join(names)))
    everything = set()
    for name in names:
        options = set(OPTION.findall(help_text(amrsp, name))) - {"--help"}
        everything |= options
        missing = undocumented(options, page)
        good = bool(options) and not missing
        ok = ok and good
        print("%s: amrsp %s --help prints %d options%s" % ("ok" if good else "FAIL", name,
              len(options), "; missing from %s: %s" % (doc, ", ".join(missing)) if missing else ""))
    # the check itself: one documented option taken out of the page must be reported
    if everything:
        probe = sorted(everything)[len(everything) // 2]
        without = re.sub(r"(?<![\w-])" + re.escape(probe) + r"(?![\w-])", "", page)
        rejected = probe in undocumented(everything, without)
        ok = ok and rejected
        print("%s: the page without %s is rejected" % ("ok" if rejected else "FAIL", probe))
    print("PASS" if ok else "FAIL")
    return 0 if ok else 1


if __name__ == "__main__":
    sys.exit(main())
