# Runs INSIDE the ParaView GUI: paraview --script=GuiSmokeScript.py --exit
# (driven by TestGuiSmoke.py, which checks what this script writes).
#
# Environment: AMRSP_PLUGIN (the plugin library), AMRSP_DATA_DIR (the data folder) and
# AMRSP_GUI_OUT (a folder for the outputs). Writes AMRSP_GUI_OUT/gui-smoke.png, a screenshot of the
# active render view, and AMRSP_GUI_OUT/gui-smoke.json with what the GUI session reported.
import json
import os
import traceback

from paraview import simple

out = os.environ["AMRSP_GUI_OUT"]
status = {"ok": False}
try:
    os.makedirs(out, exist_ok=True)
    simple.LoadPlugin(os.environ["AMRSP_PLUGIN"], remote=False, ns=globals())
    path = os.path.join(os.environ["AMRSP_DATA_DIR"], "enzo_moving7/DD0010/moving7_0010.hierarchy")
    reader = simple.EnzoReader(registrationName="moving7_0010.hierarchy", FileNames=[path])
    reader.Level = 30
    reader.CellArrayStatus = ["Density"]
    view = simple.GetActiveViewOrCreate("RenderView")
    display = simple.Show(reader, view)
    status["representation_types"] = list(display.Representation.Available)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))
    display.SetScalarBarVisibility(view, True)
    # a colour map on the low decades of the density (linear scale), ParaView's own preset
    lut = simple.GetColorTransferFunction("Density")
    lut.ApplyPreset("Cool to Warm", True)
    lut.AutomaticRescaleRangeMode = "Never"
    lut.RescaleTransferFunction(0.1, 80.0)
    pwf = simple.GetOpacityTransferFunction("Density")
    pwf.Points = [0.1, 0.0, 0.5, 0.0, 1.0, 0.02, 0.5, 0.0, 10.0, 0.2, 0.5, 0.0,
                  100.0, 0.6, 0.5, 0.0, 1000.0, 0.9, 0.5, 0.0]
    display.ScalarOpacityUnitDistance = 0.0173
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
    display.SMProxy.UpdatePropertyInformation()
    error = display.SMProxy.GetProperty("SinglePassRenderError")
    builds = display.SMProxy.GetProperty("SinglePassTextureBuilds")
    status["render_error"] = error.GetElement(0) if error.GetNumberOfElements() else None
    status["texture_builds"] = builds.GetElement(0) if builds.GetNumberOfElements() else None
    status["representation"] = display.SMProxy.GetProperty("Representation").GetElement(0)
    status["ok"] = True
except Exception:
    status["exception"] = traceback.format_exc()
text = json.dumps(status, indent=2, default=str)  # complete before the file is written
with open(os.path.join(out, "gui-smoke.json"), "w") as f:
    f.write(text)
