# pvpython test of the representation on a time series:
#
#   pvpython --force-offscreen-rendering TestPluginTimeSeries.py PLUGIN AMRSP OUTDIR
#
# Writes three time steps of the plugin's synthetic AMR source (seeds 3, 4, 5: different grids and
# densities) as VTK XML AMR files (.vthb) into OUTDIR, opens them as one file series (ParaView
# gives it the time steps 0, 1, 2) and shows it with "AMR Single-Pass Volume". Checks:
# - every change of time step rebuilds the mapper's textures exactly once (the new step's data),
#   and the image changes;
# - re-rendering, camera and colour-map changes at one time step never rebuild them;
# - going back to the first step rebuilds once more (ParaView does not cache the old step) and
#   renders the first image again (RMSE below 0.8, under 0.1 % of the pixels off by more than 2);
# - the image of every time step matches the CPU reference (`amrsp reference --view-json`) of
#   that step's file, and not that of another step: showing the wrong step fails.
# Exit codes: 0 pass, 1 fail, 125 skipped (no X display or no usable OpenGL context).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import (check_render_error, fail, leave, show_density_volume, skip,  # noqa: E402
                           write_view_json)


# Each step's image against the CPU reference of its file, over the pixels the volume covers
# (about half of the 120x120 frame; measured 2.81 to 3.16 on llvmpipe: the reference samples four
# times per finest cell, the mapper twice per cell of each level), and the least an image must
# differ from the reference of a wrong step (measured 60 to 77).
REFERENCE_RMSE_BOUND = 4.5
WRONG_STEP_RMSE = 20.0


def main():
    plugin, amrsp, outdir = sys.argv[1:4]
    from PluginTestKit import coverage, info_property, read_png, require_display, rmse, run_amrsp

    require_display()
    os.makedirs(outdir, exist_ok=True)
    from paraview import simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())

    # the time steps, written by ParaView's XML AMR writer
    files = []
    for step, seed in enumerate([3, 4, 5]):
        source = AMRCosmologysynthetic(NumberOfGrids=120, NumberOfLevels=3, NumberOfCells=60000,
                                       Seed=seed)
        path = os.path.join(outdir, "timeseries_%d.vthb" % step)
        simple.SaveData(path, proxy=source)
        simple.Delete(source)
        files.append(path)
    reader = simple.OpenDataFile(files)
    # ParaView's XML AMR reader reads only level 0 unless told otherwise (0: all levels)
    reader.DefaultNumberOfLevels = 0
    times = list(reader.TimestepValues)
    print("time series: %d files, time steps %s" % (len(files), times))
    if len(times) != 3:
        fail("the file series has %d time steps, expected 3" % len(times))

    def first_step(view):
        scene = simple.GetAnimationScene()
        scene.UpdateAnimationUsingDataTimeSteps()
        scene.AnimationTime = times[0]

    # colours and opacity follow the density's quantiles at step 0
    view, display, q = show_density_volume(reader, 120, first_step)
    scene = simple.GetAnimationScene()
    lut = simple.GetColorTransferFunction("Density")
    lut.ColorSpace = "RGB"  # the reference interpolates colours in RGB
    # Maps on [q0, q3] (q3: the 99 % quantile; denser cells clamp to the last point): the mapper's
    # 4096-entry table resolves them (the default maps reach the maximum, 1500 times the median,
    # and put three points into the table's first two entries: RMSE 10.5 against the exact
    # reference for that reason alone)
    lut.RGBPoints = [q[0], 0.2, 0.4, 1.0, q[2], 1.0, 1.0, 1.0, q[3], 1.0, 0.2, 0.1]
    simple.GetOpacityTransferFunction("Density").Points = [
        q[0], 0.0, 0.5, 0.0, q[1], 0.1, 0.5, 0.0, q[2], 0.5, 0.5, 0.0, q[3], 0.8, 0.5, 0.0]
    colours = list(lut.RGBPoints)
    # two samples per cell, as the representation test (the reference samples at least as finely)
    display.SampleDistanceFactor = 0.5
    references = {}  # time step -> (view json, CPU reference pixels of that step's file)

    def reference(step, name):
        """The CPU reference of `step`'s file in the current view."""
        json_path = os.path.join(outdir, "timeseries-%s-view.json" % name)
        write_view_json(view, display, "Density", json_path)
        image = os.path.join(outdir, "timeseries-%s-reference-of-step%d.png" % (name, step))
        run_amrsp([amrsp, "reference", files[step], "--array", "Density", "--size", "120x120",
                   "--view-json", json_path, "--reference-sample-factor", "0.25", "-o", image])
        return read_png(image)[2]

    def shot(name, expected_builds):
        path = os.path.join(outdir, "timeseries-%s.png" % name)
        simple.SaveScreenshot(path, view, ImageResolution=[120, 120], TransparentBackground=0)
        error = info_property(display, "SinglePassRenderError")
        check_render_error(error, "%s: the representation" % name)
        builds = info_property(display, "SinglePassTextureBuilds")
        pixels = read_png(path)[2]
        print("%-16s time %g, texture builds %d, volume on %5.1f %% of the pixels"
              % (name, view.ViewTime, builds, 100.0 * coverage(pixels)))
        if builds != expected_builds:
            fail("%s: %d texture builds, expected %d" % (name, builds, expected_builds))
        return pixels

    first = shot("step0", 1)
    if coverage(first) < 0.1:
        fail("the first image does not show the volume")
    shot("step0-again", 1)
    view.GetActiveCamera().Azimuth(20.0)
    first_turned = shot("step0-camera", 1)
    lut.RGBPoints = [q[0], 1.0, 0.9, 0.2, q[2], 1.0, 0.5, 0.0, q[4], 0.6, 0.0, 0.0]
    shot("step0-colours", 1)
    lut.RGBPoints = colours

    scene.AnimationTime = times[1]
    second = shot("step1", 2)
    shot("step1-again", 2)
    camera = view.GetActiveCamera()
    saved = (camera.GetPosition(), camera.GetFocalPoint(), camera.GetViewUp())
    camera.Azimuth(10.0)
    shot("step1-camera", 2)
    camera.SetPosition(saved[0])
    camera.SetFocalPoint(saved[1])
    camera.SetViewUp(saved[2])
    scene.AnimationTime = times[2]
    third = shot("step2", 3)
    scene.AnimationTime = times[0]
    back = shot("step0-back", 4)

    # every step against the CPU reference of its own file, and of the other steps' files (the
    # camera of step0-camera and step 1 is the same; steps 2 and 0-back share it too)
    reference_checks = []
    for name, step, pixels in (("step0-back", 0, back), ("step1", 1, second), ("step2", 2, third)):
        own = rmse(pixels, reference(step, name))
        others = [rmse(pixels, reference(other, name)) for other in range(3) if other != step]
        print("%-16s rmse (0-255) vs the CPU reference of its step %.2f (bound %.1f), of the "
              "other steps %s (must exceed %.1f)" % (name, own, REFERENCE_RMSE_BOUND,
                                                    ", ".join("%.2f" % o for o in others),
                                                    WRONG_STEP_RMSE))
        reference_checks.append(("%s matches its step's CPU reference" % name,
                                 own < REFERENCE_RMSE_BOUND))
        reference_checks.append(("%s differs from the other steps' references" % name,
                                 min(others) > WRONG_STEP_RMSE))

    checks = reference_checks + [
        ("step 1 differs from step 0", rmse(second, first_turned) > 3.0),
        ("step 2 differs from step 1", rmse(third, second) > 3.0),
        ("step 2 differs from step 0", rmse(third, first_turned) > 3.0),
        # the same data and camera; a few silhouette pixels differ (measured over the volume's
        # pixels: RMSE 0.43, 4 of 14400 pixels by up to 9 levels), as grazing rays do between
        # ParaView's render paths
        ("back at step 0: the same image", rmse(back, first_turned) < 0.8 and
         float((abs(back - first_turned).max(axis=1) > 2.0).mean()) < 0.001),
    ]
    print("rmse (0-255): step 1 vs 0 %.2f, step 2 vs 1 %.2f, step 2 vs 0 %.2f, step 0 again vs "
          "step 0 %.2f" % (rmse(second, first_turned), rmse(third, second),
                           rmse(third, first_turned), rmse(back, first_turned)))
    for what, ok in checks:
        print("%-40s %s" % (what, "ok" if ok else "FAILED"))
    if not all(ok for _, ok in checks):
        fail("a time-series rule does not hold")
    print("PASS")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print("usage: TestPluginTimeSeries.py PLUGIN AMRSP OUTDIR")
        leave(2)
    main()
