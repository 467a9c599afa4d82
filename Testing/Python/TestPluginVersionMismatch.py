# What a user sees when the plugin meets a ParaView it was not built for.
#
#   python3 TestPluginVersionMismatch.py PVPYTHON PLUGIN OUTDIR
#
# ParaView 5.11's plugin loader (vtkPVPluginLoader) has no version check of its own: the guard
# is that every library of a ParaView build carries its major.minor version in its name
# (libvtkRemotingCore-pv5.11.so.1), so a plugin built for another ParaView names libraries the
# running one does not have, and dlopen refuses it. The test makes such a plugin: a copy of
# PLUGIN whose dependency libvtkRemotingCore-pv<this version>.so.1 is renamed to the one of
# ParaView 5.10 (patchelf --replace-needed; exactly what a build against 5.10 would record), then
# loads it with LoadPlugin in pvpython and checks that
#   - LoadPlugin raises (pvpython: RuntimeError "Problem loading plugin <path>"), and
#   - ParaView's error line names the plugin, the missing library with its version, and the
#     reason ("cannot open shared object file");
# and, as the control, that the unmodified plugin loads in the same way.
# Exit codes: 0 pass, 1 fail, 125 skipped (patchelf missing).
import os
import re
import shutil
import subprocess
import sys

SKIP = 125
LOADER = """
import sys
from paraview import simple
try:
    simple.LoadPlugin(sys.argv[1], remote=False, ns=globals())
    print("LOADED")
except Exception as e:
    print("RAISED: %s: %s" % (type(e).__name__, e))
"""


def load(pvpython, plugin, outdir):
    script = os.path.join(outdir, "load_plugin.py")
    with open(script, "w") as f:
        f.write(LOADER)
    # pvpython's own OpenMPI singleton variables must not leak into a child pvpython
    env = {k: v for k, v in os.environ.items() if not k.startswith(("OMPI_", "PMIX_"))}
    run = subprocess.run([pvpython, script, plugin], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, universal_newlines=True, env=env)
    return re.sub(r"\x1b\[[0-9;]*m", "", run.stdout)  # without loguru's colour codes


def main():
    if len(sys.argv) != 4:
        print("usage: TestPluginVersionMismatch.py PVPYTHON PLUGIN OUTDIR")
        return 2
    pvpython, plugin, outdir = sys.argv[1:]
    patchelf = shutil.which("patchelf")
    if not patchelf:
        why = "patchelf not found (scripts/install-deps.sh installs it)"
        if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
            print("FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: " + why)
            return 1
        print("SKIPPED: " + why)
        return SKIP
    os.makedirs(outdir, exist_ok=True)

    needed = subprocess.run(["readelf", "-d", plugin], stdout=subprocess.PIPE,
                            universal_newlines=True).stdout
    match = re.search(r"\[(libvtkRemotingCore-pv(\d+)\.(\d+)\.so\.\d+)\]", needed)
    if not match:
        print("FAIL: the plugin does not depend on a versioned libvtkRemotingCore:\n" + needed)
        return 1
    library, major, minor = match.group(1), match.group(2), match.group(3)
    other = "%s.%d" % (major, int(minor) - 1)
    other_library = library.replace("pv%s.%s" % (major, minor), "pv" + other)

    control = load(pvpython, plugin, outdir)
    print("unmodified plugin: %s" % control.strip().splitlines()[-1])
    if "LOADED" not in control:
        print(control)
        print("FAIL: the unmodified plugin does not load")
        return 1

    copy = os.path.join(outdir, os.path.basename(plugin))
    shutil.copyfile(plugin, copy)
    subprocess.check_call([patchelf, "--replace-needed", library, other_library, copy])
    output = load(pvpython, copy, outdir)
    print("plugin built for ParaView %s, loaded into ParaView %s.%s:" % (other, major, minor))
    errors = [l.strip() for l in output.splitlines() if "ERR|" in l or "RAISED" in l]
    print("\n".join("  " + e for e in errors))
    checks = [
        ("LoadPlugin raises", "RAISED: RuntimeError: Problem loading plugin" in output),
        ("the error names the plugin", copy in output),
        ("the error names the missing library and its version", other_library in output),
        ("the error gives the reason", "cannot open shared object file" in output),
    ]
    for what, ok in checks:
        print("%-55s %s" % (what, "ok" if ok else "FAILED"))
    if not all(ok for _, ok in checks):
        print(output)
        print("FAIL: the mismatch is not reported as described")
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
