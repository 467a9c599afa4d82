#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The verdict rule (TestVerdict.py) on commands whose output and exit code are known: a FAIL:
line or a failing exit code fails even beside SKIPPED: or PASS; a missing pass line fails a run
that did not skip; SKIPPED: alone skips (125); exit 125 skips.

usage: TestTestVerdict.py TestVerdict.py
"""
import subprocess
import sys

wrapper = sys.argv[1]
cases = [  # (printed, exit code, pass pattern, expected verdict)
    ("PASS", 0, r"\bPASS", 0),
    ("PASS", 1, r"\bPASS", 1),                 # CTest's PASS_REGULAR_EXPRESSION passes this
    ("SKIPPED: no X\nFAIL: broken", 1, None, 1),  # CTest's SKIP_REGULAR_EXPRESSION skips this
    ("SKIPPED: no X\nFAIL: broken", 125, None, 1),
    ("SKIPPED: no X", 0, None, 125),
    ("SKIPPED: no X", 125, None, 125),
    ("", 125, None, 125),
    ("SKIPPED: no X", 125, "^PASS", 125),      # a skip needs no pass line
    ("SKIPPED: no X\nFAIL: broken", 125, "^PASS", 1),
    ("ran", 0, "^PASS", 1),                    # a run that did not skip prints its pass line
    ("all good", 0, r"\bPASS", 1),
    ("FAIL: one check\nPASS", 0, r"\bPASS", 1),
    ("ok", 0, None, 0),
    ("ok", 2, None, 1),
]
failures = 0
for printed, code, pattern, expected in cases:
    script = "import sys; print(%r); sys.exit(%d)" % (printed, code)
    args = [sys.executable, wrapper] + (["--pass", pattern] if pattern else []) + \
        ["--", sys.executable, "-c", script]
    got = subprocess.run(args, stdout=subprocess.DEVNULL).returncode
    ok = got == expected
    failures += 0 if ok else 1
    print("%s: %r exit %d -> %d (expected %d)" % ("ok" if ok else "FAIL", printed, code, got,
                                                 expected))
sys.exit(1 if failures else 0)
