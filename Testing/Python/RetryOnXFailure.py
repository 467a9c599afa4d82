#!/usr/bin/env python3
# Runs a test command and runs it again (at most ATTEMPTS times in all) when it failed because the
# X server refused a connection ("bad X server connection", which makes VTK's GLX windows abort
# the process). That happens now and then on a busy shared Xvfb; it is not a result of the code
# under test, and every retry is announced in the output. Any other failure is reported as is.
#
#   python3 RetryOnXFailure.py ATTEMPTS COMMAND [ARGS...]
import subprocess
import sys

MARKERS = ("bad X server connection", "cannot open display", "Can't open display")
# CTest's verdict patterns (Testing/CMakeLists.txt). A retried attempt's output is kept for the
# record, but with these defused: its FAIL: would otherwise fail a test whose retry passes.
VERDICTS = ("FAIL:", "SKIPPED:")


def defused(output):
    for verdict in VERDICTS:
        output = output.replace(verdict, verdict[:-1] + " (attempt void, X server refused)")
    return output


def main():
    attempts = int(sys.argv[1])
    command = sys.argv[2:]
    for attempt in range(1, attempts + 1):
        run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, errors="replace")
        x_failure = run.returncode != 0 and any(m in run.stdout for m in MARKERS)
        if not x_failure or attempt == attempts:
            sys.stdout.write(run.stdout)
            sys.stdout.flush()
            return run.returncode
        sys.stdout.write(defused(run.stdout))
        print("\nRetryOnXFailure: the X server refused a connection (attempt %d of %d); "
              "running the test again\n" % (attempt, attempts))
        sys.stdout.flush()
    return 1


if __name__ == "__main__":
    sys.exit(main())
