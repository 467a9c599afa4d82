#!/usr/bin/env python3
# Plugin.RetryOnXFailure: the retry wrapper repeats a run once when VTK's X abort ended it (and the
# void attempt's FAIL: does not count), and never repeats any other failure.
#
#   python3 TestRetryOnXFailure.py WRAPPER FLAKY STATE_FOLDER
import subprocess
import sys

wrapper, flaky, state = sys.argv[1:4]


def run(*extra):
    result = subprocess.run([sys.executable, wrapper, "3", sys.executable, flaky, state] + list(extra),
                            stdout=subprocess.PIPE, stderr=subprocess.STDOUT, universal_newlines=True)
    return result.returncode, result.stdout


failures = 0
code, out = run()
print("--- X abort, then a pass:\n" + out)
if code != 0 or "attempt 1 of 2" not in out or "\nPASS" not in out or "FAIL:" in out:
    print("FAIL: the X abort was not repeated exactly once with the void attempt defused")
    failures += 1
code, out = run("other")
print("--- another failure:\n" + out)
if code == 0 or "RetryOnXFailure:" in out or "FAIL: the image differs" not in out:
    print("FAIL: a failure without VTK's X abort line was repeated or hidden")
    failures += 1
print("retry wrapper: all checks passed" if failures == 0 else "%d check(s) failed" % failures)
sys.exit(1 if failures else 0)
