# pvpython test: playing a time series with the representation, with and without ParaView's
# animation cache.
#
#   pvpython --force-offscreen-rendering TestPluginPlayback.py PLUGIN OUTDIR
#
# The plugin's synthetic source as a series (NumberOfTimeSteps 6, RegridEvery 3: the grids change
# at steps 3, the values at every step). Checked:
# - played forwards without the cache, every step of the same structure as the one before only
#   refreshes the mapper's values (SinglePassTextureBuilds counts a build per step; the mapper's
#   value refreshes are the steps without a regrid), and the images differ from step to step;
# - with the view's animation cache on (what *Cache Geometry For Animation* does while the scene
#   plays: UseCache, CacheKey = the time), a first loop fills the cache, a second loop forwards
#   and one backwards show every step from the cache: each image equals, byte for byte, that
#   step's image without the cache. (ParaView skips the representation's update for a cached
#   step: showing the last step updated instead is what this rejects.) With GPU memory for the
#   steps shown (KeptStepsMiB), every step from the cache comes from its kept textures, no build;
# - a playback loop from the cache runs at a speed compared with still frames of one step (the
#   ratio is printed; timing is measured, not asserted).
# Exit codes: 0 pass, 1 fail, 125 skipped (no X display or no usable OpenGL context).
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import check_render_error, fail  # noqa: E402

STEPS = 6
SIZE = 96


def main():
    plugin, outdir = sys.argv[1:3]
    from PluginTestKit import info_property, read_png, require_display

    require_display()
    os.makedirs(outdir, exist_ok=True)
    from paraview import simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    source = AMRCosmologysynthetic(NumberOfGrids=120, NumberOfLevels=3,  # noqa: F821
                                   NumberOfCells=80000, Seed=2, NumberOfTimeSteps=STEPS,
                                   RegridEvery=3)
    source.UpdatePipelineInformation()
    times = list(source.TimestepValues)
    if times != [float(s) for s in range(STEPS)]:
        fail("the source's time steps are %s, expected 0 to %d" % (times, STEPS - 1))
    view = simple.CreateView("RenderView")
    view.ViewSize = [SIZE, SIZE]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    display = simple.Show(source, view)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))
    lut = simple.GetColorTransferFunction("Density")
    lut.AutomaticRescaleRangeMode = "Never"
    lut.UseLogScale = 1
    lut.RGBPoints = [0.5, 0.2, 0.4, 1.0, 50.0, 1.0, 1.0, 1.0, 5000.0, 1.0, 0.2, 0.1]
    pwf = simple.GetOpacityTransferFunction("Density")
    pwf.UseLogScale = 1
    pwf.Points = [0.5, 0.0, 0.5, 0.0, 50.0, 0.3, 0.5, 0.0, 5000.0, 0.9, 0.5, 0.0]
    view.ViewTime = times[0]
    simple.Render(view)
    view.ResetCamera()
    view.GetActiveCamera().Azimuth(30.0)
    view.GetActiveCamera().Elevation(20.0)

    def shot(name):
        path = os.path.join(outdir, "%s.png" % name)
        simple.SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE], TransparentBackground=0)
        check_render_error(info_property(display, "SinglePassRenderError"), name)
        return read_png(path)[2]

    # 1. forwards without the cache
    plain = []
    for t in times:
        view.ViewTime = t
        plain.append(shot("plain-%d" % int(t)))
    builds = info_property(display, "SinglePassTextureBuilds")
    refreshes = info_property(display, "SinglePassValueRefreshes")
    print("without the cache: %d texture builds, %d of them value refreshes" % (builds, refreshes))
    failures = []

    def check(ok, message):
        print("%s %s" % ("ok     " if ok else "FAILED ", message))
        if not ok:
            failures.append(message)

    check(builds == STEPS and refreshes == STEPS - 2,
          "one build per step, the %d steps without a regrid (1, 2, 4, 5) refreshing the values "
          "only: %d builds, %d refreshes" % (STEPS - 2, builds, refreshes))
    changes = [float(abs(plain[k] - plain[k - 1]).max()) for k in range(1, STEPS)]
    check(min(changes) > 8, "every step's image differs from the step before (largest channel "
          "differences %s)" % changes)

    # 2. with the animation cache and GPU memory for the steps shown: a loop to fill both, then
    # forwards and backwards from them
    display.KeptStepsMiB = 256
    view.UseCache = 1
    for t in times:
        view.ViewTime = t
        view.CacheKey = t
        simple.Render(view)
    builds_filled = info_property(display, "SinglePassTextureBuilds")
    hits_filled = info_property(display, "SinglePassKeptStepHits")
    for name, order in (("forwards", times), ("backwards", list(reversed(times)))):
        for t in order:
            view.ViewTime = t
            view.CacheKey = t
            cached = shot("cached-%s-%d" % (name, int(t)))
            differing = int((abs(cached - plain[int(t)]).max(axis=1) > 0).sum())
            check(differing == 0, "%s from the cache, step %d equals its image without the cache "
                  "(%d pixels differ)" % (name, int(t), differing))
    # a broken cache shows the last step updated: that image is not the others' (seen above)
    builds = info_property(display, "SinglePassTextureBuilds") - builds_filled
    hits = info_property(display, "SinglePassKeptStepHits") - hits_filled
    check(builds > 0 and hits == builds,
          "every step from the cache came from the textures kept on the GPU: %d step changes, "
          "%d from kept textures" % (builds, hits))

    # 3. the speed of a loop from the cache against still frames of one step
    start = time.perf_counter()
    for t in times:
        view.ViewTime = t
        view.CacheKey = t
        simple.Render(view)
    loop = (time.perf_counter() - start) / STEPS
    start = time.perf_counter()
    for _ in times:
        view.StillRender()
    still = (time.perf_counter() - start) / STEPS
    print("playback from the cache: %.4f s per frame, still frames %.4f s: %.2fx the still speed; "
          "%d texture builds after filling the cache, %d now"
          % (loop, still, still / loop, builds_filled,
             info_property(display, "SinglePassTextureBuilds")))
    view.UseCache = 0
    if failures:
        fail("%d check(s) failed, the first: %s" % (len(failures), failures[0]))
    print("PASS")


if __name__ == "__main__":
    main()
