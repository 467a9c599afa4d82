#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""One verdict rule for the tests that print their checks (pvpython scripts, cmake -P scripts):
run COMMAND, echo its output, and exit

  1    when it printed a line with "FAIL:" or exited with anything but 0 or 125, or when
       --pass REGEX is given and nothing it printed matches it (a failure wins over a skip);
  125  (CTest's SKIP_RETURN_CODE) when it exited 125, or exited 0 having printed "SKIPPED:";
  0    otherwise.

CTest's own PASS_REGULAR_EXPRESSION ignores the exit code, and its SKIP_REGULAR_EXPRESSION wins
over a "FAIL:" line and a failing exit code; tests run through this wrapper set only
SKIP_RETURN_CODE 125.

usage: TestVerdict.py [--pass REGEX] -- COMMAND [ARGS...]
"""
import re
import subprocess
import sys


def verdict(returncode, output, pass_pattern):
    failed = re.search(r"FAIL:", output) is not None or returncode not in (0, 125)
    skipped = returncode == 125 or "SKIPPED:" in output
    # a run that skipped prints no pass line; any other run must
    if (pass_pattern is not None and not skipped and
            re.search(pass_pattern, output, re.MULTILINE) is None):
        print("TestVerdict: FAILED: nothing printed matches %r" % pass_pattern)
        failed = True
    if failed:
        if returncode == 0 or returncode == 125:
            print("TestVerdict: FAILED (a FAIL: line, although the exit code was %d)" % returncode)
        return 1
    if skipped:
        return 125
    return 0


def main(argv):
    pass_pattern = None
    if argv[:1] == ["--pass"]:
        pass_pattern = argv[1]
        argv = argv[2:]
    if argv[:1] != ["--"] or len(argv) < 2:
        sys.exit(__doc__)
    run = subprocess.run(argv[1:], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True, errors="replace")
    sys.stdout.write(run.stdout)
    sys.stdout.flush()
    return verdict(run.returncode, run.stdout, pass_pattern)


if __name__ == "__main__":
    sys.exit(main(sys.argv[1:]))
