# pvpython test of what switching a display to "AMR Single-Pass Volume" sets up by itself
# (docs/paraview.md, "Defaults"):
#
#   pvpython --force-offscreen-rendering TestPluginDefaults.py PLUGIN OUTDIR [--server PVSERVER]
#
# Every case shows a source in a new view (ParaView's default type for AMR: Outline, Solid Color),
# switches the display to the type with nothing else set, and checks
#   - the array picked: the coloured array when it is real, else the active scalars, else the
#     first array (ParaView's choice for "Volume");
#   - the density-like rule: log scale on the colour map and the opacity function exactly when
#     the array's values are all >= 0 and its maximum exceeds its smallest positive value by more
#     than three decades, with the maps on [smallest positive value, maximum]; otherwise linear
#     maps on the data range (ParaView's RescaleTransferFunctionToDataRange);
#   - the image: the representation renders without error and shows the volume (share of
#     non-background pixels above the case's bound).
# The test shows that its checks reject the broken cases: the same display with no array
# (Solid Color, what the type drew before it had defaults) and the density-like arrays with
# linear maps (ParaView's defaults alone) fall below the image bound, and the rule, evaluated
# here on the data (builtin session), rejects the arrays that are not density-like.
# Cases: the plugin's synthetic cosmology (Density), the Enzo dataset (Density, switched the way
# the GUI does; all arrays: the first one, Dark_Matter_Density, whose minimum is 0; an array
# coloured before the switch is kept; x-velocity: linear) and a calculator's array with
# negative values that is the active scalars (linear).
# --server: the same through a pvserver (the data and the range gathering on the server).
# Exit codes: 0 pass, 1 fail, 125 skipped (no X display, data or usable OpenGL context).
import os
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import array_statistics, check_render_error, fail, skip  # noqa: E402

TYPE = "AMR Single-Pass Volume"
SIZE = 160
DECADES = 3.0  # the density-like rule: maximum / smallest positive value > 10^DECADES
ENZO = "enzo_moving7/DD0010/moving7_0010.hierarchy"
# Share of the frame's pixels that must show the volume, per case: about half of what was
# measured (synthetic 48.9 %, Enzo Density 8.7 %, the other Enzo cases 50 to 51 %, the
# calculator's array 48.9 %). The broken cases (no array; a density-like array with linear
# maps) measured 0.0 %.
BOUNDS = {
    "synthetic": 0.25,
    "enzo-density": 0.04,
    "enzo-all": 0.25,
    "enzo-kept": 0.25,
    "enzo-x-velocity": 0.25,
    "contrast": 0.25,
}


def density_like(stats):
    """The rule, on (count, minimum, maximum, smallest positive value)."""
    count, lo, hi, lo_positive = stats
    return count > 0 and lo >= 0.0 and lo_positive > 0.0 and hi / lo_positive > 10.0 ** DECADES


def function_range(function):
    points = list(function.RGBPoints) if hasattr(function, "RGBPoints") else list(function.Points)
    xs = points[0::4]
    return min(xs), max(xs)


def close(a, b, tolerance=1e-6):
    return abs(a - b) <= tolerance * max(abs(a), abs(b), 1e-300)


def forget_transfer_functions():
    """Unregisters every colour map and opacity function, so that the next case starts from
    ParaView's defaults as a new session would (they are shared by array name)."""
    from paraview import servermanager

    pxm = servermanager.ProxyManager()
    for group in ("lookup_tables", "piecewise_functions"):
        for key, proxy in list(pxm.GetProxiesInGroup(group).items()):
            pxm.UnRegisterProxy(group, key[0], proxy)


class Session:
    def __init__(self, outdir, server):
        self.outdir = outdir
        self.server = server
        self.builtin = server is None
        self.measured = {}

    def new_view(self):
        from paraview import simple

        view = simple.CreateView("RenderView")
        view.ViewSize = [SIZE, SIZE]
        view.OrientationAxesVisibility = 0
        view.UseColorPaletteForBackground = 0
        view.Background = [0.0, 0.0, 0.0]
        return view

    def shot(self, view, display, label):
        """Renders the view (the amrsp camera directions), returns the share of pixels that show
        the volume; fails on a render error."""
        from paraview import simple
        from PluginTestKit import coverage, info_property, read_png, server_died

        simple.Render(view)
        # ResetCamera keeps the view direction: start each shot from the same one
        view.CameraPosition = [0.0, 0.0, 1.0]
        view.CameraFocalPoint = [0.0, 0.0, 0.0]
        view.CameraViewUp = [0.0, 1.0, 0.0]
        view.ResetCamera()
        view.GetActiveCamera().Azimuth(30.0)
        view.GetActiveCamera().Elevation(20.0)
        path = os.path.join(self.outdir, "defaults-%s.png" % label)
        simple.SaveScreenshot(path, view, ImageResolution=[SIZE, SIZE], TransparentBackground=0)
        server_died(self.server)
        check_render_error(info_property(display, "SinglePassRenderError"), label)
        return coverage(read_png(path)[2])

    def check_case(self, label, source, display, expected_array, expected_log, stats=None):
        """Checks the array and the maps of a display just switched to the type; `stats`: the
        array's statistics from the data (builtin session) or None."""
        from paraview import simple

        picked = list(display.ColorArrayName)
        print("%s: array picked %s" % (label, picked))
        if picked != list(expected_array):
            fail("%s: picked %s, expected %s" % (label, picked, list(expected_array)))
        name = expected_array[1]
        lut = simple.GetColorTransferFunction(name)
        pwf = simple.GetOpacityTransferFunction(name)
        if display.LookupTable is None or display.LookupTable.SMProxy != lut.SMProxy:
            fail("%s: the display has no colour map for %s" % (label, name))
        if display.ScalarOpacityFunction is None or \
                display.ScalarOpacityFunction.SMProxy != pwf.SMProxy:
            fail("%s: the display has no opacity function for %s" % (label, name))
        value_range = source.CellData[name].GetRange()
        if stats is not None:
            rule = density_like(stats)
            print("%s: %s over the sampled cells: min %.6g, smallest positive %.6g, max %.6g "
                  "(max / smallest positive %.3g): density-like %s"
                  % (label, name, stats[1], stats[3], stats[2],
                     stats[2] / stats[3] if stats[3] > 0 else float("inf"), rule))
            if rule != expected_log:
                fail("%s: the rule on the data says %s, the case expects %s"
                     % (label, rule, expected_log))
        for function, what in ((lut, "colour map"), (pwf, "opacity function")):
            lo, hi = function_range(function)
            print("%s: %s %s scale on [%.6g, %.6g]"
                  % (label, what, "log" if function.UseLogScale else "linear", lo, hi))
            if bool(function.UseLogScale) != expected_log:
                fail("%s: the %s is %s scale, expected %s" % (label, what,
                     "log" if function.UseLogScale else "linear",
                     "log" if expected_log else "linear"))
            if not close(hi, value_range[1]):
                fail("%s: the %s ends at %g, the data at %g" % (label, what, hi, value_range[1]))
            if expected_log:
                # the smallest positive value: exactly (builtin) or at least not ParaView's
                # fallback for log ranges reaching 0 (min(max / 10^4, 1))
                if stats is not None and not close(lo, stats[3]):
                    fail("%s: the %s starts at %g, the smallest positive value is %g"
                         % (label, what, lo, stats[3]))
                if value_range[0] <= 0.0 and (lo <= 0.0 or close(lo, min(1.0, hi * 1.0e-4))):
                    fail("%s: the %s starts at %g, ParaView's fallback, not at a data value"
                         % (label, what, lo))
                if value_range[0] > 0.0 and not close(lo, value_range[0]):
                    fail("%s: the %s starts at %g, the data at %g" % (label, what, lo,
                         value_range[0]))
            elif not close(lo, value_range[0]):
                fail("%s: the %s starts at %g, the data at %g" % (label, what, lo, value_range[0]))

    def image(self, label, view, display):
        covered = self.shot(view, display, label)
        self.measured[label] = covered
        print("%s: the volume covers %.1f %% of the pixels (bound %.1f %%)"
              % (label, 100.0 * covered, 100.0 * BOUNDS[label]))
        if covered < BOUNDS[label]:
            fail("%s: the image does not show the volume" % label)

    def reject_empty(self, label, view, display, assoc_name):
        """The same display with no array (Solid Color): the bound must reject its image."""
        from paraview import simple

        simple.ColorBy(display, None)
        covered = self.shot(view, display, label + "-solid")
        rejected = covered < BOUNDS[label]
        print("%s: with no array (Solid Color) the volume covers %.1f %%: %s"
              % (label, 100.0 * covered, "rejected" if rejected else "NOT REJECTED"))
        if not rejected:
            fail("%s: the bound does not reject the image without an array" % label)
        simple.ColorBy(display, assoc_name)

    def reject_linear(self, label, view, display, name):
        """The density-like array with linear maps (the colour-map editor unchecking log scale:
        the points keep their places): the bound must reject its image."""
        from paraview import simple

        lut = simple.GetColorTransferFunction(name)
        pwf = simple.GetOpacityTransferFunction(name)
        for function in (lut, pwf):
            function.MapControlPointsToLinearSpace()
            function.UseLogScale = 0
        function_lo = function_range(lut)[0]
        covered = self.shot(view, display, label + "-linear")
        rejected = covered < BOUNDS[label]
        print("%s: with linear maps on [%.6g, ...] the volume covers %.1f %%: %s"
              % (label, function_lo, 100.0 * covered, "rejected" if rejected else "NOT REJECTED"))
        if not rejected:
            fail("%s: the bound does not reject the linear maps of a density-like array" % label)

    def finish(self, view, sources):
        from paraview import simple

        for source in sources:
            simple.Delete(source)
        simple.Delete(view)
        forget_transfer_functions()


def enzo_reader(path, arrays):
    from paraview import simple

    reader = simple.EnzoReader(FileNames=[path])
    reader.Level = 30  # all levels
    reader.CellArrayStatus = arrays if arrays else reader.CellArrayStatus.Available
    reader.UpdatePipeline()
    return reader


def run_cases(session, enzo_path):
    from paraview import simple

    # 1. the synthetic cosmology: Density, switched with the property
    source = AMRCosmologysynthetic(NumberOfGrids=400, NumberOfLevels=4,  # noqa: F821
                                   NumberOfCells=300000, Seed=3)
    source.UpdatePipeline()
    view = session.new_view()
    display = simple.Show(source, view)
    if TYPE not in display.Representation.Available or display.ColorArrayName[1]:
        fail("unexpected start: types %s, array %s" % (display.Representation.Available,
                                                      display.ColorArrayName))
    display.Representation = TYPE
    stats = array_statistics(source, "Density") if session.builtin else None
    session.check_case("synthetic", source, display, ["CELLS", "Density"], True, stats)
    session.image("synthetic", view, display)
    session.reject_empty("synthetic", view, display, ("CELLS", "Density"))
    session.reject_linear("synthetic", view, display, "Density")
    session.finish(view, [source])

    # 2. Enzo, Density alone, switched the way the GUI's representation menu does
    reader = enzo_reader(enzo_path, ["Density"])
    view = session.new_view()
    display = simple.Show(reader, view)
    display.SetRepresentationType(TYPE)
    stats = array_statistics(reader, "Density") if session.builtin else None
    session.check_case("enzo-density", reader, display, ["CELLS", "Density"], True, stats)
    session.image("enzo-density", view, display)
    session.reject_empty("enzo-density", view, display, ("CELLS", "Density"))
    session.reject_linear("enzo-density", view, display, "Density")
    session.finish(view, [reader])

    # 3. Enzo, every array: the first one, whose minimum is 0 (the smallest positive value is
    # gathered from the data)
    reader = enzo_reader(enzo_path, None)
    view = session.new_view()
    display = simple.Show(reader, view)
    display.Representation = TYPE
    name = "Dark_Matter_Density"
    stats = array_statistics(reader, name) if session.builtin else None
    if reader.CellData[name].GetRange()[0] != 0.0:
        fail("%s no longer has the minimum 0 this case needs" % name)
    session.check_case("enzo-all", reader, display, ["CELLS", name], True, stats)
    session.image("enzo-all", view, display)
    # a second switch of a coloured display keeps its array and colour map
    display.Representation = "Outline"
    simple.ColorBy(display, ("CELLS", "x-velocity"))
    display.Representation = TYPE
    kept = list(display.ColorArrayName)
    print("enzo-all: switched again, coloured by x-velocity: array %s" % kept)
    if kept != ["CELLS", "x-velocity"]:
        fail("enzo-all: the coloured array was replaced by %s" % kept)
    session.finish(view, [reader])

    # 4. Enzo, coloured by Temperature before the first switch: the array is kept, the rule applies
    reader = enzo_reader(enzo_path, None)
    view = session.new_view()
    display = simple.Show(reader, view)
    simple.ColorBy(display, ("CELLS", "Temperature"))
    display.Representation = TYPE
    stats = array_statistics(reader, "Temperature") if session.builtin else None
    session.check_case("enzo-kept", reader, display, ["CELLS", "Temperature"], True, stats)
    session.image("enzo-kept", view, display)
    session.finish(view, [reader])

    # 5. Enzo, x-velocity alone: positive, but not three decades: linear
    reader = enzo_reader(enzo_path, ["x-velocity"])
    view = session.new_view()
    display = simple.Show(reader, view)
    display.Representation = TYPE
    stats = array_statistics(reader, "x-velocity") if session.builtin else None
    session.check_case("enzo-x-velocity", reader, display, ["CELLS", "x-velocity"], False, stats)
    session.image("enzo-x-velocity", view, display)
    session.finish(view, [reader])

    # 6. a calculator's array with negative values, the active scalars (listed after Density):
    # picked before the first array, linear
    source = AMRCosmologysynthetic(NumberOfGrids=400, NumberOfLevels=4,  # noqa: F821
                                   NumberOfCells=300000, Seed=3)
    calculator = simple.Calculator(Input=source)
    calculator.AttributeType = "Cell Data"
    calculator.ResultArrayName = "LogContrast"
    calculator.Function = "log10(Density) - 0.5"
    calculator.UpdatePipeline()
    view = session.new_view()
    display = simple.Show(calculator, view)
    display.Representation = TYPE
    stats = array_statistics(calculator, "LogContrast") if session.builtin else None
    session.check_case("contrast", calculator, display, ["CELLS", "LogContrast"], False, stats)
    session.image("contrast", view, display)
    session.finish(view, [calculator, source])


def main():
    usage = "usage: TestPluginDefaults.py PLUGIN OUTDIR [--server PVSERVER]"
    args = sys.argv[1:]
    if len(args) not in (2, 4) or (len(args) == 4 and args[2] != "--server"):
        print(usage)
        return 2
    plugin, outdir = args[:2]
    pvserver = args[3] if len(args) == 4 else None
    data_dir = os.environ.get("AMRSP_DATA_DIR", os.path.join(os.getcwd(), "../shared/data"))
    enzo_path = os.path.join(data_dir, ENZO)
    if not os.path.exists(enzo_path):
        skip("dataset not found: %s" % enzo_path)
    from PluginTestKit import require_display, start_server, stop_server

    require_display()
    os.makedirs(outdir, exist_ok=True)
    from paraview import simple

    server = None
    if pvserver:
        server = start_server(pvserver, os.path.join(outdir, "defaults-pvserver.log"))
        simple.LoadPlugin(plugin, remote=True, ns=globals())
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    session = Session(outdir, server)
    run_cases(session, enzo_path)
    print("measured shares of pixels showing the volume: %s"
          % ", ".join("%s %.1f %%" % (k, 100.0 * v) for k, v in session.measured.items()))
    if server:
        stop_server(server)
    print("PASS")
    return 0


if __name__ == "__main__":
    if main() != 0:
        from PluginTestKit import leave

        leave(2)
