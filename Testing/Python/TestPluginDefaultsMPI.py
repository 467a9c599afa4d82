# The density-like rule of "AMR Single-Pass Volume" under MPI (docs/paraview.md, "Defaults"): the
# smallest positive value must be that of all ranks' blocks, not rank 0's.
#
#   pvpython TestPluginDefaultsMPI.py MPIEXEC PVBATCH PLUGIN OUTDIR      (the driver)
#   pvbatch TestPluginDefaultsMPI.py --run PLUGIN                        (one run)
#
# A run opens Enzo moving7 with every array, switches a display to the type (which picks
# Dark_Matter_Density, minimum 0, and puts its maps in log scale from its smallest positive value)
# and prints the maps' range and the smallest positive value of the blocks rank 0 holds. The
# driver runs pvbatch on one rank, then on 2 ranks under MPIEXEC, and checks that both runs chose
# the same log range. It shows that the check can fail: on 2 ranks, rank 0's own smallest positive
# value differs from the global one (the blocks holding it are on rank 1), so a range not merged
# over the ranks would start elsewhere.
# Exit codes: 0 pass, 1 fail, 125 skipped (no data, no display).
import os
import re
import subprocess
import sys

HERE = os.path.dirname(os.path.abspath(__file__))
sys.path.insert(0, HERE)
ENZO = "enzo_moving7/DD0010/moving7_0010.hierarchy"
RESULT = re.compile(r"^defaults: ranks (\d+), picked (\S+), log (\d), range \[(\S+), (\S+)\], "
                    r"rank 0's smallest positive value (\S+)$", re.M)


def run_one(plugin):
    """One pvbatch run: prints the result line."""
    from PluginTestKit import array_statistics, fail, require_display, skip

    path = os.path.join(os.environ.get("AMRSP_DATA_DIR", "../shared/data"), ENZO)
    if not os.path.exists(path):
        skip("dataset not found: %s" % path)
    require_display()
    from paraview import servermanager, simple

    simple.LoadPlugin(plugin, remote=False, ns=globals())
    ranks = servermanager.ActiveConnection.GetNumberOfDataPartitions()
    reader = simple.EnzoReader(FileNames=[path])
    reader.Level = 30
    reader.CellArrayStatus = reader.CellArrayStatus.Available
    reader.UpdatePipeline()
    view = simple.CreateView("RenderView")
    display = simple.Show(reader, view)
    display.Representation = "AMR Single-Pass Volume"
    name = display.ColorArrayName[1]
    if not name:
        fail("no array was picked")
    lut = simple.GetColorTransferFunction(name)
    xs = list(lut.RGBPoints)[0::4]
    # rank 0's own blocks (pvbatch: the script runs on rank 0)
    local = array_statistics(reader, name)
    print("defaults: ranks %d, picked %s, log %d, range [%.9g, %.9g], rank 0's smallest positive "
          "value %.9g" % (ranks, name, lut.UseLogScale, min(xs), max(xs), local[3]))
    print("PASS")


def driver(mpiexec, pvbatch, plugin, outdir):
    from PluginTestKit import MPI_PVBATCH_OPTIONS, SKIP, call_with_hang_detector

    os.makedirs(outdir, exist_ok=True)
    script = [os.path.abspath(__file__), "--run", plugin]
    serial_command = [pvbatch, "--force-offscreen-rendering"] + script
    mpi = [mpiexec, "-np", "2"]
    if os.geteuid() == 0:
        mpi.append("--allow-run-as-root")  # OpenMPI refuses root without it
    mpi.append("--oversubscribe")
    mpi_command = mpi + [pvbatch, "--force-offscreen-rendering"] + MPI_PVBATCH_OPTIONS + script
    results = []
    for label, command in (("serial", serial_command), ("mpi2", mpi_command)):
        log_path = os.path.join(outdir, "defaults-%s.log" % label)
        with open(log_path, "w") as log:
            code = call_with_hang_detector(command, log)
        with open(log_path, errors="replace") as f:
            text = f.read()
        if "SKIPPED:" in text:
            if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
                print("FAIL: a run was skipped although AMRSP_REQUIRE_GPU=1 (log %s)" % log_path)
                return 1
            print("SKIPPED: a run was skipped (log %s)" % log_path)
            return SKIP
        match = RESULT.search(text)
        if code != 0 or not match or "\nPASS" not in text:
            print("\n".join(l for l in text.splitlines() if "X server" in l))
            print("end of the log:\n" + "\n".join(text.splitlines()[-15:]))
            print("FAIL: the %s run failed with exit code %d (log %s)" % (label, code, log_path))
            return 1
        print("%s: %s" % (label, match.group(0)))
        results.append(match)
    serial, parallel = results
    if int(parallel.group(1)) != 2:
        print("FAIL: the MPI run had %s ranks, not 2" % parallel.group(1))
        return 1
    if serial.group(2, 3) != parallel.group(2, 3) or serial.group(3) != "1":
        print("FAIL: the runs picked %s (log %s) and %s (log %s)"
              % (serial.group(2), serial.group(3), parallel.group(2), parallel.group(3)))
        return 1
    lo, hi = float(serial.group(4)), float(serial.group(5))
    lo2, hi2 = float(parallel.group(4)), float(parallel.group(5))
    if abs(lo2 - lo) > 1e-6 * lo or abs(hi2 - hi) > 1e-6 * hi:
        print("FAIL: 2 ranks chose the log range [%g, %g], one rank [%g, %g]" % (lo2, hi2, lo, hi))
        return 1
    if abs(float(serial.group(6)) - lo) > 1e-6 * lo:
        print("FAIL: on one rank the range starts at %g, the data's smallest positive value is %s"
              % (lo, serial.group(6)))
        return 1
    rank0 = float(parallel.group(6))
    rejected = abs(rank0 - lo) > 1e-6 * lo
    print("rank 0 alone holds %.6g as its smallest positive value, all ranks %.6g: a range from "
          "rank 0's blocks alone would be %s" % (rank0, lo, "rejected" if rejected
                                                 else "NOT DISTINGUISHED (same value)"))
    if not rejected:
        print("FAIL: the data no longer shows whether the ranks' values are merged")
        return 1
    print("PASS")
    return 0


def main():
    if sys.argv[1:2] == ["--run"] and len(sys.argv) == 3:
        run_one(sys.argv[2])
        return 0
    if len(sys.argv) != 5:
        print("usage: TestPluginDefaultsMPI.py MPIEXEC PVBATCH PLUGIN OUTDIR")
        return 2
    return driver(*sys.argv[1:5])


if __name__ == "__main__":
    code = main()
    # a run that passes returns from the script: pvbatch then finalises MPI on every rank
    if sys.argv[1:2] != ["--run"]:
        sys.exit(code)
