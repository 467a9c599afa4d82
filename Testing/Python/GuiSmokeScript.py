# Runs INSIDE the ParaView GUI: paraview --script=GuiSmokeScript.py --exit
# (driven by TestGuiSmoke.py, which checks what this script writes).
#
# Environment: AMRSP_PLUGIN (the plugin library), AMRSP_DATA_DIR (the data folder), AMRSP_GUI_OUT
# (a folder for the outputs) and AMRSP_TEST_DIR (this folder). Writes AMRSP_GUI_OUT/gui-smoke.png,
# a screenshot of the active render view, gui-smoke-view.json (the view for amrsp reference),
# gui-smoke-log.png (the same view with the colour map and opacity function log-scaled) and
# gui-smoke.json with what the GUI session reported (also the interactive-frame properties and
# the quality of one interactive and one still render).
import json
import os
import sys
import traceback

from paraview import simple

sys.path.insert(0, os.environ["AMRSP_TEST_DIR"])
from PluginTestKit import write_view_json  # noqa: E402

out = os.environ["AMRSP_GUI_OUT"]
status = {"ok": False}
try:
    os.makedirs(out, exist_ok=True)
    simple.LoadPlugin(os.environ["AMRSP_PLUGIN"], remote=False, ns=globals())
    path = os.path.join(os.environ["AMRSP_DATA_DIR"], "enzo_moving7/DD0010/moving7_0010.hierarchy")
    reader = simple.EnzoReader(registrationName="moving7_0010.hierarchy", FileNames=[path])
    reader.Level = 30
    reader.CellArrayStatus = ["Density"]
    reader.ConvertToCGS = 1  # as amrsp reads Enzo, for the reference
    view = simple.GetActiveViewOrCreate("RenderView")
    display = simple.Show(reader, view)
    status["representation_types"] = list(display.Representation.Available)
    status["array_before"] = list(display.ColorArrayName)
    display.Representation = "AMR Single-Pass Volume"
    # what the type picked by itself (docs/paraview.md, "Defaults")
    status["array_picked"] = list(display.ColorArrayName)
    status["log_scale_picked"] = [simple.GetColorTransferFunction("Density").UseLogScale,
                                  simple.GetOpacityTransferFunction("Density").UseLogScale]
    simple.ColorBy(display, ("CELLS", "Density"))
    display.SetScalarBarVisibility(view, True)
    # a colour map on the low decades of the density (linear scale; g/cm^3, the lowest density
    # lo = 6.16e-28), ParaView's own preset interpolated in RGB as the reference does
    lo = 6.16257e-28
    lut = simple.GetColorTransferFunction("Density")
    lut.UseLogScale = 0  # the type's defaults chose log scale for the density
    lut.ApplyPreset("Cool to Warm", True)
    lut.ColorSpace = "RGB"
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(lo, 800.0 * lo)
    pwf = simple.GetOpacityTransferFunction("Density")
    pwf.UseLogScale = 0
    pwf.Points = [lo, 0.0, 0.5, 0.0, 10.0 * lo, 0.02, 0.5, 0.0, 100.0 * lo, 0.2, 0.5, 0.0,
                  1000.0 * lo, 0.6, 0.5, 0.0, 10000.0 * lo, 0.9, 0.5, 0.0]
    display.ScalarOpacityUnitDistance = 0.0173
    # a plain black background (the palette's may be a gradient), for the reference
    if hasattr(view, "UseColorPaletteForBackground"):
        view.UseColorPaletteForBackground = 0
    if hasattr(view, "BackgroundColorMode"):
        view.BackgroundColorMode = "Single Color"
    view.Background = [0.0, 0.0, 0.0]
    display.SampleDistanceFactor = 0.5
    view.OrientationAxesVisibility = 1
    view.ResetCamera()
    camera = view.GetActiveCamera()
    camera.Azimuth(30.0)
    camera.Elevation(20.0)
    camera.OrthogonalizeViewUp()
    simple.Render(view)
    simple.SaveScreenshot(os.path.join(out, "gui-smoke.png"), view, ImageResolution=[300, 300],
        TransparentBackground=0)
    write_view_json(view, display, "Density", os.path.join(out, "gui-smoke-view.json"))
    display.SMProxy.UpdatePropertyInformation()
    error = display.SMProxy.GetProperty("SinglePassRenderError")
    builds = display.SMProxy.GetProperty("SinglePassTextureBuilds")
    status["render_error"] = error.GetElement(0) if error.GetNumberOfElements() else None
    status["texture_builds"] = builds.GetElement(0) if builds.GetNumberOfElements() else None
    status["representation"] = display.SMProxy.GetProperty("Representation").GetElement(0)

    def last_frame_quality():
        display.SMProxy.UpdatePropertyInformation()
        prop = display.SMProxy.GetProperty("SinglePassLastFrameQuality")
        return [prop.GetElement(i) for i in range(prop.GetNumberOfElements())]

    # the interactive-frame properties as the GUI shows them, then one interactive render (as
    # the GUI renders while the mouse drags the camera) and one still render
    status["interactive_properties"] = {
        name: display.GetPropertyValue(name)
        for name in ("AutoAdjustSampleDistances", "ImageSampleDistance",
                     "MinimumImageSampleDistance", "MaximumImageSampleDistance",
                     "InteractiveAdjustSampleDistances")}
    display.MaximumImageSampleDistance = 2.0
    view.SMProxy.InteractiveRender()
    status["interactive_quality"] = last_frame_quality()
    view.SMProxy.StillRender()
    status["still_quality"] = last_frame_quality()
    # log-scaled colour map and opacity function over the same positive range
    lut.UseLogScale = 1
    pwf.UseLogScale = 1
    simple.Render(view)
    simple.SaveScreenshot(os.path.join(out, "gui-smoke-log.png"), view,
        ImageResolution=[300, 300], TransparentBackground=0)
    display.SMProxy.UpdatePropertyInformation()
    error = display.SMProxy.GetProperty("SinglePassRenderError")
    status["log_render_error"] = error.GetElement(0) if error.GetNumberOfElements() else None
    status["ok"] = True
except Exception:
    status["exception"] = traceback.format_exc()
text = json.dumps(status, indent=2, default=str)  # complete before the file is written
with open(os.path.join(out, "gui-smoke.json"), "w") as f:
    f.write(text)
