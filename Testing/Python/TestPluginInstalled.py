# The plugin as ParaView users get it: `cmake --install` of this build into a fresh prefix, then
# pvpython and pvbatch started with only the documented environment (docs/paraview.md,
# "Installing the plugin") and no LoadPlugin: PV_PLUGIN_PATH=the installed plugin's folder, and
# PV_PLUGIN_CONFIG_FILE=the installed SinglePassAMR.plugins.xml (auto_load="1"). Each run must
# find the representation and the source proxies; the same run without either variable must not
# (the check's own control), so a passing run proves the variable loaded the plugin.
#
# Arguments: CMAKE BUILD_DIR WORK_DIR PVPYTHON PVBATCH
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import PluginTestKit as kit  # noqa: E402

cmake, build, work, pvpython, pvbatch = sys.argv[1:6]
prefix = os.path.join(work, "prefix")
shutil.rmtree(work, ignore_errors=True)
os.makedirs(work)
install = subprocess.run([cmake, "--install", build, "--prefix", prefix],
                         capture_output=True, text=True)
if install.returncode != 0:
    kit.fail("cmake --install %s failed:\n%s%s" % (build, install.stdout, install.stderr))

plugin = [os.path.join(d, f) for d, _, files in os.walk(prefix) for f in files
          if f == "SinglePassAMRPlugin.so"]
if len(plugin) != 1:
    kit.fail("expected one installed SinglePassAMRPlugin.so under %s, found %s" % (prefix, plugin))
plugin_dir = os.path.dirname(plugin[0])
plugins_dir = os.path.dirname(plugin_dir)
relative = os.path.relpath(plugins_dir, prefix)
if not (relative.startswith("lib") and os.path.basename(os.path.dirname(plugins_dir)).startswith("paraview-")
        and os.path.basename(plugins_dir) == "plugins"):
    kit.fail("the plugin is installed in %s, not in LIBDIR/paraview-X.Y/plugins" % relative)
xml = os.path.join(plugins_dir, "SinglePassAMR.plugins.xml")
if not os.path.exists(xml):
    kit.fail("no %s installed" % xml)
with open(xml) as f:
    text = f.read()
import xml.etree.ElementTree as ElementTree  # noqa: E402
try:  # ParaView's own parser (expat) drops a file that is not well-formed, autoload and all
    entries = [e.attrib for e in ElementTree.fromstring(text).iter("Plugin")]
except ElementTree.ParseError as error:
    kit.fail("%s is not well-formed XML (%s):\n%s" % (xml, error, text))
if not any(e.get("name") == "SinglePassAMRPlugin" and e.get("auto_load") == "1" for e in entries):
    kit.fail("%s does not mark the plugin for autoloading:\n%s" % (xml, text))
print("installed: %s, %s" % (os.path.relpath(plugin[0], prefix), os.path.relpath(xml, prefix)))

# what the child prints: whether the proxies exist, never loading anything itself
probe = os.path.join(work, "probe.py")
with open(probe, "w") as f:
    f.write(
        "from paraview import servermanager\n"
        "from paraview.simple import *\n"
        "pxm = servermanager.ProxyManager()\n"
        "found = [g + '/' + n for g, n in (('representations', 'SinglePassAMRVolumeRepresentation'),\n"
        "         ('sources', 'AMRCosmoSource'))\n"
        "         if pxm.SMProxyManager.GetPrototypeProxy(g, n) is not None]\n"
        "print('FOUND: ' + ','.join(found))\n")

base = {k: v for k, v in kit.clean_environment().items()
        if k not in ("PV_PLUGIN_PATH", "PV_PLUGIN_CONFIG_FILE")}
both = "representations/SinglePassAMRVolumeRepresentation,sources/AMRCosmoSource"
runs = [("no variable (control)", {}, ""),
        ("PV_PLUGIN_PATH", {"PV_PLUGIN_PATH": plugin_dir}, both),
        ("PV_PLUGIN_CONFIG_FILE", {"PV_PLUGIN_CONFIG_FILE": xml}, both)]
ok = True
for exe, options in ((pvpython, ["--force-offscreen-rendering"]),
                     (pvbatch, kit.MPI_PVBATCH_OPTIONS + ["--force-offscreen-rendering"])):
    for what, extra, expected in runs:
        env = dict(base, **extra)
        try:
            run = subprocess.run([exe] + options + [probe], capture_output=True, text=True,
                                 env=env, timeout=120)
        except subprocess.TimeoutExpired:
            kit.fail("%s with %s did not finish in 120 s" % (os.path.basename(exe), what))
        lines = [l for l in run.stdout.splitlines() if l.startswith("FOUND:")]
        found = lines[-1][len("FOUND:"):].strip() if lines else None
        good = run.returncode == 0 and found == expected
        ok = ok and good
        print("%s: %s with %s: %s (expected %s)" % (
            "ok" if good else "FAIL", os.path.basename(exe), what,
            "found " + (found or "nothing") if found is not None else
            "exit %d, no FOUND line" % run.returncode, expected or "nothing"))
        if not good:
            print(run.stdout[-2000:] + run.stderr[-2000:])
print("PASS" if ok else "FAIL")
sys.exit(0 if ok else 1)
