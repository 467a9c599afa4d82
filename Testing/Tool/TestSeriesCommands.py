# The tool's time-series commands on the synthetic series (4 steps, a regrid at step 2):
#   amrsp render SERIES --time all -o DIR/frame_%04d.png   one numbered image per step, a line per
#       step saying whether the mapper refreshed the values (steps 1 and 3) or built (0 and 2);
#   amrsp render SERIES --time 1:2                           the selected steps only;
#   amrsp bench SERIES --time-series --json -                step_switch_s and rebuild_s per method.
# Errors: a --time outside the series and a pattern that matches nothing name the problem.
# File series of the real formats (Enzo, AMReX, .vthb): DATA's datasets, each linked twice as two
# steps of one series (symbolic links in OUTDIR, the data used in place): a pattern finds both
# steps, the second refreshes the values only (the same hierarchy), and both images are equal.
#
#   python3 TestSeriesCommands.py AMRSP OUTDIR [DATA]
# Exit codes: 0 pass, 1 fail, 125 skipped (no OpenGL context: see PluginTestKit.skip).
import json
import os
import re
import shutil
import subprocess
import sys

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), "..", "Python"))
from PluginTestKit import fail, skip  # noqa: E402

SERIES = "synthetic:cosmo:grids=60,levels=3,cells=200k,seed=4,steps=4,regrid=2"


def run(args, expect_ok=True):
    result = subprocess.run(args, stdout=subprocess.PIPE, stderr=subprocess.STDOUT, text=True,
                            timeout=300)
    print("$ %s\n%s" % (" ".join(args), result.stdout))
    if expect_ok and result.returncode != 0:
        fail("%s exited with %d" % (args[1], result.returncode))
    return result


def main():
    amrsp, outdir = sys.argv[1:3]
    data = sys.argv[3] if len(sys.argv) > 3 else ""
    os.makedirs(outdir, exist_ok=True)
    for name in os.listdir(outdir):
        path = os.path.join(outdir, name)
        if os.path.isdir(path) and not os.path.islink(path):
            shutil.rmtree(path)
        else:
            os.remove(path)
    out = run([amrsp, "render", SERIES, "--time", "all", "--size", "48x48", "-o",
               os.path.join(outdir, "frame_%04d.png")]).stdout
    if "no OpenGL context" in out:
        skip("no OpenGL context for the GPU mapper: " + out.strip().splitlines()[0])
    failures = []

    def check(ok, message):
        print("%s %s" % ("ok     " if ok else "FAILED ", message))
        if not ok:
            failures.append(message)

    kinds = re.findall(r"^step (\d+) \(\d+ of 4\): \d+ grids, (values refreshed|built)", out, re.M)
    check([(int(s), k) for s, k in kinds] == [(0, "built"), (1, "values refreshed"),
                                             (2, "built"), (3, "values refreshed")],
          "a line per step, the values refreshed between regrids: %s" % kinds)
    frames = sorted(f for f in os.listdir(outdir) if f.startswith("frame_"))
    check(frames == ["frame_%04d.png" % s for s in range(4)], "one image per step: %s" % frames)
    sizes = {f: os.path.getsize(os.path.join(outdir, f)) for f in frames}
    contents = {open(os.path.join(outdir, f), "rb").read() for f in frames}
    check(len(contents) == len(frames), "the images differ from step to step (sizes %s)" % sizes)

    part = run([amrsp, "render", SERIES, "--time", "1:2", "--size", "48x48", "-o",
                os.path.join(outdir, "part.png")]).stdout
    written = sorted(f for f in os.listdir(outdir) if f.startswith("part"))
    check(written == ["part_0001.png", "part_0002.png"] and "step 0 " not in part,
          "--time 1:2 renders steps 1 and 2 only, numbered: %s" % written)

    bad = run([amrsp, "render", SERIES, "--time", "4"], expect_ok=False)
    check(bad.returncode != 0 and "outside the series' steps 0 to 3" in bad.stdout,
          "--time 4 is refused naming the series' steps")
    missing = run([amrsp, "render", os.path.join(outdir, "nothing_*.vthb"), "--time", "all"],
                  expect_ok=False)
    check(missing.returncode != 0 and "matches no file or folder" in missing.stdout,
          "a pattern that matches nothing is refused naming it")

    bench = run([amrsp, "bench", SERIES, "--time-series", "--size", "48x48", "--methods",
                 "packing,multipass", "--json", "-"]).stdout
    j = json.loads(bench[bench.index("{"):])
    for method in ("packing", "multipass"):
        r = j["methods"][method]
        refreshed = [s["refreshed"] for s in r["per_step"]]
        check(refreshed == [True, False, True] and r["step_switch_s"] > 0 and r["rebuild_s"] > 0,
              "%s: steps 1 and 3 refreshed, step 2 rebuilt; step_switch_s %.4f, rebuild_s %.4f"
              % (method, r["step_switch_s"], r["rebuild_s"]))
    check_file_series(amrsp, outdir, data, check)
    if failures:
        fail("%d check(s) failed, the first: %s" % (len(failures), failures[0]))
    print("PASS")


# (name, the dataset folder in DATA, the file inside each step's folder; "" for the folder itself)
FILE_SERIES = [("enzo", "enzo_moving7/DD0010", "moving7_0010.hierarchy"),
               ("amrex", "amrex_plt1_Y", ""),
               ("vthb", "vthb_hierarchicalbox", "HierarchicalBoxDataset.v1.1.vthb")]


def check_file_series(amrsp, outdir, data, check):
    """Each real dataset as a two-step file series: step_0000 and step_0001 link to its folder."""
    for name, folder, inside in FILE_SERIES:
        source = os.path.join(data, folder) if data else ""
        if not source or not os.path.isdir(source):
            required = os.environ.get("AMRSP_REQUIRE_GPU") == "1"
            check(not required, "%s file series: %s is missing (%s)" % (
                name, source or "no data folder given",
                "required here: AMRSP_REQUIRE_GPU=1" if required else "left out"))
            continue
        series = os.path.join(outdir, "files", name)
        os.makedirs(series, exist_ok=True)
        for step in ("step_0000", "step_0001"):
            os.symlink(os.path.abspath(source), os.path.join(series, step))
        pattern = os.path.join(series, "step_*", inside) if inside else os.path.join(series,
                                                                                       "step_*")
        out = run([amrsp, "render", pattern, "--time", "all", "--size", "48x48", "-o",
                   os.path.join(series, "frame_%04d.png")]).stdout
        kinds = re.findall(r"^step (\d+) \(\d+ of 2\): \d+ grids, (values refreshed|built)",
                           out, re.M)
        check([(int(s), k) for s, k in kinds] == [(0, "built"), (1, "values refreshed")],
              "%s file series '%s': two steps, the second refreshes the values: %s"
              % (name, pattern, kinds))
        frames = [os.path.join(series, "frame_%04d.png" % k) for k in range(2)]
        same = all(os.path.exists(f) for f in frames) and \
            open(frames[0], "rb").read() == open(frames[1], "rb").read()
        check(same, "%s file series: the refreshed step's image equals the first's (the same "
              "data)" % name)


if __name__ == "__main__":
    main()
