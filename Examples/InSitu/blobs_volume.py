# script-version: 2
# Catalyst script of the in-situ example (ParaView 5.11 and later, "v2" Catalyst scripts): shows
# the simulation's channel "input", a vtkOverlappingAMR with the cell array "density", with the
# representation "AMR Single-Pass Volume", and saves one image per step. The adaptor loads the
# plugin and passes, in the data description's user data, the output folder (OutputDirectory)
# and optionally the image size (ImageSize) and whether to write the view for `amrsp reference`
# (WriteViewJson).
#
# Written per step into the output folder: step_NNNN.png, and from rank 0 step_NNNN.json with what
# the step cost on the slowest rank: the first render after the data change (the representation's
# copy of its input, its region split on several ranks, the mapper's build and upload, the
# draw), the mapper's own build and upload seconds, the screenshot (a second render, compositing
# and PNG writing); summed over the ranks, the array values the mappers read that are copies
# (not the simulation's memory) and the values their conversion read in place or copied; the
# texture builds so far, the storage that rendered and the representation's error ("" when
# fine). With WriteViewJson also
# view.json: camera, colour map and opacity function as `amrsp reference --view-json` reads them.
import json
import os
import sys
import time

from paraview import catalyst
from paraview.simple import *  # noqa: F401,F403

options = catalyst.Options()

producer = TrivialProducer(registrationName="input")  # noqa: F405

ARRAY = "density"
# the field is a sum of blobs of amplitude <= 1: fixed maps keep the images of the steps comparable
RGB_POINTS = [0.0, 0.23, 0.30, 0.75, 0.5, 0.87, 0.87, 0.87, 1.2, 0.71, 0.02, 0.15]
OPACITY_POINTS = [0.0, 0.0, 0.5, 0.0, 0.15, 0.0, 0.5, 0.0, 0.6, 0.5, 0.5, 0.0, 1.2, 0.9, 0.5, 0.0]
UNIT_DISTANCE = 0.05
SAMPLE_DISTANCE_FACTOR = 0.5

state = {}


def user_value(info, name, default):
    data = info.dataDescription.GetUserData()
    array = data.GetAbstractArray(name) if data else None
    return array.GetVariantValue(0).ToString() if array else default


def reduce(values, operation):
    """Each of `values` reduced over all ranks with vtkCommunicator's `operation` (MAX_OP,
    SUM_OP); rank 0 gets the result."""
    from paraview.modules.vtkRemotingCore import vtkProcessModule
    from vtkmodules.vtkCommonCore import vtkDoubleArray
    from vtkmodules.vtkParallelCore import vtkCommunicator

    controller = vtkProcessModule.GetProcessModule().GetGlobalController()
    if controller is None or controller.GetNumberOfProcesses() < 2:
        return list(values)
    send, receive = vtkDoubleArray(), vtkDoubleArray()
    for v in values:
        send.InsertNextValue(v)
    receive.SetNumberOfTuples(len(values))
    controller.Reduce(send, receive, getattr(vtkCommunicator, operation), 0)
    return [receive.GetValue(i) for i in range(len(values))]


def slowest(values):
    return reduce(values, "MAX_OP")


def information(proxy, name):
    """An information-only property of the representation: its value, or list of values."""
    p = proxy.GetProperty(name)
    values = [p.GetElement(i) for i in range(p.GetNumberOfElements())]
    return values[0] if len(values) == 1 else values


def rank():
    from paraview.modules.vtkRemotingCore import vtkProcessModule

    return vtkProcessModule.GetProcessModule().GetPartitionId()


def set_up(info):
    size = [int(v) for v in user_value(info, "ImageSize", "256 256").split()]
    view = CreateView("RenderView")  # noqa: F405
    view.ViewSize = size
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    display = Show(producer, view)  # noqa: F405
    display.Representation = "AMR Single-Pass Volume"
    ColorBy(display, ("CELLS", ARRAY))  # noqa: F405
    lut = GetColorTransferFunction(ARRAY)  # noqa: F405
    lut.AutomaticRescaleRangeMode = "Never"
    lut.UseLogScale = 0
    lut.RGBPoints = RGB_POINTS
    lut.ColorSpace = "RGB"  # linear between the points, as `amrsp reference` interpolates
    pwf = GetOpacityTransferFunction(ARRAY)  # noqa: F405
    pwf.UseLogScale = 0
    pwf.Points = OPACITY_POINTS
    display.ScalarOpacityUnitDistance = UNIT_DISTANCE
    display.SampleDistanceFactor = SAMPLE_DISTANCE_FACTOR
    # the unit cube seen as `amrsp render` sees it: reset, azimuth 30, elevation 20
    view.ResetCamera(0.0, 1.0, 0.0, 1.0, 0.0, 1.0)
    camera = view.GetActiveCamera()
    camera.Azimuth(30.0)
    camera.Elevation(20.0)
    camera.OrthogonalizeViewUp()
    state.update(view=view, display=display, size=size)


def catalyst_execute(info):
    if "view" not in state:
        set_up(info)
    view, display = state["view"], state["display"]
    folder = user_value(info, "OutputDirectory", ".")
    start = time.perf_counter()
    Render(view)  # noqa: F405
    render_s = time.perf_counter() - start
    start = time.perf_counter()
    SaveScreenshot(os.path.join(folder, "step_%04d.png" % info.timestep), view,  # noqa: F405
                   ImageResolution=state["size"])
    screenshot_s = time.perf_counter() - start
    proxy = display.SMProxy
    proxy.UpdatePropertyInformation()
    build_s, upload_s = information(proxy, "SinglePassLastBuildSeconds")
    borrowed, converted = information(proxy, "SinglePassLastInputValues")
    copied = information(proxy, "SinglePassCopiedValues")
    # the mapper's last frame on each rank: interactive (1) or still, its image sample distance
    # and the seconds the view allocated to it (a still frame has far more than one)
    interactive, sample_distance, _, budget, _ = information(proxy, "SinglePassLastFrameQuality")
    costs = slowest([render_s, screenshot_s, build_s, upload_s, interactive, sample_distance,
                     -budget])
    values = reduce([borrowed, converted, copied], "SUM_OP")
    error = information(proxy, "SinglePassRenderError")
    if rank() != 0:
        return
    if user_value(info, "WriteViewJson", "0") == "1" and info.timestep == 0:
        sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..",
                                        "Tools", "scripts"))
        from paraview_view_json import write_view_json

        write_view_json(view, display, ARRAY, os.path.join(folder, "view.json"))
    with open(os.path.join(folder, "step_%04d.json" % info.timestep), "w") as f:
        json.dump({
            "step": info.timestep, "time": info.time,
            "render_s": round(costs[0], 4), "screenshot_s": round(costs[1], 4),
            "build_s": round(costs[2], 4), "upload_s": round(costs[3], 4),
            # over all ranks: values the mappers read from arrays that are not the input's, and
            # values their conversion read in place or copied
            "values_copied": int(values[2]),
            "conversion_borrowed": int(values[0]), "conversion_copied": int(values[1]),
            "texture_builds": information(proxy, "SinglePassTextureBuilds"),
            # over all ranks: whether any rank's last frame was interactive, the largest image
            # sample distance and the smallest time budget (seconds)
            "frame_interactive": int(costs[4]), "image_sample_distance": costs[5],
            "frame_budget_s": -costs[6],
            "storage": information(proxy, "SinglePassDataStorage"),
            "error": error,
        }, f, indent=1)
