# The tool's progress bar (Tools/amrsp/AmrspProgress.h): drawn on stderr for the synthetic
# generation, the reading of a file, the mapper's build and upload, the CPU reference and the
# bench rounds when stderr is a terminal, never into a pipe, never with --quiet.
# usage: python3 TestProgressBar.py AMRSP ENZO_HIERARCHY
import os
import pty
import subprocess
import sys

amrsp = sys.argv[1]
enzo = sys.argv[2]
command = [amrsp, "render", "synthetic:cosmo:grids=60,levels=3,cells=200k,seed=3", "--method",
           "packing", "--size", "32x32", "-o", os.devnull]
# draw at once instead of after a second: this dataset builds in milliseconds
env = dict(os.environ, AMRSP_PROGRESS_AFTER="0")


def spawn(extra, base=None):
    out = bytearray()

    def read(fd):
        data = os.read(fd, 4096)
        out.extend(data)
        return data

    saved = dict(os.environ)
    os.environ.update(env)
    try:
        status = pty.spawn((base or command) + extra, read)
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
check("amrsp: generation: synthetic:cosmo" in shown,
      "and the synthetic generation draws its bar: %r" % shown[:300])
code, reference = spawn([], [amrsp, "reference", "synthetic:cosmo:grids=20,levels=2,cells=50k",
                             "--size", "24x24", "-o", os.devnull])
check(code == 0 and "amrsp: reference: " in reference and "100%" in reference,
      "the CPU reference draws its bar: %r" % reference[-300:])
if os.path.exists(enzo):
    code, reading = spawn([], [amrsp, "inspect", enzo])
    check(code == 0 and "amrsp: reading: " in reading and "100%" in reading,
          "reading a file draws its bar: %r" % reading[:300])
else:
    check(False, "the Enzo hierarchy %s is missing" % enzo)
code, rounds = spawn([], [amrsp, "bench", "synthetic:cosmo:grids=20,levels=2,cells=50k", "--size",
                          "16x16", "--frames", "1", "--methods", "packing", "--rounds", "3"])
check(code == 0 and "amrsp: bench rounds: " in rounds and "100%" in rounds,
      "the bench rounds draw their bar: %r" % rounds[-300:])
piped = subprocess.run(command, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE, text=True)
check(piped.returncode == 0 and "[#" not in piped.stderr and "%" not in piped.stderr,
      "into a pipe nothing is drawn: %r" % piped.stderr[-200:])
code, quiet = spawn(["--quiet"])
check(code == 0 and "[#" not in quiet, "--quiet draws nothing on a terminal: %r" % quiet[-200:])
print("PASSED" if failures == 0 else "FAILED: %d check(s)" % failures)
sys.exit(0 if failures == 0 else 1)
