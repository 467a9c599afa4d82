# GUI smoke test of the plugin: runs the ParaView GUI on a script and checks what it produced.
#
#   pvpython TestGuiSmoke.py PARAVIEW PLUGIN OUTDIR      (AMRSP_DATA_DIR names the data folder)
#
# `paraview --dr --script=GuiSmokeScript.py --exit` loads the plugin in the GUI, opens the Enzo
# hierarchy, switches it to "AMR Single-Pass Volume", colours it by Density and saves a screenshot
# of the render view. This driver then checks, without anyone looking: the GUI exited normally,
# the representation type was offered and selected, the mapper reported no error and built its
# textures once, and the screenshot shows the volume: enough pixels differ from the view's
# background, and the coloured pixels are not all one colour.
# Exit codes: 0 pass, 1 fail, 125 skipped (no data, or no X display for the GUI).
import json
import os
import subprocess
import sys
import time

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import check_render_error, fail, leave, skip  # noqa: E402

MIN_COVERAGE = 0.05  # share of the checked pixels that must show the volume (measured 12.6 %)


def display_answers():
    import ctypes
    import ctypes.util

    if not os.environ.get("DISPLAY"):
        return False
    library = ctypes.util.find_library("X11")
    if not library:
        return True
    x11 = ctypes.cdll.LoadLibrary(library)
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    handle = x11.XOpenDisplay(None)
    if not handle:
        return False
    x11.XCloseDisplay(handle)
    return True


def main():
    paraview, plugin, outdir = sys.argv[1:4]
    data_dir = os.environ.get("AMRSP_DATA_DIR", "")
    if not os.path.exists(os.path.join(data_dir, "enzo_moving7/DD0010/moving7_0010.hierarchy")):
        skip("Enzo moving7 not found under %r" % data_dir)
    # The GUI is an X application even where VTK renders without an X server (ParaView 6.1 on
    # VTK 9.6): the test runs without DISPLAY there, and scripts/run-tests.sh names the X server
    # for the GUI alone in AMRSP_GUI_DISPLAY.
    gui_display = os.environ.get("DISPLAY") or os.environ.get("AMRSP_GUI_DISPLAY", "")
    if gui_display:
        os.environ["DISPLAY"] = gui_display
    if not display_answers():
        skip("no X display answers (DISPLAY=%r); the GUI needs one (scripts/start-xvfb.sh)"
             % os.environ.get("DISPLAY"))
    os.makedirs(outdir, exist_ok=True)
    for name in ("gui-smoke.png", "gui-smoke.json"):
        if os.path.exists(os.path.join(outdir, name)):
            os.remove(os.path.join(outdir, name))

    script = os.path.join(os.path.dirname(os.path.abspath(__file__)), "GuiSmokeScript.py")
    env = dict(os.environ, AMRSP_PLUGIN=plugin, AMRSP_DATA_DIR=data_dir, AMRSP_GUI_OUT=outdir)
    started = time.time()
    try:
        run = subprocess.run([paraview, "--dr", "--script=" + script, "--exit"], env=env,
                             stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                             universal_newlines=True, timeout=300)
    except subprocess.TimeoutExpired:
        fail("the GUI did not exit within 300 s")
    seconds = time.time() - started
    print("paraview --script ... --exit: exit code %d after %.1f s" % (run.returncode, seconds))
    if run.returncode != 0:
        print(run.stdout[-4000:])
        fail("the GUI exited with code %d" % run.returncode)

    status_path = os.path.join(outdir, "gui-smoke.json")
    if not os.path.exists(status_path):
        print(run.stdout[-4000:])
        fail("the GUI script wrote no status (did it run?)")
    with open(status_path) as f:
        status = json.load(f)
    print("GUI status: %s" % json.dumps(status))
    if not status.get("ok"):
        fail("the GUI script failed: %s" % status.get("exception"))
    if "AMR Single-Pass Volume" not in status.get("representation_types", []):
        fail("the GUI does not offer the representation type")
    if status.get("representation") != "AMR Single-Pass Volume":
        fail("the representation was not selected")
    check_render_error(status.get("render_error"), "the mapper in the GUI")
    if status.get("texture_builds") != 1:
        fail("the mapper built its textures %s times (expected once)" % status.get("texture_builds"))

    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy
    import numpy

    shot = os.path.join(outdir, "gui-smoke.png")
    if not os.path.exists(shot):
        fail("no screenshot was saved")
    reader = vtkPNGReader()
    reader.SetFileName(shot)
    reader.Update()
    pixels = vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)
    # the view's background (the colour palette's) is the most common colour of the border rows
    dims = reader.GetOutput().GetDimensions()
    image = pixels.reshape(dims[1], dims[0], 3)
    border = numpy.concatenate([image[0], image[-1], image[:, 0], image[:, -1]])
    colours, counts = numpy.unique(border, axis=0, return_counts=True)
    background = colours[counts.argmax()]
    # the volume: pixels away from the background, not in the lower-left corner where the
    # orientation axes sit, nor in the right-hand strip of the scalar bar
    h, w = dims[1], dims[0]
    mask = numpy.ones((h, w), dtype=bool)
    mask[: h // 4, : w // 4] = False
    mask[:, int(w * 0.75):] = False
    differs = (numpy.abs(image - background).max(axis=2) > 12.0) & mask
    covered = differs.sum() / float(mask.sum())
    distinct = len(numpy.unique(image[differs].round(-1), axis=0)) if differs.any() else 0
    print("screenshot %s: %dx%d, background %s, %.1f %% of the checked pixels show the volume "
          "(bound %.1f %%), %d distinct colours there"
          % (shot, w, h, background.tolist(), 100.0 * covered, 100.0 * MIN_COVERAGE, distinct))
    if covered < MIN_COVERAGE:
        fail("the GUI screenshot does not show the volume")
    if distinct < 10:
        fail("the volume is drawn in fewer than 10 colours: not a colour-mapped volume")
    print("PASS")
    return 0


if __name__ == "__main__":
    if len(sys.argv) != 4:
        print("usage: TestGuiSmoke.py PARAVIEW PLUGIN OUTDIR")
        leave(2)
    main()
