# MPI-parallel test of the "AMR Single-Pass Volume" representation in pvbatch.
#
#   pvpython TestPluginParallel.py MPIEXEC PVBATCH RANKS PLUGIN AMRSP DATASET OUTDIR [regions|gather]
#       [--serial-from DIR]
#
# Runs TestPluginRepresentation.py (same dataset, camera, colour map and checks, including the
# CPU reference) twice: in pvbatch on one rank, then under `MPIEXEC -np RANKS pvbatch`, where
# each rank reads only some of the blocks. With RANKS 1 only the one-rank run (ctest's fixture
# Plugin.MPI.np1.DATASET); with --serial-from DIR the one-rank run's screenshot is DIR's, which
# must be newer than PLUGIN and AMRSP (the parallel runs of one dataset share that run). With `regions` (the default, the representation's
# default ParallelMode) every rank receives and renders its own box of the domain; the log of
# that run must show one region per rank, each with blocks, tiling the domain. With `gather`,
# rank 0 receives every block and renders alone. Then compares the two screenshots: the
# parallel one must equal the serial one within the bounds below.
# Exit codes: 0 pass, 1 fail, 125 skipped (a run skipped: no display, no data).
import glob
import os
import re
import sys

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
from PluginTestKit import (MPI_PVBATCH_OPTIONS, SKIP, call_with_hang_detector,  # noqa: E402
                           clean_environment, distributed_bounds, fixture_problem,
                           off_share, pop_option, rmse as kit_rmse)

# The parallel image is the ranks' region images composited by IceT in visibility order (or,
# gathering, rank 0's image over the others' empty ones). Pixels on the volume's silhouette
# differ, as they do when a pvserver renders (Plugin.ClientServer.remote.*), and with regions
# the samples along a ray restart at each region face (a shift below one sample step).
# The bounds per dataset and split, with what was measured: PluginTestKit.DISTRIBUTED_BOUNDS.
HERE = os.path.dirname(os.path.abspath(__file__))


REGION_LINE = re.compile(r"AMR single-pass: rank (\d+) renders region \[(\S+), (\S+)\] x "
                         r"\[(\S+), (\S+)\] x \[(\S+), (\S+)\]: (\d+) blocks, "
                         r"(\d+) cells")


# Each rank's stderr (ParaView's log, where the representation names its region) goes to a file
# of its own, LOG.rankN: ranks writing one shared stream interleave the pieces of their log lines
# (seen with ParaView 5.13, whose logger writes a line in several parts).
RANK_STDERR = 'exec "$@" 2>>"$0.rank${OMPI_COMM_WORLD_RANK:-${PMI_RANK:-unknown}}"'


def read_log_and_rank_logs(log_path):
    import glob

    parts = []
    for path in [log_path] + sorted(glob.glob(log_path + ".rank*")):
        with open(path, errors="replace") as f:
            parts.append(f.read())
    return "\n".join(parts)


def check_regions(log_path, ranks, mode):
    """The ranks' regions from the representation's log lines: one per rank, each holding
    blocks, disjoint and filling their bounding box (regions mode); none when gathering."""
    text = read_log_and_rank_logs(log_path)
    if "cannot split the AMR hierarchy" in text:
        print("FAIL: the representation could not split the hierarchy into regions (log %s)"
              % log_path)
        sys.exit(1)
    regions = {}
    for match in REGION_LINE.finditer(text):
        rank = int(match.group(1))
        box = [float(match.group(i)) for i in range(2, 8)]
        regions[rank] = (box, int(match.group(8)))
        print("rank %d: region %s, %d blocks, %s cells" % (rank, box, regions[rank][1],
                                                           match.group(9)))
    if mode == "gather":
        if regions:
            print("FAIL: ranks rendered their own regions although ParallelMode is gather")
            sys.exit(1)
        return
    if sorted(regions) != list(range(ranks)):
        print("FAIL: expected one region for each of the %d ranks, found ranks %s (log %s)"
              % (ranks, sorted(regions), log_path))
        sys.exit(1)
    boxes = [box for box, blocks in regions.values()]
    if any(blocks == 0 for box, blocks in regions.values()):
        print("FAIL: a rank's region holds no block")
        sys.exit(1)

    def volume(b):
        return max(0.0, b[1] - b[0]) * max(0.0, b[3] - b[2]) * max(0.0, b[5] - b[4])

    union = [min(b[0] for b in boxes), max(b[1] for b in boxes), min(b[2] for b in boxes),
             max(b[3] for b in boxes), min(b[4] for b in boxes), max(b[5] for b in boxes)]
    overlap = sum(volume([max(a[0], b[0]), min(a[1], b[1]), max(a[2], b[2]), min(a[3], b[3]),
                          max(a[4], b[4]), min(a[5], b[5])])
                  for i, a in enumerate(boxes) for b in boxes[i + 1:])
    covered = sum(volume(b) for b in boxes)
    if overlap > 1e-9 * volume(union) or abs(covered - volume(union)) > 1e-9 * volume(union):
        print("FAIL: the regions do not tile their bounding box (overlap %g, covered %g of %g)"
              % (overlap, covered, volume(union)))
        sys.exit(1)


def run(command, log_path):
    with open(log_path, "w") as log:
        code = call_with_hang_detector(command, log)
    text = read_log_and_rank_logs(log_path)
    lines = [l for l in text.splitlines()
             if l.startswith(("parallel:", "texture builds", "block copies", "rmse", "screenshot",
                              "render window:", "SKIPPED", "FAIL", "PASS"))]
    print("$ %s\n  %s" % (" ".join(command), "\n  ".join(lines)))
    if "SKIPPED:" in text:
        if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
            print("FAIL: a run was skipped although AMRSP_REQUIRE_GPU=1 (log %s)" % log_path)
            sys.exit(1)
        print("SKIPPED: a run was skipped (log %s)" % log_path)
        sys.exit(SKIP)
    if "render window:" not in text:
        print("FAIL: the run did not say which window it rendered through (log %s)" % log_path)
        sys.exit(1)
    if code != 0 or "\nPASS" not in text:
        # the X server's refusals are repeated for RetryOnXFailure.py
        print("\n".join(l for l in text.splitlines() if "X server" in l or "open display" in l))
        print("end of the log:\n" + "\n".join(text.splitlines()[-15:]))
        print("FAIL: the run failed with exit code %d (log %s)" % (code, log_path))
        sys.exit(1)


def main():
    args = sys.argv[1:]
    serial_from = pop_option(args, "--serial-from")
    if len(args) not in (7, 8) or args[7:] not in ([], ["regions"], ["gather"]):
        print("usage: TestPluginParallel.py MPIEXEC PVBATCH RANKS PLUGIN AMRSP DATASET OUTDIR "
              "[regions|gather] [--serial-from DIR]")
        return 2
    mpiexec, pvbatch, ranks, plugin, amrsp, dataset, outdir = args[:7]
    mode = args[7] if len(args) == 8 else "regions"
    os.makedirs(outdir, exist_ok=True)
    script = [os.path.join(HERE, "TestPluginRepresentation.py"), plugin, amrsp, dataset, outdir]
    pvbatch_args = [pvbatch, "--force-offscreen-rendering"]
    serial_png = os.path.join(serial_from or outdir, "%s-builtin-paraview.png" % dataset)
    if serial_from is None:
        if os.path.exists(serial_png):
            os.remove(serial_png)
        run(pvbatch_args + script, os.path.join(outdir, "%s-serial.log" % dataset))
        if ranks == "1":
            print("PASS")
            return 0
    else:
        # the shared one-rank run must come from these binaries (ctest runs the fixture first)
        problem = fixture_problem([serial_png], [plugin, amrsp], outdir)
        if problem:
            print("FAIL: the one-rank screenshot: %s (run Plugin.MPI.np1.%s first)"
                  % (problem, dataset))
            return 1
        print("one-rank run: %s (the fixture Plugin.MPI.np1.%s)" % (serial_png, dataset))
    mpi = [mpiexec, "-np", ranks]
    if os.geteuid() == 0:
        mpi.append("--allow-run-as-root")  # OpenMPI refuses root without it
    mpi.append("--oversubscribe")  # more ranks than cores on small machines
    mpi_log = os.path.join(outdir, "%s-mpi%s.log" % (dataset, ranks))
    for stale in glob.glob(mpi_log + ".rank*"):
        os.remove(stale)
    mpi += ["sh", "-c", RANK_STDERR, mpi_log]
    run(mpi + pvbatch_args + MPI_PVBATCH_OPTIONS + script + ["--parallel-mode", mode], mpi_log)
    check_regions(mpi_log, int(ranks), mode)

    import numpy
    from vtkmodules.util.numpy_support import vtk_to_numpy
    from vtkmodules.vtkIOImage import vtkPNGReader

    def read(path):
        reader = vtkPNGReader()
        reader.SetFileName(path)
        reader.Update()
        return vtk_to_numpy(reader.GetOutput().GetPointData().GetScalars())[:, :3].astype(float)

    serial = read(serial_png)
    parallel = read(os.path.join(outdir, "%s-mpi%s-paraview.png" % (dataset, ranks)))
    rmse_bound, differing_bound = distributed_bounds(
        dataset, "whole" if mode == "gather" else "regions")
    rmse = kit_rmse(serial, parallel)
    difference = abs(serial - parallel).max(axis=1)
    differing = off_share(serial, parallel, 2)
    print("%s ranks vs 1 rank, over the volume's pixels: rmse (0-255) %.3f (bound %.1f), %.2f %% "
          "of them differ by more than 2 levels (bound %.1f %%), largest difference %d levels"
          % (ranks, rmse, rmse_bound, 100.0 * differing, 100.0 * differing_bound,
             int(difference.max())))
    if rmse > rmse_bound or differing > differing_bound:
        print("FAIL: the parallel image differs from the serial one")
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
