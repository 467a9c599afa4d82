# pvpython --force-offscreen-rendering Tools/scripts/paraview_interactive.py PLUGIN
#     [GRIDS LEVELS CELLS] [SIZE] [FRAMES] [--save DIR]
# Interactive frames of the representation "AMR Single-Pass Volume" in a pvpython render view,
# driven as the GUI drives it while the mouse drags the camera: the camera turns by 3 degrees and
# the view renders with vtkSMViewProxy::InteractiveRender (vtkPVRenderView asks the render window
# for 5 frames a second), then with StillRender (0.002 frames a second) at the same camera. Each
# frame's seconds include reading the image back (which waits for the GPU). Per camera step it
# reports the interactive and the still frame's seconds, the mapper's image sample distance,
# sample-distance scale and allocated seconds, and the RMSE (0-255) between the interactive frame
# and its own still frame over the pixels either covers. Before the interactive frames and after
# them one still frame is taken at the first camera: bit_identical_still says whether they match.
# The colour map and opacity function of Density are log-scaled (ParaView's defaults over the
# data range, mapped to log space). Default: the paper's dataset-3 size (39061 grids, 13 levels, 140 M cells) at 512², 10 steps.
import json
import os
import sys
import time

import numpy
sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from pvpython_exit import exit_keeping_output  # noqa: E402

from paraview import simple
from vtkmodules.util.numpy_support import vtk_to_numpy
from vtkmodules.vtkRenderingCore import vtkWindowToImageFilter


def grab(view):
    """The view's last rendered image as an (h, w, 3) uint8 array (no new render)."""
    w2i = vtkWindowToImageFilter()
    w2i.SetInput(view.GetRenderWindow())
    w2i.SetShouldRerender(False)
    w2i.ReadFrontBufferOff()
    w2i.SetInputBufferTypeToRGB()
    w2i.Update()
    img = w2i.GetOutput()
    w, h, _ = img.GetDimensions()
    return vtk_to_numpy(img.GetPointData().GetScalars()).reshape(h, w, 3).copy()


def volume_rmse(a, b, background):
    covered = numpy.any(a != background, axis=2) | numpy.any(b != background, axis=2)
    if not covered.any():
        return 0.0
    d = a[covered].astype(float) - b[covered].astype(float)
    return float(numpy.sqrt(numpy.mean(d * d)))


def last_frame_quality(display):
    """The mapper's last frame: interactive, image sample distance, scale, allocated s, s."""
    display.SMProxy.UpdatePropertyInformation()
    prop = display.SMProxy.GetProperty("SinglePassLastFrameQuality")
    return [prop.GetElement(i) for i in range(5)]


def timed(render, view):
    t0 = time.perf_counter()
    render()
    image = grab(view)
    return time.perf_counter() - t0, image


def main():
    args = [a for a in sys.argv[1:]]
    save = None
    if "--save" in args:
        i = args.index("--save")
        save = args[i + 1]
        del args[i:i + 2]
    plugin = args[0]
    grids, levels, cells = (int(v) for v in (args[1:4] if len(args) >= 4
                                             else (39061, 13, 140000000)))
    size = int(args[4]) if len(args) >= 5 else 512
    frames = int(args[5]) if len(args) >= 6 else 10
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    source = AMRCosmologysynthetic(NumberOfGrids=grids, NumberOfLevels=levels,
                                   NumberOfCells=cells)
    view = simple.CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    display = simple.Show(source, view)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))
    simple.ResetCamera(view)
    # the densities span many decades: log-scaled colour map and opacity function, as a user
    # shows them
    lut = simple.GetColorTransferFunction("Density")
    lut.MapControlPointsToLogSpace()
    lut.UseLogScale = 1
    simple.GetOpacityTransferFunction("Density").UseLogScale = 1
    proxy = view.SMProxy
    background = numpy.zeros(3, dtype=numpy.uint8)

    t0 = time.perf_counter()
    simple.Render(view)  # build, upload, first frame
    first_image = time.perf_counter() - t0
    _, first_still = timed(proxy.StillRender, view)
    steps = []
    camera = view.GetActiveCamera()
    for k in range(frames):
        camera.Azimuth(3.0)
        t_int, interactive = timed(proxy.InteractiveRender, view)
        quality = last_frame_quality(display)
        step = {
            "interactive_s": round(t_int, 4),
            "interactive": bool(quality[0]),
            "image_sample_distance": quality[1],
            "sample_distance_scale": quality[2],
            "allocated_s": round(quality[3], 4),
            "mapper_s": round(quality[4], 4),
        }
        t_still, still = timed(proxy.StillRender, view)
        step["still_s"] = round(t_still, 4)
        step["rmse"] = round(volume_rmse(interactive, still, background), 3)
        steps.append(step)
        if save:
            from vtkmodules.vtkIOImage import vtkPNGWriter  # noqa: F401
            numpy.save(os.path.join(save, "interactive-%02d.npy" % k), interactive)
            numpy.save(os.path.join(save, "still-%02d.npy" % k), still)
    camera.Azimuth(-3.0 * frames)
    _, last_still = timed(proxy.StillRender, view)
    # the first interactive frame still learns the frame time; the rest show the steady state
    steady = steps[1:] if len(steps) > 1 else steps
    median = lambda xs: float(numpy.median(xs))  # noqa: E731
    still_s = median([s["still_s"] for s in steady])
    interactive_s = median([s["interactive_s"] for s in steady])
    print(json.dumps({
        "dataset": "AMR Cosmology (synthetic) grids=%d levels=%d cells=%d" % (grids, levels, cells),
        "image": [size, size],
        "time_to_first_image_s": round(first_image, 3),
        "still_frame_s": round(still_s, 4),
        "interactive_frame_s": round(interactive_s, 4),
        "speedup": round(still_s / interactive_s, 2),
        "rmse_median": round(median([s["rmse"] for s in steady]), 3),
        "rmse_max": round(max(s["rmse"] for s in steps), 3),
        "bit_identical_still": bool(numpy.array_equal(first_still, last_still)),
        "coverage": round(float(numpy.mean(numpy.any(first_still != background, axis=2))), 3),
        "steps": steps,
    }, indent=1))
    exit_keeping_output(0)


if __name__ == "__main__":
    main()
