#!/usr/bin/env python3
# Testing.RequireMode: the skip rule of every kind of test. Run by hand, a test whose context,
# program or data is missing reports SKIPPED (CTest's skip code 125 or its skip pattern); with
# AMRSP_REQUIRE_GPU=1 (scripts/run-tests.sh sets it in CI) the same test FAILS naming what is
# missing. Checked for the Python plugin tests' skip(), the CMake stand-in for a missing program or
# data (MissingPrerequisite.cmake) and the tool tests' expect-output.sh. (The C++ tests'
# mappertest::SkipOrFail follows the same rule; CI's run-tests.sh also fails on any skip left.)
#
#   python3 TestRequireMode.py CMAKE SOURCE_DIR
import os
import subprocess
import sys

cmake, source = sys.argv[1:3]
testing = os.path.join(source, "Testing")
cases = {
    "python skip()": [sys.executable, "-c",
                      "import sys; sys.path.insert(0, %r); import PluginTestKit; "
                      "PluginTestKit.skip('no X display')" % os.path.join(testing, "Python")],
    "missing program (cmake -P)": [cmake, "-DWHAT=pvserver was not found", "-P",
                                   os.path.join(testing, "MissingPrerequisite.cmake")],
    "tool test (expect-output.sh)": ["sh", os.path.join(testing, "Tool", "expect-output.sh"), "x",
                                     "sh", "-c", "echo 'the packing method cannot render here: no "
                                     "OpenGL' >&2; exit 1"],
}
failures = 0
for name, command in cases.items():
    for require in ("", "1"):
        env = dict(os.environ)
        env.pop("AMRSP_REQUIRE_GPU", None)
        if require:
            env["AMRSP_REQUIRE_GPU"] = require
        run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, env=env)
        out = run.stdout.strip().replace("\n", " | ")
        if require:
            ok = run.returncode not in (0, 125) and "FAIL: required here (AMRSP_REQUIRE_GPU=1)" in run.stdout \
                and "SKIPPED:" not in run.stdout
        else:
            ok = "SKIPPED:" in run.stdout and "FAIL" not in run.stdout and run.returncode in (0, 125)
        print("%s %-30s AMRSP_REQUIRE_GPU=%-2s exit %d: %s" % ("ok    " if ok else "FAILED", name,
                                                               require or "-", run.returncode, out))
        failures += 0 if ok else 1
print("require mode: %s" % ("all checks passed" if failures == 0 else "%d checks failed" % failures))
sys.exit(1 if failures else 0)
