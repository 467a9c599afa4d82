# pvpython test of the representation on what a damaged or partial read hands it:
#
#   pvpython --force-offscreen-rendering TestPluginDamagedData.py PLUGIN OUTDIR
#
# Each case is a vtkOverlappingAMR built here and shown through a TrivialProducer as "AMR
# Single-Pass Volume" coloured by Density: an AMR with no blocks, blocks without the array, the
# array NaN everywhere, and a partial AMR (a block its metadata describes holds no data, as when
# a reader could not load it). Each must render three frames without a crash or hang, draw
# nothing (black screenshot), report its problem in SinglePassRenderError, and say it in
# ParaView's output window exactly once. A good AMR afterwards renders again.
# Exit codes: 0 pass, 1 fail, 125 skipped (no usable OpenGL context).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import leave  # noqa: E402


def say(text):
    """Straight to file descriptor 1: pvpython routes print() through vtkOutputWindow, which this
    test replaces (and ParaView 5.13 and 6.1 do not give back its way to stdout)."""
    os.write(1, (text + "\n").encode())

CASES = [
    ("no blocks", "holds no blocks"),
    ("blocks without the array", "no cell array named 'Density'"),
    ("Density NaN everywhere", "holds no finite value"),
    ("a described block without data", "has no data loaded"),
]


def make_amr(case):
    import math
    from vtkmodules.vtkCommonDataModel import vtkAMRBox, vtkOverlappingAMR, vtkUniformGrid
    from vtkmodules.vtkCommonCore import vtkDoubleArray

    amr = vtkOverlappingAMR()
    if case == "no blocks":
        amr.Initialize(1, [0])
        amr.SetOrigin([0.0, 0.0, 0.0])
        amr.SetGridDescription(9)  # VTK_XYZ_GRID
        amr.SetSpacing(0, [0.125, 0.125, 0.125])
        return amr
    amr.Initialize(2, [1, 1])
    amr.SetOrigin([0.0, 0.0, 0.0])
    amr.SetRefinementRatio(0, 2)
    for level, lo, n, h in ((0, 0, 8, 0.125), (1, 4, 8, 0.0625)):
        amr.SetSpacing(level, [h, h, h])
        box = vtkAMRBox([lo, lo, lo], [lo + n - 1, lo + n - 1, lo + n - 1])
        amr.SetAMRBox(level, 0, box)
        if case == "a described block without data" and level == 1:
            continue  # described by the metadata, never loaded
        grid = vtkUniformGrid()
        grid.SetOrigin(lo * h, lo * h, lo * h)
        grid.SetSpacing(h, h, h)
        grid.SetDimensions(n + 1, n + 1, n + 1)
        if case != "blocks without the array":
            density = vtkDoubleArray()
            density.SetName("Density")
            for k in range(n):
                for j in range(n):
                    for i in range(n):
                        x, y, z = ((lo + c + 0.5) * h for c in (i, j, k))
                        r2 = (x - 0.5) ** 2 + (y - 0.45) ** 2 + (z - 0.5) ** 2
                        density.InsertNextValue(float("nan") if case == "Density NaN everywhere"
                                                else math.exp(-8.0 * r2))
            grid.GetCellData().AddArray(density)
        amr.SetDataSet(level, 0, grid)
    return amr


def main():
    plugin, outdir = sys.argv[1:3]
    from PluginTestKit import info_property, read_png, require_display

    require_display()
    os.makedirs(outdir, exist_ok=True)
    from paraview import simple
    from vtkmodules.vtkCommonCore import vtkFileOutputWindow, vtkOutputWindow

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    log = os.path.join(outdir, "damaged-output-window.txt")
    if os.path.exists(log):
        os.remove(log)
    original = vtkOutputWindow.GetInstance()
    report = []
    window = vtkFileOutputWindow()
    window.SetFileName(log)
    window.SetFlush(1)
    vtkOutputWindow.SetInstance(window)

    view = simple.CreateView("RenderView")
    view.ViewSize = [64, 64]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    checks = []
    for name, expected in CASES + [("good", None)]:
        producer = simple.TrivialProducer()
        producer.GetClientSideObject().SetOutput(
            make_amr("good" if expected is None else name))
        display = simple.Show(producer, view)
        display.Representation = "AMR Single-Pass Volume"
        display.ColorArrayName = ["CELLS", "Density"]
        # the colour map and opacity function (what ColorBy would attach; ColorBy itself
        # refuses an array the data lacks)
        display.LookupTable = simple.GetColorTransferFunction("Density")
        display.ScalarOpacityFunction = simple.GetOpacityTransferFunction("Density")
        lut = simple.GetColorTransferFunction("Density")
        lut.AutomaticRescaleRangeMode = "Never"
        lut.UseLogScale = 0  # linear maps, whatever the type's defaults chose
        lut.RGBPoints = [0.0, 0.2, 0.4, 1.0, 1.0, 1.0, 0.8, 0.2]
        simple.GetOpacityTransferFunction("Density").UseLogScale = 0
        simple.GetOpacityTransferFunction("Density").Points = [0.0, 0.0, 0.5, 0.0,
                                                                1.0, 0.8, 0.5, 0.0]
        view.ResetCamera()
        for _ in range(3):
            simple.Render(view)
        shot = os.path.join(outdir, "damaged-%d.png" % len(checks))
        simple.SaveScreenshot(shot, view, ImageResolution=[64, 64], TransparentBackground=0)
        pixels = read_png(shot)[2]
        drawn = float((pixels.max(axis=1) > 2).mean())
        error = info_property(display, "SinglePassRenderError") or ""
        said = 0
        if expected and os.path.exists(log):
            with open(log) as f:
                said = f.read().count(expected)
        if expected is None:
            ok = drawn > 0.05 and not error
            report.append("%-32s drawn on %4.1f %% of the pixels, error '%s'"
                          % (name, 100 * drawn, error))
        else:
            ok = expected in error and drawn == 0.0 and said == 1
            report.append("%-32s error '%s', drawn on %.1f %% of the pixels, said %d time(s) in "
                          "the output window" % (name, error, 100 * drawn, said))
        checks.append((name, ok))
        simple.Delete(display)
        simple.Delete(producer)
    vtkOutputWindow.SetInstance(original)
    for line in report:
        say(line)
    for name, ok in checks:
        say("%-32s %s" % (name, "ok" if ok else "FAILED"))
    if not all(ok for _, ok in checks):
        say("FAIL: a damaged input was not reported once, or drew something, or the good one did "
            "not render")
        leave(1)
    say("PASS")
    leave(0)


if __name__ == "__main__":
    if len(sys.argv) != 3:
        print("usage: TestPluginDamagedData.py PLUGIN OUTDIR")
        leave(2)
    main()
