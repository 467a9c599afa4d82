# What the plugin's Checked AMR Reader costs against ParaView's own reader of the same files
# (docs/paraview.md, "Opening files: the Checked AMR Reader"):
#
#   pvpython paraview_checked_reader_cost.py PLUGIN DATA_DIR [REPEATS [FOLDER]]
#
# Reads enzo_moving7 and amrex_plt1_Y REPEATS times (default 10) with every level and cell array,
# and with FOLDER also the plugin's synthetic cosmology (2,666 grids, 4 M cells) written there as
# .vthb (27 MB; XMLUniformGridAMRReader as ParaView's reader):
# ParaView's own reader, the checked reader (VTK's reader in a child process) and the checked
# reader in this process (ReadInChildProcess off: the header checks alone on top). Prints the
# median seconds per read and the ratios to ParaView's reader.
import os
import statistics
import sys
import time

from paraview import simple


def median_read_seconds(make_reader, repeats):
    """Median seconds of UpdatePipeline on a new reader proxy (a reader reads once)."""
    seconds = []
    for _ in range(repeats):
        reader = make_reader()
        start = time.perf_counter()
        reader.UpdatePipeline()
        seconds.append(time.perf_counter() - start)
        simple.Delete(reader)
    return statistics.median(seconds)


def main():
    plugin, data = sys.argv[1:3]
    repeats = int(sys.argv[3]) if len(sys.argv) > 3 else 10
    simple.LoadPlugin(plugin, remote=False, ns=globals())
    cases = [
        ("enzo_moving7", os.path.join(data, "enzo_moving7/DD0010/moving7_0010.hierarchy"),
         "EnzoReader", os.path.join(data, "enzo_moving7/DD0010/moving7_0010.hierarchy")),
        ("amrex_plt1_Y", os.path.join(data, "amrex_plt1_Y"), "AMReXBoxLibGridReader",
         os.path.join(data, "amrex_plt1_Y", "Header")),
    ]
    if len(sys.argv) > 4:
        cosmo = os.path.join(sys.argv[4], "cosmo.vthb")
        if not os.path.exists(cosmo):
            source = AMRCosmologysynthetic(NumberOfGrids=2666, NumberOfLevels=4,  # noqa: F821
                                           NumberOfCells=4000000, Seed=1)
            simple.SaveData(cosmo, proxy=source)
            simple.Delete(source)
        cases.append(("cosmo 2666 grids", cosmo, "XMLUniformGridAMRReader", cosmo))
    for name, own_path, own_reader, checked_path in cases:
        def own():
            if own_reader == "XMLUniformGridAMRReader":
                reader = simple.XMLUniformGridAMRReader(FileName=own_path)
                reader.DefaultNumberOfLevels = 0  # every level
                return reader
            reader = getattr(simple, own_reader)(FileNames=[own_path])
            reader.Level = 100
            reader.CellArrayStatus = reader.CellArrayStatus.Available
            return reader

        t_own = median_read_seconds(own, repeats)
        t_checked = median_read_seconds(
            lambda: CheckedAMRReader(FileNames=[checked_path]), repeats)  # noqa: F821
        t_in = median_read_seconds(
            lambda: CheckedAMRReader(FileNames=[checked_path], ReadInChildProcess=0),  # noqa: F821
            repeats)
        print("%s: ParaView's %s %.4f s, checked (child) %.4f s (%.2fx), checked in process "
              "%.4f s (%.2fx); median of %d reads" % (name, own_reader, t_own, t_checked,
                                                     t_checked / t_own, t_in, t_in / t_own,
                                                     repeats))


if __name__ == "__main__":
    main()
