# Shared by the plugin's Python tests: exit codes, and the synthetic cosmology volume they view.
# Imports nothing of ParaView at module level (TestGuiSmoke.py runs under plain python3).
# Importing it makes an uncaught exception a FAIL that runs the BEFORE_FAIL hooks.
import os
import subprocess
import sys
import time

sys.path.insert(
    0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "..", "Tools", "scripts"))
from pvpython_exit import exit_keeping_output  # noqa: E402
from paraview_view_json import first_light, write_view_json  # noqa: E402,F401

SKIP = 125  # CTest's skip code (SKIP_RETURN_CODE)

# Functions called (without arguments) before a failure is printed, e.g. to repeat what a
# helper process logged.
BEFORE_FAIL = []
# Functions called before the process ends, e.g. to stop a helper process.
BEFORE_LEAVE = []


def leave(code):
    """Ends the process with `code`, without finalising ParaView and keeping what was printed
    (Tools/scripts/pvpython_exit.py says why). A test that passes simply returns from the
    script."""
    for hook in BEFORE_LEAVE:
        hook()
    exit_keeping_output(code)


def pop_option(args, name):
    """The value after NAME in the list ARGS, removed from it with NAME (None when absent)."""
    if name not in args[:-1]:
        return None
    at = args.index(name)
    value = args[at + 1]
    del args[at:at + 2]
    return value


def outdated_fixture_files(outputs, inputs):
    """Why the files OUTPUTS of a fixture run (ctest FIXTURES_SETUP) cannot stand for a run of
    the binaries INPUTS, or None when they can: one is missing, or the oldest of them is older
    than an input (the binaries were rebuilt after the fixture ran)."""
    missing = [path for path in outputs if not os.path.exists(path)]
    if missing:
        return "%s is missing" % missing[0]
    oldest = min(outputs, key=os.path.getmtime)
    newer = [path for path in inputs if os.path.getmtime(path) > os.path.getmtime(oldest)]
    if newer:
        return "%s is older than %s" % (oldest, ", ".join(newer))
    return None


def fixture_problem(outputs, inputs, folder):
    """What keeps a test from using a fixture run's OUTPUTS made by the binaries INPUTS (None when
    nothing): first the check itself, shown in FOLDER to reject a missing and an outdated file
    (show_fixture_check_rejects), then outdated_fixture_files."""
    wrong = show_fixture_check_rejects(folder)
    if wrong:
        return "the check of the fixture run is broken: " + "; ".join(wrong)
    return outdated_fixture_files(outputs, inputs)


def show_fixture_check_rejects(folder):
    """outdated_fixture_files on files made in FOLDER: it must reject a missing output and one
    older than its binary, and accept a current one; returns what it got wrong (empty when
    nothing)."""
    work = os.path.join(folder, "fixture-check")
    os.makedirs(work, exist_ok=True)
    output, binary = os.path.join(work, "output"), os.path.join(work, "binary")
    for path in (output, binary):
        if os.path.exists(path):
            os.remove(path)
    open(binary, "w").close()
    wrong = []
    if outdated_fixture_files([output], [binary]) is None:
        wrong.append("a missing output was accepted")
    open(output, "w").close()
    now = time.time()
    os.utime(output, (now - 100, now - 100))
    os.utime(binary, (now, now))
    if outdated_fixture_files([output], [binary]) is None:
        wrong.append("an output older than its binary was accepted")
    os.utime(binary, (now - 200, now - 200))
    if outdated_fixture_files([output], [binary]) is not None:
        wrong.append("a current output was rejected")
    return wrong


def fail(message):
    for hook in BEFORE_FAIL:
        hook()
    print("FAIL: " + message)
    leave(1)


def _fail_on_uncaught_exception(kind, value, trace):
    # An exception nobody caught (e.g. simple.Show raising when a pvserver died) goes through
    # fail(), so that the BEFORE_FAIL hooks report what the helper processes logged.
    import traceback

    traceback.print_exception(kind, value, trace)
    fail("uncaught %s: %s" % (kind.__name__, value))


sys.excepthook = _fail_on_uncaught_exception


def skip(message):
    """Reports a test that cannot run here as skipped (CTest's skip code). With AMRSP_REQUIRE_GPU=1
    (scripts/run-tests.sh sets it in CI, where everything a test needs is installed) the same
    condition is a failure that names what is missing."""
    if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
        fail("required here (AMRSP_REQUIRE_GPU=1) but missing: " + message)
    print("SKIPPED: " + message)
    leave(SKIP)


# What the mapper's render-support probe (vtkSinglePassAMRRenderSupport::IsRenderSupported) says when the
# OpenGL context cannot run it at all. Only these make a test skip; any other render error, even
# one that mentions OpenGL or the context (an upload that failed, a texture limit), is a failure.
UNSUPPORTED_CONTEXT = (
    "the OpenGL context cannot be created or is older than VTK's minimum (3.2 core)",
    "lacks GLSL 1.50 integer textures (3.2 core needed)",
    "the render window is not an OpenGL render window",
)


def check_render_error(error, what="the representation"):
    """Skips on the render-support probe's own messages, fails on any other error."""
    if not error:
        return
    if any(message in error for message in UNSUPPORTED_CONTEXT):
        skip("the mapper cannot render in this context: %s" % error)
    fail("%s reported an error: %s" % (what, error))


# The windows of VTK's window systems; ParaView's own offscreen window wraps one of them.
WINDOW_SYSTEMS = ("vtkXOpenGLRenderWindow", "vtkEGLRenderWindow", "vtkOSOpenGLRenderWindow")


def check_window(view):
    """Prints the view's render window class and OpenGL renderer string, and fails where the test
    did not render through the backend of its pass (scripts/run-tests.sh): a window of another
    window system than VTK_DEFAULT_OPENGL_WINDOW asks for, or another OpenGL renderer than the one
    the pass's backend check saw the tool render with (AMRSP_EXPECTED_RENDERER; OSMesa's Mesa 25
    and EGL's Mesa 26 name different LLVM versions)."""
    window = view.GetRenderWindow()
    name = window.GetClassName()
    renderer = "unknown"
    for line in window.ReportCapabilities().splitlines():
        if line.startswith("OpenGL renderer string:"):
            renderer = line.split(":", 1)[1].strip()
    print("render window: %s, OpenGL renderer: %s" % (name, renderer))
    wanted = os.environ.get("VTK_DEFAULT_OPENGL_WINDOW")
    if wanted and name in WINDOW_SYSTEMS and name != wanted:
        fail("asked for %s (VTK_DEFAULT_OPENGL_WINDOW), rendered through %s" % (wanted, name))
    expected = os.environ.get("AMRSP_EXPECTED_RENDERER")
    if expected and not os.environ.get("MESA_LOADER_DRIVER_OVERRIDE") and renderer != expected:
        fail("rendered by '%s', where this pass's backend check rendered with '%s'"
             % (renderer, expected))


def density_quantiles(source, fractions):
    """Quantiles of the cell array Density over the level-0 blocks, i.e. by volume (builtin
    session: the source's own output, as servermanager.Fetch cannot move a vtkOverlappingAMR)."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    source.UpdatePipeline()
    amr = source.GetClientSideObject().GetOutputDataObject(0)
    values = []
    for index in range(amr.GetNumberOfDataSets(0)):
        block = amr.GetDataSet(0, index)
        if block is not None:
            values.append(vtk_to_numpy(block.GetCellData().GetArray("Density")))
    return numpy.quantile(numpy.concatenate(values), fractions).tolist()


def show_density_volume(source, size, before_show=None):
    """A black `size`² render view showing `source` (the plugin's synthetic cosmology) with the
    representation "AMR Single-Pass Volume" coloured by Density; the density is heavy-tailed, so
    colours and opacity follow its quantiles, not its range. Returns (view, display, q): q the
    Density quantiles 0, 0.5, 0.9, 0.99 and 1 the maps are built on. before_show(view), if given,
    runs between creating the view and showing the source in it."""
    from paraview import simple

    view = simple.CreateView("RenderView")
    view.ViewSize = [size, size]
    view.OrientationAxesVisibility = 0
    view.UseColorPaletteForBackground = 0
    view.Background = [0.0, 0.0, 0.0]
    if before_show:
        before_show(view)
    display = simple.Show(source, view)
    display.Representation = "AMR Single-Pass Volume"
    simple.ColorBy(display, ("CELLS", "Density"))
    q = density_quantiles(source, [0.0, 0.5, 0.9, 0.99, 1.0])
    lut = simple.GetColorTransferFunction("Density")
    lut.AutomaticRescaleRangeMode = "Never"
    # linear maps (switching to the type put this density-like array's maps in log scale)
    lut.UseLogScale = 0
    lut.RGBPoints = [q[0], 0.2, 0.4, 1.0, q[2], 1.0, 1.0, 1.0, q[4], 1.0, 0.2, 0.1]
    pwf = simple.GetOpacityTransferFunction("Density")
    pwf.UseLogScale = 0
    pwf.Points = [q[0], 0.0, 0.5, 0.0, q[1], 0.1, 0.5, 0.0, q[2], 0.5, 0.5, 0.0,
                  q[3], 0.8, 0.5, 0.0, q[4], 0.9, 0.5, 0.0]
    display.ScalarOpacityUnitDistance = 0.05
    simple.Render(view)
    view.ResetCamera()
    view.GetActiveCamera().Azimuth(30.0)
    view.GetActiveCamera().Elevation(20.0)
    return view, display, q


# Image comparisons over the pixels the volume covers (either image not black background, as
# amrsp::ImageDifference in C++): a frame's background agrees whatever the renderer does, so a
# whole-frame RMSE shrinks with the volume's share of the frame. Pixels: N x 3 arrays, 0-255.
BACKGROUND_LEVEL = 2
OFF_LEVELS = 8


def covered(a, b):
    return (a.max(axis=1) > BACKGROUND_LEVEL) | (b.max(axis=1) > BACKGROUND_LEVEL)


def coverage(pixels):
    """Share of the pixels the volume covers (any channel above BACKGROUND_LEVEL on black)."""
    return float((pixels.max(axis=1) > BACKGROUND_LEVEL).mean())


def rmse(a, b):
    """RMSE of the RGB channels (0-255) over the covered pixels; 0 when none is covered."""
    import numpy

    mask = covered(a, b)
    if not mask.any():
        return 0.0
    return float(numpy.sqrt(numpy.mean((a[mask] - b[mask]) ** 2)))


def off_share(a, b, levels=OFF_LEVELS):
    """Share (0-1) of the covered pixels whose largest channel difference exceeds `levels`."""
    mask = covered(a, b)
    if not mask.any():
        return 0.0
    return float((abs(a[mask] - b[mask]).max(axis=1) > levels).mean())


# Distributed rendering against the one-process image of the same view, over the volume's pixels:
# (RMSE bound, bound on the share differing by more than 2 levels). "regions": several pvbatch
# ranks each render their region, composited by IceT; "whole": one image of all the data drawn
# elsewhere (a pvserver with remote rendering, or rank 0 gathering every block). Measured on
# llvmpipe, the same with ParaView 5.11, 5.13 and 6.1 (2026-11-28): Enzo 2 ranks 1.08, 7.1 %;
# 4 ranks 1.32, 9.9 %; gathering and pvserver 0.50, 1.6 %; AMReX 2 and 4 ranks 3.33-3.34,
# 6.5-6.6 %, pvserver 3.32, 6.5 % (its silhouette). Bounds about 1.5x.
DISTRIBUTED_BOUNDS = {
    ("enzo", "regions"): (2.0, 0.15),
    ("enzo", "whole"): (0.8, 0.025),
    ("amrex", "regions"): (5.0, 0.10),
    ("amrex", "whole"): (5.0, 0.10),
}


def distributed_bounds(dataset, split):
    """DISTRIBUTED_BOUNDS of a dataset (its readers' variants share the bounds of the data:
    enzo-checked is enzo) and a split ("regions" or "whole")."""
    key = (dataset.split("-")[0], split)
    if key not in DISTRIBUTED_BOUNDS:
        fail("no distributed-rendering bounds for %s (%s)" % key)
    return DISTRIBUTED_BOUNDS[key]


def read_png(path):
    from vtkmodules.vtkIOImage import vtkPNGReader
    from vtkmodules.util.numpy_support import vtk_to_numpy

    reader = vtkPNGReader()
    reader.SetFileName(path)
    reader.Update()
    image = reader.GetOutput()
    dims = image.GetDimensions()
    pixels = vtk_to_numpy(image.GetPointData().GetScalars())
    return dims[0], dims[1], pixels[:, :3].astype("float64")


def x_display_answers():
    """Whether the X display named by DISPLAY answers (True when libX11 cannot be found to ask)."""
    import ctypes
    import ctypes.util

    if not os.environ.get("DISPLAY"):
        return False
    library = ctypes.util.find_library("X11")
    if not library:
        return True  # cannot probe; let VTK try
    x11 = ctypes.cdll.LoadLibrary(library)
    x11.XOpenDisplay.restype = ctypes.c_void_p
    x11.XOpenDisplay.argtypes = [ctypes.c_char_p]
    x11.XCloseDisplay.argtypes = [ctypes.c_void_p]
    display = x11.XOpenDisplay(None)
    if not display:
        return False
    x11.XCloseDisplay(display)
    return True


def require_display():
    """ParaView builds on VTK < 9.4 render through GLX only and abort the process when no X
    display answers: probe first. CTest sets AMRSP_GLX_ONLY=0 for ParaView on VTK >= 9.4, which
    renders through EGL or OSMesa when there is no X server and needs nothing here."""
    if os.environ.get("AMRSP_GLX_ONLY", "1") == "0":
        return
    if not os.environ.get("DISPLAY"):
        skip("no X display (DISPLAY is unset); start one with scripts/start-xvfb.sh")
    if not x_display_answers():
        skip("the X display %s does not answer" % os.environ["DISPLAY"])


def info_property(display, name):
    """An information-only property of the representation, fetched from where it renders."""
    display.SMProxy.UpdatePropertyInformation()
    prop = display.SMProxy.GetProperty(name)
    if prop is None:
        fail("the representation has no property %s" % name)
    return prop.GetElement(0) if prop.GetNumberOfElements() > 0 else None


# ---- pvservers this test started (ended with it; their logs reported when it fails)
SERVER = []  # the pvservers this test started (one; more after a failed start); ended with it
SERVER_LOGS = []  # their log files, in the same order


# ghost types the range information skips: duplicate, refined (under a finer level), hidden
SKIPPED_GHOSTS = 1 | 8 | 32


def end_process(process, seconds):
    """Terminates `process`, killing it when it has not ended within `seconds`."""
    process.terminate()
    try:
        process.wait(timeout=seconds)
    except subprocess.TimeoutExpired:
        process.kill()


def stop_servers():
    for server in SERVER:
        if server.poll() is None:
            end_process(server, 10)


def report_servers():
    # The end of the log of a pvserver that is gone (its exit code says whether it crashed).
    for server, path in zip(SERVER, SERVER_LOGS):
        try:
            with open(path, errors="replace") as f:
                lines = f.readlines()
        except OSError:
            continue
        if server.poll() is not None:
            print("pvserver ended with exit code %s; its log (%s) ends:\n%s"
                  % (server.returncode, path, "".join(lines[-15:])))


BEFORE_LEAVE.append(stop_servers)
BEFORE_FAIL.append(report_servers)


def run_amrsp(command):
    run = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                         universal_newlines=True)
    if run.returncode != 0:
        print(run.stdout)
        fail("%s failed (exit code %d)" % (" ".join(command[:2]), run.returncode))
    return run.stdout.strip()


def free_port():
    import socket

    with socket.socket(socket.AF_INET, socket.SOCK_STREAM) as s:
        s.bind(("localhost", 0))
        return s.getsockname()[1]


def copy_server_output(server, log_path):
    """Copies the pvserver's output into its log as it comes. VTK's X abort line (the X server
    refused the pvserver's window) is also repeated on this test's output at once, where
    RetryOnXFailure.py sees it: the client often crashes when its server aborts, before any
    report could be printed."""
    import threading

    def copy():
        with open(log_path, "a", errors="replace") as log:
            for raw in iter(server.stdout.readline, b""):
                line = raw.decode(errors="replace")
                log.write(line)
                log.flush()
                if "bad X server connection" in line:
                    sys.stdout.write("pvserver: " + line.strip() + "\n")
                    sys.stdout.flush()

    threading.Thread(target=copy, daemon=True).start()


def start_server(pvserver, log_path):
    """Starts our own pvserver on a free loopback port and connects to it."""
    from paraview import simple

    for attempt in range(3):
        port = free_port()
        open(log_path, "w").close()
        server = subprocess.Popen([pvserver, "--force-offscreen-rendering",
                                   "--server-port=%d" % port], stdout=subprocess.PIPE,
                                  stderr=subprocess.STDOUT)
        copy_server_output(server, log_path)
        SERVER.append(server)
        SERVER_LOGS.append(log_path)
        deadline = time.time() + 60.0
        while server.poll() is None and time.time() < deadline:
            with open(log_path) as f:
                if "Accepting connection" in f.read():
                    break
            time.sleep(0.1)
        if server.poll() is None:
            simple.Connect("localhost", port)
            print("client-server: connected to our pvserver on port %d (log %s)"
                  % (port, log_path))
            return server
        server.wait()
    fail("pvserver did not start (see %s)" % log_path)


def server_died(server):
    """Fails (report_servers prints the end of its log) when our pvserver is gone."""
    if server is not None and server.poll() is not None:
        fail("pvserver ended unexpectedly (exit code %s)" % server.returncode)


def stop_server(server):
    from paraview import simple

    simple.Disconnect()
    end_process(server, 30)


def clean_environment():
    """pvpython initialises MPI as a singleton and exports OpenMPI's variables (OMPI_*, PMIX_*);
    an mpiexec (or pvbatch) started with them exits at once with code 1 and no output.
    ParaView's data-movement log is switched on: the representation names each rank's region
    there."""
    env = {k: v for k, v in os.environ.items()
           if not k.startswith(("OMPI_", "PMIX_", "OPAL_", "ORTE_"))}
    env["PARAVIEW_LOG_DATA_MOVEMENT_VERBOSITY"] = "INFO"
    return env


# pvbatch on several ranks renders in parallel only while every rank passed ParaView's X display
# and OpenGL check (vtkPVRenderingCapabilitiesInformation, at view creation); one refused X
# connection on one rank (an Xvfb without -noreset refused 4 of 160 connections made 4 at a
# time: it drops connections while it resets) turns parallel rendering off on all ranks, and ParaView 5.11 then deadlocks in IceT at
# the first render (docs/paraview.md, "MPI runs and the X display check"). --disable-xdisplay-test skips
# that check: each rank opens its own window when it renders, and a refused connection there
# aborts the run with "bad X server connection", which RetryOnXFailure.py runs again.
MPI_PVBATCH_OPTIONS = ["--disable-xdisplay-test"]
# A run that takes longer than this has hung (2 and 4 ranks take 5 to 25 s here): it is killed
# and the test FAILS (no retry).
HANG_SECONDS = 150


def call_with_hang_detector(command, log):
    import signal

    process = subprocess.Popen(command, stdout=log, stderr=subprocess.STDOUT,
                               env=clean_environment(), start_new_session=True)
    try:
        return process.wait(timeout=HANG_SECONDS)
    except subprocess.TimeoutExpired:
        os.killpg(process.pid, signal.SIGKILL)
        process.wait()
        log.flush()
        with open(log.name) as f:
            tail = f.read().splitlines()[-15:]
        print("end of the log:\n" + "\n".join(tail))
        print("FAIL: %s did not finish within %d s: it hung (killed)"
              % (" ".join(command), HANG_SECONDS))
        sys.exit(1)


def array_statistics(source, name):
    """(count, minimum, maximum, smallest positive value) of the cell array `name` over every
    block of the source's vtkOverlappingAMR, skipping the cells the mapper never samples (builtin
    session: the source's own output)."""
    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy

    amr = source.GetClientSideObject().GetOutputDataObject(0)
    values = []
    for level in range(amr.GetNumberOfLevels()):
        for index in range(amr.GetNumberOfDataSets(level)):
            block = amr.GetDataSet(level, index)
            if block is None or block.GetCellData().GetArray(name) is None:
                continue
            data = vtk_to_numpy(block.GetCellData().GetArray(name)).astype("float64")
            if data.ndim > 1:
                data = data[:, 0]
            ghosts = block.GetCellData().GetArray("vtkGhostType")
            if ghosts is not None:
                data = data[(vtk_to_numpy(ghosts) & SKIPPED_GHOSTS) == 0]
            values.append(data[numpy.isfinite(data)])
    data = numpy.concatenate(values) if values else numpy.zeros(0)
    positive = data[data > 0.0]
    return (int(data.size), float(data.min()) if data.size else 0.0,
            float(data.max()) if data.size else 0.0,
            float(positive.min()) if positive.size else 0.0)
