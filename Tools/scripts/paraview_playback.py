# Measures playing a time series in pvpython with "AMR Single-Pass Volume": still frames of one
# step, a first loop over the steps (each step computed and built), a second loop from ParaView's
# animation cache (what *Cache Geometry For Animation* does while the scene plays), and the
# resident memory after each. Prints one JSON object.
#
#   pvpython --force-offscreen-rendering Tools/scripts/paraview_playback.py PLUGIN \
#       [--grids N] [--cells C] [--levels L] [--steps T] [--regrid K] [--size S] [--loops M]
#
# --loops M plays the cached steps M times back and forth (memory over many steps).
import argparse
import json
import os
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvpython_exit import exit_keeping_output  # noqa: E402

from paraview import simple  # noqa: E402


def resident_bytes():
    with open("/proc/self/statm") as f:
        return int(f.read().split()[1]) * os.sysconf("SC_PAGE_SIZE")


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("plugin")
    parser.add_argument("--grids", type=int, default=18528)
    parser.add_argument("--cells", type=int, default=33000000)
    parser.add_argument("--levels", type=int, default=4)
    parser.add_argument("--steps", type=int, default=8)
    parser.add_argument("--regrid", type=int, default=4)
    parser.add_argument("--size", type=int, default=512)
    parser.add_argument("--loops", type=int, default=1)
    parser.add_argument("--kept-mib", type=float, default=0.0,
                        help="the representation's KeptStepsMiB (GPU memory for shown steps)")
    a = parser.parse_args()
    simple.LoadPlugin(a.plugin, remote=False, ns=globals())
    source = AMRCosmologysynthetic(NumberOfGrids=a.grids, NumberOfLevels=a.levels,  # noqa: F821
                                   NumberOfCells=a.cells, Seed=1, NumberOfTimeSteps=a.steps,
                                   RegridEvery=a.regrid)
    source.UpdatePipelineInformation()
    times = list(source.TimestepValues)
    view = simple.CreateView("RenderView")
    view.ViewSize = [a.size, a.size]
    view.OrientationAxesVisibility = 0
    display = simple.Show(source, view)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))
    display.KeptStepsMiB = a.kept_mib
    view.ViewTime = times[0]
    simple.Render(view)
    view.ResetCamera()
    for _ in range(2):
        view.StillRender()
    start = time.perf_counter()
    for _ in range(3):
        view.StillRender()
    still = (time.perf_counter() - start) / 3
    rss_one = resident_bytes()

    def seconds_per_step(order):
        start = time.perf_counter()
        for t in order:
            view.ViewTime = t
            view.CacheKey = t
            simple.Render(view)
        return (time.perf_counter() - start) / len(order)

    view.UseCache = 1
    first_loop = seconds_per_step(times)
    rss_filled = resident_bytes()
    order = (times + list(reversed(times))) * a.loops
    cached_loop = seconds_per_step(order)
    rss_after = resident_bytes()
    view.UseCache = 0
    display.SMProxy.UpdatePropertyInformation()
    print(json.dumps({
        "series": "grids=%d,levels=%d,cells=%d,steps=%d,regrid=%d" % (
            a.grids, a.levels, a.cells, a.steps, a.regrid),
        "size": a.size,
        "still_frame_s": round(still, 4),
        "first_loop_s_per_step": round(first_loop, 4),
        "cached_loop_s_per_step": round(cached_loop, 4),
        "cached_loop_vs_still": round(still / cached_loop, 3),
        "cached_steps_played": len(order),
        "rss_one_step_bytes": rss_one,
        "rss_cache_filled_bytes": rss_filled,
        "rss_after_playing_bytes": rss_after,
        "texture_builds": display.SMProxy.GetProperty("SinglePassTextureBuilds").GetElement(0),
        "value_refreshes": display.SMProxy.GetProperty("SinglePassValueRefreshes").GetElement(0),
        "kept_mib": a.kept_mib,
        "kept_step_hits": display.SMProxy.GetProperty("SinglePassKeptStepHits").GetElement(0),
    }, indent=1))
    exit_keeping_output(0)


if __name__ == "__main__":
    main()
