#!/usr/bin/env python3
# Runs a test command and runs it once more when it failed because the X server refused a
# connection: VTK's GLX window then prints "bad X server connection. DISPLAY=... Aborting." and
# aborts the process. An X server that resets when its last client leaves (Xvfb without
# -noreset, see scripts/start-xvfb.sh) drops connections that way; it is not a result of the code
# under test. Only that line counts (not any mention of X in a log the test repeats), only a
# failed run is repeated, at most once, and the repetition is said in the output. Any other
# failure is reported as is.
#
#   python3 RetryOnXFailure.py ATTEMPTS COMMAND [ARGS...]     (ATTEMPTS: 2 = one repetition)
import re
import subprocess
import sys

# vtkXOpenGLRenderWindow's abort, the one cause of a repetition
X_ABORT = re.compile(r"bad X server connection\. DISPLAY=\S*\. Aborting\.")
# CTest's verdict patterns (Testing/CMakeLists.txt). A retried attempt's output is kept for the
# record, but with these defused: its FAIL: would otherwise fail a test whose retry passes.
VERDICTS = ("FAIL:", "SKIPPED:")


def defused(output):
    for verdict in VERDICTS:
        output = output.replace(verdict, verdict[:-1] + " (attempt void, X server refused)")
    return output


def main():
    attempts = min(int(sys.argv[1]), 2)  # at most one repetition
    command = sys.argv[2:]
    for attempt in range(1, attempts + 1):
        run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, errors="replace")
        x_failure = run.returncode != 0 and X_ABORT.search(run.stdout) is not None
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
