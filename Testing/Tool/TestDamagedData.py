#!/usr/bin/env python3
# Damaged copies of every real dataset in ../shared/data, made at test time:
#
#   python3 TestDamagedData.py AMRSP DATA_DIR WORK_DIR
#
# For each variant (truncation at several offsets inside the header and inside the data, a
# deleted data file, overwritten bytes, a header with one changed count) `amrsp inspect` and
# `amrsp render --method cpu-kdtree` must end within TIME_LIMIT seconds, without a signal, either
# with an image identical to the intact dataset's (the damage touched nothing the render reads)
# or with exactly one line on stderr, "amrsp: error: ...", naming the damaged file. Prints one
# line per variant and the outcome counts. Also: the AMReX plotfile rewritten as embedded-boundary
# output (a vfrac variable, EB_WriteMultiLevelPlotfile's Header) must be read, or fail naming the
# variables its Header lists; and the reader watchdog must end VTK's looping Enzo reader. Exit code 0 pass, 1 fail, 125 skipped (no data).
import os
import random
import shutil
import signal
import subprocess
import sys

TIME_LIMIT = 60
SKIP = 125


def truncate(path, size):
    with open(path, "r+b") as f:
        f.truncate(size)


def overwrite(path, offset, count, seed=1):
    rng = random.Random(seed)
    with open(path, "r+b") as f:
        f.seek(offset)
        f.write(bytes(rng.randrange(256) for _ in range(count)))


def replace_text(path, old, new):
    with open(path) as f:
        text = f.read()
    if old not in text:
        raise RuntimeError("%r not in %s" % (old, path))
    with open(path, "w") as f:
        f.write(text.replace(old, new, 1))


def size_of(root, rel):
    return os.path.getsize(os.path.join(root, rel))


def variants(name, root):
    """(description, file the damage is in (relative), damage function of the copy's folder)."""
    v = []
    if name == "enzo_moving7":
        h = "DD0010/moving7_0010.hierarchy"
        g = "DD0010/moving7_0010.cpu0000"
        hs, gs = size_of(root, h), size_of(root, g)
        for at in (200, 1500, int(0.6 * hs), hs - 10):
            v.append(("hierarchy cut after %d of %d bytes" % (at, hs), h,
                      lambda d, at=at: truncate(os.path.join(d, h), at)))
        v.append(("grid file deleted", g, lambda d: os.remove(os.path.join(d, g))))
        for at in (1000, gs // 2):
            v.append(("grid file cut after %d of %d bytes" % (at, gs), g,
                      lambda d, at=at: truncate(os.path.join(d, g), at)))
        v.append(("grid file's first 4096 bytes overwritten", g,
                  lambda d: overwrite(os.path.join(d, g), 0, 4096)))
        v.append(("hierarchy: grid 1's GridDimension changed", h,
                  lambda d: replace_text(os.path.join(d, h), "GridDimension     = 22 22 22",
                                         "GridDimension     = 23 22 22")))
        v.append(("hierarchy: grid 3 renumbered 30", h,
                  lambda d: replace_text(os.path.join(d, h), "Grid = 3\n", "Grid = 30\n")))
    elif name == "amrex_plt1_Y":
        hs = size_of(root, "Header")
        for at in (40, int(0.4 * hs), hs - 30):
            v.append(("Header cut after %d of %d bytes" % (at, hs), "Header",
                      lambda d, at=at: truncate(os.path.join(d, "Header"), at)))
        ch = "Level_1/Cell_H"
        v.append(("Level_1/Cell_H cut in half", ch,
                  lambda d: truncate(os.path.join(d, ch), size_of(d, ch) // 2)))
        v.append(("Level_1/Cell_H deleted", ch, lambda d: os.remove(os.path.join(d, ch))))
        cd = "Level_1/Cell_D_00000"
        cs = size_of(root, cd)
        v.append(("%s deleted" % cd, cd, lambda d: os.remove(os.path.join(d, cd))))
        for at in (100, cs // 2):
            v.append(("%s cut after %d of %d bytes" % (cd, at, cs), cd,
                      lambda d, at=at: truncate(os.path.join(d, cd), at)))
        v.append(("%s: its FAB header overwritten" % cd, cd,
                  lambda d: overwrite(os.path.join(d, cd), 0, 64)))
        v.append(("every Cell_D cut to 100 bytes", "Cell_D",
                  lambda d: [truncate(os.path.join(r, f), 100) for r, _, fs in os.walk(d)
                             for f in fs if f.startswith("Cell_D")]))
        v.append(("Header: one variable more", "Header",
                  lambda d: replace_text(os.path.join(d, "Header"), "HyperCLaw-V1.1\n4\n",
                                         "HyperCLaw-V1.1\n5\n")))
    elif name == "chombo3d_vtm":
        m = "chombo3d.vtm"
        ms = size_of(root, m)
        for at in (100, ms // 2):
            v.append(("%s cut after %d of %d bytes" % (m, at, ms), m,
                      lambda d, at=at: truncate(os.path.join(d, m), at)))
        p = "chombo3d_3.vti"
        v.append(("%s deleted" % p, p, lambda d: os.remove(os.path.join(d, p))))
        v.append(("%s cut in half" % p, p,
                  lambda d: truncate(os.path.join(d, p), size_of(d, p) // 2)))
        v.append(("%s: 200 bytes overwritten" % p, p,
                  lambda d: overwrite(os.path.join(d, p), 0, 200)))
    elif name == "vthb_hierarchicalbox":
        m = "HierarchicalBoxDataset.v1.1.vthb"
        ms = size_of(root, m)
        for at in (100, ms // 2):
            v.append(("%s cut after %d of %d bytes" % (m, at, ms), m,
                      lambda d, at=at: truncate(os.path.join(d, m), at)))
        pieces = sorted(os.listdir(os.path.join(root, "HierarchicalBoxDataset.v1.1")))
        p = os.path.join("HierarchicalBoxDataset.v1.1", pieces[len(pieces) // 2])
        v.append(("%s deleted" % p, p, lambda d: os.remove(os.path.join(d, p))))
        v.append(("%s cut in half" % p, p,
                  lambda d: truncate(os.path.join(d, p), size_of(d, p) // 2)))
    return v


def make_eb_plotfile(source, target, version):
    """A copy of the AMReX plotfile `source` as AMReX's EB_WriteMultiLevelPlotfile writes
    embedded-boundary output: the variable "vfrac" (the volume fraction, here 1 everywhere)
    after the others in the Header, in every FAB and in the Cell_H min/max tables, and one line
    of the small-volume-fraction threshold per level at the Header's end; `version` on the first
    line (HyperCLaw-V1.1, or CartGrid-V2.0 as older EB codes wrote)."""
    import re
    import struct

    shutil.copytree(source, target)
    for r, dirs, files in os.walk(target):
        for x in dirs + files:
            os.chmod(os.path.join(r, x), 0o755 if x in dirs else 0o644)
    header = os.path.join(target, "Header")
    with open(header) as f:
        lines = f.read().rstrip("\n").split("\n")
    count = int(lines[1])
    lines[0] = version
    lines[1] = str(count + 1)
    lines.insert(2 + count, "vfrac")
    finest = int(lines[2 + count + 1 + 2])  # after the names: dimension, time, finest level
    with open(header, "w") as f:
        f.write("\n".join(lines) + "\n" + "1.0e-6\n" * (finest + 1))
    for level in range(finest + 1):
        folder = os.path.join(target, "Level_%d" % level)
        with open(os.path.join(folder, "Cell_H")) as f:
            cell_h = f.read().split("\n")
        cell_h[2] = str(int(cell_h[2]) + 1)
        rewritten = {}  # data file -> new bytes
        for i, line in enumerate(cell_h):
            if not line.startswith("FabOnDisk:"):
                m = re.match(r"^(\d+),(\d+)$", line)
                if m:
                    cell_h[i] = "%s,%d" % (m.group(1), int(m.group(2)) + 1)
                elif re.match(r"^[-0-9.eE+]+(,[-0-9.eE+]+)*,$", line):
                    cell_h[i] = line + "1.0000000000000000e+00,"
                continue
            _, name, offset = line.split()
            with open(os.path.join(folder, name), "rb") as f:
                data = f.read()
            offset = int(offset)
            end = data.index(b"\n", offset)
            head = data[offset:end].decode()
            bits = int(re.search(r"FAB \(\(\d+, \((\d+)", head).group(1))
            corners = re.findall(r"\((-?\d+),(-?\d+),(-?\d+)\)", head)
            cells = 1
            for a in range(3):
                cells *= int(corners[1][a]) - int(corners[0][a]) + 1
            components = int(head.split()[-1])
            body = data[end + 1:end + 1 + cells * components * bits // 8]
            one = struct.pack("<d" if bits == 64 else "<f", 1.0)
            out = rewritten.setdefault(name, bytearray())
            cell_h[i] = "FabOnDisk: %s %d" % (name, len(out))
            out += (head[:head.rfind(" ")] + " %d\n" % (components + 1)).encode() + body
            out += one * cells
        for name, data in rewritten.items():
            with open(os.path.join(folder, name), "wb") as f:
                f.write(bytes(data))
        with open(os.path.join(folder, "Cell_H"), "w") as f:
            f.write("\n".join(cell_h))


ENTRY = {
    "enzo_moving7": "DD0010/moving7_0010.hierarchy",
    "amrex_plt1_Y": "",
    "chombo3d_vtm": "chombo3d.vtm",
    "vthb_hierarchicalbox": "HierarchicalBoxDataset.v1.1.vthb",
}


def run(command):
    """(outcome, detail): 'ok' with the PNG bytes, 'error' with the stderr line, or 'FAIL'."""
    try:
        p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=TIME_LIMIT)
    except subprocess.TimeoutExpired:
        return "FAIL", "no end within %d s" % TIME_LIMIT
    err = [l for l in p.stderr.decode(errors="replace").splitlines() if l.strip()]
    if p.returncode < 0:
        return "FAIL", "killed by signal %s" % signal.Signals(-p.returncode).name
    if p.returncode == 0:
        return "ok", None
    if len(err) != 1 or not err[0].startswith("amrsp: error: "):
        return "FAIL", "exit code %d with %d stderr lines: %s" % (p.returncode, len(err),
                                                                  " | ".join(err[:4]))
    return "error", err[0]


def main():
    if len(sys.argv) != 4:
        print("usage: TestDamagedData.py AMRSP DATA_DIR WORK_DIR")
        return 2
    amrsp, data, work = sys.argv[1:]
    present = [n for n in ENTRY if os.path.isdir(os.path.join(data, n))]
    if not present:
        if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
            print("FAIL: no dataset under %s (required here: AMRSP_REQUIRE_GPU=1)" % data)
            return 1
        print("SKIPPED: no dataset under %s" % data)
        return SKIP
    shutil.rmtree(work, ignore_errors=True)
    os.makedirs(work)
    counts = {"ok": 0, "error": 0, "FAIL": 0}
    failures = []
    for name in present:
        source = os.path.join(data, name)
        intact = os.path.join(work, name + "-intact.png")
        spec = os.path.join(source, ENTRY[name]) if ENTRY[name] else source
        p = subprocess.run([amrsp, "render", spec, "--method", "cpu-kdtree", "--size", "32x32",
                            "-o", intact], stdout=subprocess.PIPE, stderr=subprocess.STDOUT,
                           timeout=TIME_LIMIT)
        if p.returncode != 0:
            print(p.stdout.decode(errors="replace"))
            print("FAIL: the intact %s does not render" % name)
            return 1
        with open(intact, "rb") as f:
            intact_png = f.read()
        for index, (what, damaged, damage) in enumerate(variants(name, source)):
            copy = os.path.join(work, "%s-%d" % (name, index))
            shutil.copytree(source, copy)
            for r, dirs, files in os.walk(copy):
                for x in dirs + files:
                    os.chmod(os.path.join(r, x), 0o755 if x in dirs else 0o644)
            damage(copy)
            spec = os.path.join(copy, ENTRY[name]) if ENTRY[name] else copy
            png = os.path.join(work, "%s-%d.png" % (name, index))
            results = []
            for command in ([amrsp, "inspect", spec],
                            [amrsp, "render", spec, "--method", "cpu-kdtree", "--size", "32x32",
                             "-o", png]):
                outcome, detail = run(command)
                if outcome == "ok" and command[1] == "render":
                    with open(png, "rb") as f:
                        if f.read() != intact_png:
                            outcome, detail = "FAIL", "exit code 0 with another image (silent)"
                if outcome == "error" and os.path.basename(damaged) not in detail:
                    outcome = "FAIL"
                    detail = "the line does not name %s: %s" % (os.path.basename(damaged),
                                                                 detail)
                counts[outcome] += 1
                results.append("%s %s%s" % (command[1], outcome,
                                            ": " + detail if detail else ""))
                if outcome == "FAIL":
                    failures.append("%s, %s: %s %s" % (name, what, command[1], detail))
            print("%-22s %-52s %s" % (name, what, "; ".join(results)))
    # embedded-boundary plotfiles (valid, unusual): read, the usual variable giving the intact
    # image and vfrac rendering, or one error line naming the variables the Header lists
    if "amrex_plt1_Y" in present:
        with open(os.path.join(work, "amrex_plt1_Y-intact.png"), "rb") as f:
            intact_png = f.read()
        for version in ("HyperCLaw-V1.1", "CartGrid-V2.0"):
            copy = os.path.join(work, "amrex_plt1_Y-eb-" + version)
            make_eb_plotfile(os.path.join(data, "amrex_plt1_Y"), copy, version)
            results, ok = [], True
            for array in (None, "vfrac"):
                png = copy + "-%s.png" % (array or "default")
                outcome, detail = run([amrsp, "render", copy, "--method", "cpu-kdtree", "--size",
                                       "32x32", "-o", png] + (["--array", array] if array else []))
                if outcome == "ok" and array is None:
                    with open(png, "rb") as f:
                        if f.read() != intact_png:
                            outcome, detail = "FAIL", "the usual variable renders another image"
                if outcome == "error" and not all(v in detail for v in ("Y(H2)", "vfrac")):
                    outcome, detail = "FAIL", "the error does not list the variables: " + detail
                ok = ok and outcome != "FAIL"
                results.append("%s %s%s" % (array or "Y(H)", outcome, ": " + detail if detail
                                            else ""))
            print("%-22s %-52s %s" % ("amrex_plt1_Y", "EB plotfile (vfrac), version " + version,
                                      "; ".join(results)))
            if not ok:
                failures.append("EB plotfile %s: %s" % (version, "; ".join(results)))

    # the reader watchdog: VTK's Enzo reader loops forever on a hierarchy cut inside a grid
    # entry; with the file checks off (AMRSP_SKIP_FILE_CHECKS=1) it must be ended after
    # --read-timeout seconds with one line and exit code 75
    if "enzo_moving7" in present:
        copy = os.path.join(work, "enzo_moving7-watchdog")
        shutil.copytree(os.path.join(data, "enzo_moving7"), copy)
        os.chmod(os.path.join(copy, "DD0010"), 0o755)
        hierarchy = os.path.join(copy, "DD0010", "moving7_0010.hierarchy")
        os.chmod(hierarchy, 0o644)
        truncate(hierarchy, 1500)
        try:
            p = subprocess.run([amrsp, "inspect", hierarchy, "--read-timeout", "1"],
                               stdout=subprocess.PIPE, stderr=subprocess.PIPE, timeout=TIME_LIMIT,
                               env=dict(os.environ, AMRSP_SKIP_FILE_CHECKS="1"))
            err = [l for l in p.stderr.decode(errors="replace").splitlines() if l.strip()]
            ok = (p.returncode == 75 and len(err) == 1 and
                  "did not finish within 1 s" in err[0] and "moving7_0010.hierarchy" in err[0])
            detail = "exit code %d: %s" % (p.returncode, " | ".join(err[:3]))
        except subprocess.TimeoutExpired:
            ok, detail = False, "no end within %d s" % TIME_LIMIT
        print("%-22s %-52s %s" % ("enzo_moving7", "watchdog: checks off, hierarchy cut at 1500",
                                  ("ok, " if ok else "FAILED, ") + detail))
        if not ok:
            failures.append("the reader watchdog: " + detail)
    total = sum(counts.values())
    print("%d runs on %d variants: %d rendered the intact image, %d ended with one error line "
          "naming the damaged file, %d failed" % (total, total // 2, counts["ok"],
                                                   counts["error"], counts["FAIL"]))
    if failures:
        print("FAIL: " + "\nFAIL: ".join(failures))
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
