#!/usr/bin/env python3
# Stand-in for a test whose first run meets a refusing X server (for Plugin.RetryOnXFailure):
# the first call prints a FAIL: line with VTK's X message and exits 1, later calls print PASS.
#
#   python3 FlakyXCommand.py STATE_FOLDER [other]
# With "other" the first call fails for another reason (no X abort line), which must not be
# repeated.
# The state file is named after the calling wrapper's process, so a file left by an earlier run
# cannot turn a first call into a second one.
import os
import sys

state = os.path.join(sys.argv[1], "flaky-x-command-%d.state" % os.getppid())
if not os.path.exists(state):
    open(state, "w").close()
    if sys.argv[2:] == ["other"]:
        print("a log line that mentions the bad X server connection in passing")
        print("FAIL: the image differs from the reference")
    else:
        print("vtkXOpenGLRenderWindow: bad X server connection. DISPLAY=:99. Aborting.")
        print("FAIL: uncaught RuntimeError: Could not create a representation object")
    sys.exit(1)
os.remove(state)
print("\nPASS")
