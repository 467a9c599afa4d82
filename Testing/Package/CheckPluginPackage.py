# pvpython script of scripts/test-package.sh: the ParaView plugin as the Debian package installs it.
#
#   pvpython --force-offscreen-rendering CheckPluginPackage.py build PLUGIN OUTDIR
#       in the build's own environment: loads the build tree's PLUGIN and renders the plugin's
#       synthetic cosmology (PluginTestKit.show_density_volume, 128x128) to OUTDIR/build.png, and
#       the same with the camera turned by 2 degrees to OUTDIR/build-turned.png
#   pvpython --force-offscreen-rendering CheckPluginPackage.py installed OUTDIR
#       in the clean root after `apt-get install ./singlepassamr-paraview-plugin_*.deb`, started
#       from a login shell (the package's /etc/profile.d file names its .plugins file): no
#       LoadPlugin; the representation and the source must already be there. Renders the same
#       view to OUTDIR/installed.png, which must match build.png (covered RMSE at most
#       MATCH_BOUND) while build-turned.png must not (the comparison's own control)
#   pvpython CheckPluginPackage.py probe
#       prints whether the plugin's proxies exist (FOUND: ...) and nothing else
# Exit codes: 0 pass, 1 fail.
import os
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
import PluginTestKit as kit  # noqa: E402

MATCH_BOUND = 1.0  # 0-255: the same binary, ParaView and Mesa draw the same pixels (measured 0.0)
SIZE = 128


def found_proxies():
    from paraview import servermanager
    from paraview.simple import GetSources  # noqa: F401 (initialises the session)

    pxm = servermanager.ProxyManager()
    return [g + "/" + n for g, n in (("representations", "SinglePassAMRVolumeRepresentation"),
                                     ("sources", "AMRCosmoSource"))
            if pxm.SMProxyManager.GetPrototypeProxy(g, n) is not None]


def render(path, azimuth=0.0):
    from paraview import simple

    source = simple.AMRCosmologysynthetic(NumberOfGrids=60, NumberOfLevels=3, NumberOfCells=200000,
                                          Seed=2)
    view, display, _ = kit.show_density_volume(source, SIZE)
    view.GetActiveCamera().Azimuth(azimuth)
    simple.Render(view)
    kit.check_window(view)
    display.SMProxy.UpdatePropertyInformation()
    kit.check_render_error(display.SMProxy.GetProperty("SinglePassRenderError").GetElement(0))
    simple.SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE])
    simple.Delete(display)
    simple.Delete(view)
    simple.Delete(source)


mode = sys.argv[1]
if mode == "probe":
    print("FOUND: " + ",".join(found_proxies()))
    kit.leave(0)
if mode == "build":
    plugin, out = sys.argv[2], sys.argv[3]
    from paraview.simple import LoadPlugin

    LoadPlugin(os.path.abspath(plugin), remote=False)  # into paraview.simple's namespace
    os.makedirs(out, exist_ok=True)
    render(os.path.join(out, "build.png"))
    render(os.path.join(out, "build-turned.png"), azimuth=2.0)
    print("rendered %s/build.png and build-turned.png with %s" % (out, plugin))
    kit.leave(0)
if mode != "installed":
    kit.fail("unknown mode %s (build, installed or probe)" % mode)
out = sys.argv[2]
found = found_proxies()
print("proxies at start, with no LoadPlugin: %s" % (", ".join(found) or "none"))
print("PV_PLUGIN_CONFIG_FILE=%s" % os.environ.get("PV_PLUGIN_CONFIG_FILE", "(unset)"))
if len(found) != 2:
    kit.fail("the installed plugin was not loaded at start")
installed = os.path.join(out, "installed.png")
render(installed)
_, _, image = kit.read_png(installed)
ok = True
for name, expect_match in (("build.png", True), ("build-turned.png", False)):
    if not os.path.exists(os.path.join(out, name)):
        kit.fail("no %s in %s (the build tree's render failed)" % (name, out))
    _, _, other = kit.read_png(os.path.join(out, name))
    if len(other) != len(image):
        kit.fail("%s has %d pixels, installed.png %d" % (name, len(other), len(image)))
    error = kit.rmse(image, other)
    good = (error <= MATCH_BOUND) == expect_match
    ok = ok and good
    print("%s: installed.png against %s: covered RMSE %.2f (%s %.1f); covered %.3f of the image" % (
        "ok" if good else "FAIL", name, error, "at most" if expect_match else "must exceed",
        MATCH_BOUND, kit.coverage(image)))
if kit.coverage(image) < 0.05:
    ok = False
    print("FAIL: the volume covers %.3f of the image" % kit.coverage(image))
print("PASS" if ok else "FAIL")
kit.leave(0 if ok else 1)
