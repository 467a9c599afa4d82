# The tool's progress bar (Tools/amrsp/AmrspProgress.h): drawn on stderr for the mapper's build and
# upload when stderr is a terminal, never into a pipe, never with --quiet.
# usage: python3 TestProgressBar.py AMRSP
import os
import pty
import subprocess
import sys

amrsp = sys.argv[1]
command = [amrsp, "render", "synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3", "--method",
           "packing", "--size", "32x32", "-o", os.devnull]
# draw at once instead of after a second: this dataset builds in milliseconds
env = dict(os.environ, AMRSP_PROGRESS_AFTER="0")


def spawn(extra):
    out = bytearray()

    def read(fd):
        data = os.read(fd, 4096)
        out.extend(data)
        return data

    saved = dict(os.environ)
    os.environ.update(env)
    try:
        status = pty.spawn(command + extra, read)
    finally:
        os.environ.clear()
        os.environ.update(saved)
    return os.waitstatus_to_exitcode(status), out.decode(errors="replace")


code, shown = spawn([])
if "no OpenGL context" in shown or code != 0:
    message = "amrsp render --method packing cannot render here: " + shown.strip()[-300:]
    if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
        print("FAIL: required here (AMRSP_REQUIRE_GPU=1): " + message)
        sys.exit(1)
    print("SKIPPED: " + message)
    sys.exit(125)
failures = 0


def check(ok, what):
    global failures
    print(("ok      " if ok else "FAILED  ") + what)
    failures += 0 if ok else 1


check("amrsp: build: " in shown and "100%" in shown and "amrsp: upload: " in shown,
      "on a terminal the build and the upload draw their bars: %r" % shown[-400:])
piped = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
check(piped.returncode == 0 and "[#" not in piped.stderr and "%" not in piped.stderr,
      "into a pipe nothing is drawn: %r" % piped.stderr[-200:])
code, quiet = spawn(["--quiet"])
check(code == 0 and "[#" not in quiet, "--quiet draws nothing on a terminal: %r" % quiet[-200:])
print("PASSED" if failures == 0 else "FAILED: %d check(s)" % failures)
sys.exit(0 if failures == 0 else 1)
