# pvpython test of the plugin's "Checked AMR Reader" (vtkSinglePassAMRCheckedReader wrapped in
# ParaView's file series):
#
#   pvpython --force-offscreen-rendering TestPluginCheckedReader.py PLUGIN OUTDIR
#
# AMRSP_DATA_DIR names ../shared/data. The test writes, into OUTDIR, Enzo dumps made from
# enzo_moving7 (links to its files; the hierarchy and parameter file edited): "deep" (all 10 grids
# on 8 levels) and "shallow" (without grid 10: 7 levels, 9 grids), each at time 0.5 and at the
# data's own time 0.8175..., and three damaged copies of moving7. Checks:
# - a series whose levels change (deep then shallow, and shallow then deep) plays: its times are
#   the dumps' own, and every step, forwards and back, has the levels and grids of its own
#   hierarchy (counted from its "Grid = " entries) and the values of a fresh vtkAMREnzoReader of
#   that file alone; the process's open descriptors do not grow over 12 step changes (VTK's Enzo
#   reader leaks two per read: here they end with the reading child);
# - OpenDataFile still picks ParaView's own readers for .hierarchy and .vthb files;
# - the AMReX plotfile (opened through its Header) and the VTK XML AMR sample read as VTK's own
#   readers of the same files read them (levels, blocks, every cell array, an array's sum), with
#   the AMReX Header's time;
# - with AMRSP_REPORT_OWN_READER=1, ParaView's own EnzoReader on the same deep-then-shallow series,
#   in a separate pvpython, is reported (ParaView 5.11: SIGABRT) - not judged, as ParaView's
#   readers are not ours, and so not run by default;
# - damaged files (a NaN grid edge, on which VTK's reader loops; a grid whose start index is past
#   its end, on which it aborts; a truncated grid file) end in an empty output and one error that
#   names the file and the problem, and the same reader reads a good file next;
# - with the checks off (AMRSP_SKIP_FILE_CHECKS=1) the reading child still keeps ParaView alive:
#   the abort becomes "crashed inside VTK's reader (SIGABRT...", the loop "did not finish within
#   3 s"; and the same abort read in pvpython's own process (ReadInChildProcess off, in a separate
#   pvpython) kills that process by a signal: the isolation is what the check rests on;
# - the shallow step shown as "AMR Single-Pass Volume" gives the image of the same dump read by
#   ParaView's own EnzoReader alone (RMSE below 0.5 over the covered pixels).
# Exit codes: 0 pass, 1 fail, 125 skipped (no X display or no usable OpenGL context).
import os
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import fail, leave, show_density_volume, skip  # noqa: E402

ENZO = os.path.join("enzo_moving7", "DD0010")
STEM = "moving7_0010"
DATA_TIME = 0.81751317119117  # moving7's own InitialTime
EARLY_TIME = 0.5
# the image of the checked reader's dump against ParaView's own reader's (identical data and
# pipeline: measured 0.0)
SAME_DATA_RMSE = 0.5


def link_dump(source, target, hierarchy_edit=None, time=None):
    """A copy of the Enzo dump `source` in `target`: links to its files, the hierarchy passed
    through `hierarchy_edit` and the parameter file's InitialTime set to `time` when given."""
    os.makedirs(target, exist_ok=True)
    for name in os.listdir(source):
        os.symlink(os.path.join(source, name), os.path.join(target, name))
    if hierarchy_edit:
        path = os.path.join(target, STEM + ".hierarchy")
        text = open(os.path.join(source, STEM + ".hierarchy")).read()
        os.remove(path)
        open(path, "w").write(hierarchy_edit(text))
    if time is not None:
        path = os.path.join(target, STEM)
        lines = open(os.path.join(source, STEM)).read().splitlines(True)
        os.remove(path)
        open(path, "w").write("".join(
            "InitialTime         = %r\n" % time if line.startswith("InitialTime ") else line
            for line in lines))
    return os.path.join(target, STEM + ".hierarchy")


def without_grid_10(text):
    """moving7's hierarchy without its finest grid (grid 10, the only one on level 8)."""
    start = text.index("Grid = 10\n")
    end_marker = "Pointer: Grid[10]->NextGridNextLevel = 0\n"
    end = text.index(end_marker) + len(end_marker)
    text = text[:start] + text[end:]
    return text.replace("Pointer: Grid[9]->NextGridNextLevel = 10",
                        "Pointer: Grid[9]->NextGridNextLevel = 0")


def replace_once(old, new):
    def edit(text):
        if old not in text:
            fail("moving7's hierarchy lacks %r: the damaged copy would be undamaged" % old)
        return text.replace(old, new, 1)
    return edit


def grids_listed(hierarchy):
    return sum(1 for line in open(hierarchy) if line.startswith("Grid = "))


def open_descriptors():
    return len(os.listdir("/proc/self/fd"))


def run_pvpython(*args):
    """A separate pvpython running this script in a child mode; (exit code, output)."""
    command = [os.environ.get("AMRSP_PVPYTHON", "pvpython"), "--force-offscreen-rendering",
               os.path.abspath(__file__)] + list(args)
    done = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                          timeout=120, env=dict(os.environ, AMRSP_SKIP_FILE_CHECKS="1"))
    return done.returncode, done.stdout.decode("utf-8", "replace")


def own_reader_series(files):
    """Child mode: ParaView's own EnzoReader on `files` as one series; prints each step's levels."""
    from paraview import simple

    reader = simple.EnzoReader(FileNames=files)
    reader.Level = 100
    for t in reader.TimestepValues:
        reader.UpdatePipeline(t)
        amr = reader.GetClientSideObject().GetOutputDataObject(0)
        print("OWN step %g: %d levels, %d blocks" % (t, amr.GetNumberOfLevels(),
                                                     amr.GetTotalNumberOfBlocks()))
    leave(0)


def unchecked_in_process(plugin, path):
    """Child mode: the checked reader with its checks skipped and VTK's reader in this process."""
    from paraview import simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    reader = CheckedAMRReader(FileNames=[path], ReadInChildProcess=0,  # noqa: F821
                              ConvertToCGS=1)
    reader.UpdatePipeline()
    print("IN-PROCESS read returned")
    leave(0)


def save_density_image(source, png):
    """`source` as "AMR Single-Pass Volume" in a new 120x120 view (PluginTestKit's maps), to
    `png`."""
    from paraview import simple

    view, display, q = show_density_volume(source, 120)
    simple.SaveScreenshot(png, view, ImageResolution=[120, 120])


def own_reader_image(plugin, path, png):
    """Child mode: the dump read by ParaView's own EnzoReader alone, shown and saved as the
    checked reader's output is."""
    from paraview import simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    reader = simple.EnzoReader(FileNames=[path])
    reader.Level = 100
    reader.CellArrayStatus = reader.CellArrayStatus.Available
    save_density_image(reader, png)
    leave(0)


def direct_read(path, cgs=False):
    """A fresh vtkAMREnzoReader of one file: every level and cell array, in code units as
    ParaView's Enzo reader and the checked reader give them by default (or CGS)."""
    from vtkmodules.vtkIOAMR import vtkAMREnzoReader

    reader = vtkAMREnzoReader()
    reader.SetConvertToCGS(1 if cgs else 0)
    reader.SetFileName(path)
    reader.SetMaxLevel(1000)
    reader.UpdateInformation()
    for i in range(reader.GetNumberOfCellArrays()):
        reader.SetCellArrayStatus(reader.GetCellArrayName(i), 1)
    reader.Update()
    return reader.GetOutput()


def block_of(amr, level, index):
    """Block `index` of `level` as image data (VTK 9.6's GetDataSet answers vtkUniformGrid only)."""
    if hasattr(amr, "GetDataSetAsImageData"):
        return amr.GetDataSetAsImageData(level, index)
    return amr.GetDataSet(level, index)


def summary(amr, array="Density"):
    """(levels, blocks, sum of `array` over the blocks) of a vtkOverlappingAMR."""
    from vtkmodules.util.numpy_support import vtk_to_numpy

    total = 0.0
    for level in range(amr.GetNumberOfLevels()):
        for index in range(amr.GetNumberOfDataSets(level)):
            block = block_of(amr, level, index)
            if block is not None:
                total += float(vtk_to_numpy(block.GetCellData().GetArray(array)).sum())
    return amr.GetNumberOfLevels(), amr.GetTotalNumberOfBlocks(), total


def other_formats(data):
    """The AMReX plotfile (through its Header) and the VTK XML AMR sample read by the checked
    reader: the levels, blocks, an array's sum and every cell array as VTK's own reader of the
    same files gives them; the AMReX time from its Header."""
    from paraview import simple
    from vtkmodules.vtkIOAMR import vtkAMReXGridReader
    from vtkmodules.vtkIOXML import vtkXMLUniformGridAMRReader

    amrex = vtkAMReXGridReader()
    amrex.SetFileName(os.path.join(data, "amrex_plt1_Y"))
    amrex.SetMaxLevel(1000)
    amrex.UpdateInformation()
    for i in range(amrex.GetNumberOfCellArrays()):
        amrex.SetCellArrayStatus(amrex.GetCellArrayName(i), 1)
    xml = vtkXMLUniformGridAMRReader()
    xml.SetFileName(os.path.join(data, "vthb_hierarchicalbox", "HierarchicalBoxDataset.v1.1.vthb"))
    xml.SetMaximumLevelsToReadByDefault(0)
    header = open(os.path.join(data, "amrex_plt1_Y", "Header")).read().split("\n")
    amrex_time = float(header[2 + int(header[1]) + 1])
    for name, path, vtk_reader, array, time in (
            ("AMReX", os.path.join(data, "amrex_plt1_Y", "Header"), amrex, "Y(H2)", amrex_time),
            ("VTK XML", xml.GetFileName(), xml, None, None)):
        vtk_reader.Update()
        want_amr = vtk_reader.GetOutputDataObject(0)
        first = block_of(want_amr, 0, 0).GetCellData()
        array = array or first.GetArrayName(0)
        reader = CheckedAMRReader(FileNames=[path])  # noqa: F821
        reader.UpdatePipeline()
        got_amr = reader.GetClientSideObject().GetOutputDataObject(0)
        got, want = summary(got_amr, array), summary(want_amr, array)
        got_first = block_of(got_amr, 0, 0).GetCellData()
        arrays = sorted(got_first.GetArrayName(i) for i in range(got_first.GetNumberOfArrays()))
        want_arrays = sorted(first.GetArrayName(i) for i in range(first.GetNumberOfArrays()))
        times = list(reader.TimestepValues)
        print("%s: %s (levels, blocks, %s sum), arrays %s, times %s" % (name, got, array,
                                                                          arrays, times))
        if got[:2] != want[:2] or abs(got[2] - want[2]) > 1e-9 * abs(want[2]) or \
                arrays != want_arrays:
            fail("%s through the checked reader: %s and arrays %s; VTK's reader: %s and %s"
                 % (name, got, arrays, want, want_arrays))
        if time is not None and (len(times) != 1 or abs(times[0] - time) > 1e-9 * abs(time)):
            fail("%s: the checked reader's time is %s, the Header says %r" % (name, times, time))
        simple.Delete(reader)


def last_error(reader):
    reader.UpdatePropertyInformation()
    return reader.GetProperty("LastError").GetData()


def main():
    if len(sys.argv) > 1 and sys.argv[1] == "--own-reader-series":
        own_reader_series(sys.argv[2:])
    if len(sys.argv) > 1 and sys.argv[1] == "--own-reader-image":
        own_reader_image(*sys.argv[2:5])
    if len(sys.argv) > 1 and sys.argv[1] == "--unchecked-in-process":
        unchecked_in_process(sys.argv[2], sys.argv[3])
    plugin, outdir = sys.argv[1:3]
    data = os.environ.get("AMRSP_DATA_DIR", "")
    source = os.path.join(data, ENZO)
    if not os.path.isfile(os.path.join(source, STEM + ".hierarchy")):
        skip("the Enzo sample %s is missing (AMRSP_DATA_DIR=%r)" % (source, data))
    from PluginTestKit import coverage, read_png, require_display, rmse

    require_display()
    shutil.rmtree(outdir, ignore_errors=True)
    os.makedirs(outdir)
    from paraview import simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    # series A: deep at time 0.5, shallow at 0.8175; series B: shallow first (0.5), then deep
    deep = link_dump(source, os.path.join(outdir, "deep"), time=EARLY_TIME)
    shallow = link_dump(source, os.path.join(outdir, "shallow"), without_grid_10)
    early_shallow = link_dump(source, os.path.join(outdir, "early-shallow"), without_grid_10,
                              EARLY_TIME)
    late_deep = link_dump(source, os.path.join(outdir, "late-deep"))
    expected = {}
    for path in (deep, shallow, early_shallow, late_deep):
        expected[path] = summary(direct_read(path))
        if expected[path][1] != grids_listed(path):
            fail("VTK's reader reads %d grids from %s, its hierarchy lists %d"
                 % (expected[path][1], path, grids_listed(path)))
    print("deep: %d levels, %d grids; shallow: %d levels, %d grids" % (
        expected[deep][0], expected[deep][1], expected[shallow][0], expected[shallow][1]))
    if expected[deep][0] != expected[shallow][0] + 1:
        fail("the two dumps do not differ by a level: the series would not test level changes")

    # 1. series whose levels change, in both orders (a series is ordered by its dumps' times)
    for name, files in (("deep-then-shallow", [deep, shallow]),
                        ("shallow-then-deep", [early_shallow, late_deep])):
        reader = CheckedAMRReader(FileNames=files)  # noqa: F821
        times = list(reader.TimestepValues)
        if len(times) != 2 or abs(times[0] - EARLY_TIME) > 1e-12 or \
                abs(times[1] - DATA_TIME) > 1e-12:
            fail("the series' times are %s, the dumps say %s" % (times, [EARLY_TIME, DATA_TIME]))
        descriptors = None
        for change in range(12):
            step = change % 2
            reader.UpdatePipeline(times[step])
            got = summary(reader.GetClientSideObject().GetOutputDataObject(0))
            want = expected[files[step]]
            if got[:2] != want[:2] or abs(got[2] - want[2]) > 1e-9 * abs(want[2]):
                fail("%s step %d (%s) read as %s (levels, grids, Density sum); the file alone: %s"
                     % (name, step, files[step], got, want))
            if change == 1:
                descriptors = open_descriptors()
        if open_descriptors() > descriptors:
            fail("open descriptors grew from %d to %d over 10 step changes"
                 % (descriptors, open_descriptors()))
        print("series %s: times %s, levels %d then %d, 12 step changes, every step as its file "
              "alone, %d descriptors throughout" % (name, times, expected[files[0]][0],
                                                   expected[files[1]][0], descriptors))
        simple.Delete(reader)

    if os.environ.get("AMRSP_REPORT_OWN_READER") == "1":
        # a report on ParaView's reader, judged by nothing (its readers are not ours)
        rc, output = run_pvpython("--own-reader-series", deep, shallow)
        said = [line for line in output.splitlines() if line.startswith("OWN")]
        print("ParaView's own EnzoReader on the deep-shallow series: %s%s" % (
            "exit code %d" % rc if rc >= 0 else "killed by signal %d" % -rc,
            "; " + "; ".join(said) if said else ""))

    other_formats(data)

    # ConvertToCGS: off by default (ParaView's Enzo reader's units), on as VTK's reader's default
    reader = CheckedAMRReader(FileNames=[deep], ConvertToCGS=1)  # noqa: F821
    reader.UpdatePipeline()
    got = summary(reader.GetClientSideObject().GetOutputDataObject(0))
    want = summary(direct_read(deep, cgs=True))
    print("ConvertToCGS on: Density sum %g (VTK's reader in CGS: %g; in code units: %g)"
          % (got[2], want[2], expected[deep][2]))
    if abs(got[2] - want[2]) > 1e-9 * abs(want[2]) or abs(got[2] - expected[deep][2]) < \
            1e-3 * abs(expected[deep][2]):
        fail("ConvertToCGS on gave a Density sum of %g, VTK's reader in CGS %g" % (got[2], want[2]))
    simple.Delete(reader)

    # loading the plugin leaves the reader File > Open and OpenDataFile pick as it was
    for path in (deep, os.path.join(data, "vthb_hierarchicalbox",
                                    "HierarchicalBoxDataset.v1.1.vthb")):
        opened = simple.OpenDataFile(path)
        if opened is None or opened.GetXMLName() == "CheckedAMRReader":
            fail("OpenDataFile(%s) gave %s: the plugin took over ParaView's reader choice"
                 % (path, opened.GetXMLName() if opened else None))
        print("OpenDataFile(%s): %s" % (os.path.basename(path), opened.GetXMLName()))
        simple.Delete(opened)

    # 2. damaged files: one error naming the file, an empty output, the reader usable after
    damaged = {
        "nan-edge": (replace_once("GridLeftEdge      = 0.1875 0.1875 0.1875",
                                  "GridLeftEdge      = nan 0.1875 0.1875"), "GridLeftEdge"),
        "start-past-end": (replace_once("GridStartIndex    = 3 3 3 \nGridEndIndex      = 12 12 12",
                                        "GridStartIndex    = 13 3 3 \nGridEndIndex      = 12 12 12"),
                           "GridStartIndex"),
    }
    cases = {}
    for name, (edit, field) in damaged.items():
        cases[name] = (link_dump(source, os.path.join(outdir, name), edit), field)
    truncated = link_dump(source, os.path.join(outdir, "truncated-grid-file"))
    grid_file = os.path.join(os.path.dirname(truncated), STEM + ".cpu0000")
    whole = open(grid_file, "rb").read()
    os.remove(grid_file)
    open(grid_file, "wb").write(whole[:len(whole) // 2])
    cases["truncated-grid-file"] = (truncated, "truncated")
    reader = CheckedAMRReader(FileNames=[shallow])  # noqa: F821
    for name, (path, field) in sorted(cases.items()):
        reader.FileNames = [path]
        reader.UpdatePipeline()
        amr = reader.GetClientSideObject().GetOutputDataObject(0)
        message = last_error(reader)
        print("%s: %s" % (name, message))
        if amr.GetTotalNumberOfBlocks() != 0:
            fail("%s: the damaged dump gave %d blocks" % (name, amr.GetTotalNumberOfBlocks()))
        if os.path.dirname(path) not in message or field not in message or "\n" in message:
            fail("%s: the error does not name the file and %s in one line: %r"
                 % (name, field, message))
        reader.FileNames = [shallow]
        reader.UpdatePipeline()
        if summary(reader.GetClientSideObject().GetOutputDataObject(0))[:2] != expected[shallow][:2]:
            fail("after %s the reader no longer reads a good dump" % name)

    # 3. the checks off: the reading child still keeps this process alive
    os.environ["AMRSP_SKIP_FILE_CHECKS"] = "1"
    reader.ConvertToCGS = 1  # VTK's reader aborts on start-past-end while converting to CGS
    # the abort's message carries the assertion's text, which names VTK's Enzo reader; the loop
    # is ended by the watchdog (1 s: the reader spins a core until then)
    for name, timeout, wants in (("start-past-end", 120, ("crashed inside VTK's reader (SIGABRT",
                                                          "vtkAMREnzoReader")),
                                 ("nan-edge", 1, ("did not finish within 1 s",))):
        reader.ReadTimeout = timeout
        reader.FileNames = [cases[name][0]]
        reader.UpdatePipeline()
        message = last_error(reader)
        print("%s, unchecked: %s" % (name, message))
        if any(want not in message for want in wants) or \
                reader.GetClientSideObject().GetOutputDataObject(0).GetTotalNumberOfBlocks() != 0:
            fail("%s with the checks off: expected %s, got %r" % (name, wants, message))
    del os.environ["AMRSP_SKIP_FILE_CHECKS"]
    reader.ReadTimeout = 120
    reader.ConvertToCGS = 0
    rc, output = run_pvpython("--unchecked-in-process", plugin, cases["start-past-end"][0])
    print("start-past-end, unchecked, in pvpython's own process: %s" % (
        "killed by signal %d" % -rc if rc < 0 else "exit code %d" % rc))
    if rc >= 0 and rc != 134:
        fail("VTK's reader in pvpython's own process survived the start-past-end dump (exit code "
             "%d): the isolation check above proves nothing\n%s" % (rc, output[-2000:]))

    # 4. the shallow dump through the representation, against ParaView's own reader of it alone
    # (each the first view of its own process: the maps are made for the source shown)
    reader.FileNames = [shallow]
    checked_png = os.path.join(outdir, "checked.png")
    save_density_image(reader, checked_png)
    own_png = os.path.join(outdir, "own.png")
    rc, output = run_pvpython("--own-reader-image", plugin, shallow, own_png)
    if rc != 0 or not os.path.isfile(own_png):
        fail("ParaView's own reader's image of %s failed (exit code %d)\n%s"
             % (shallow, rc, output[-2000:]))
    images = [read_png(checked_png)[2], read_png(own_png)[2]]
    share = coverage(images[0])
    difference = rmse(images[0], images[1])
    print("image of the shallow dump: %.1f %% covered, RMSE %.3f against ParaView's own reader"
          % (100 * share, difference))
    if share < 0.05 or difference > SAME_DATA_RMSE:
        fail("the checked reader's image covers %.1f %% and differs by RMSE %.3f from ParaView's "
             "own reader's (bound %.1f)" % (100 * share, difference, SAME_DATA_RMSE))
    print("PASS")


if __name__ == "__main__":
    main()
