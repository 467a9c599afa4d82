#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A seeded, format-aware fuzzer of the real datasets: damaged copies of ../shared/data's Enzo,
AMReX and VTK XML AMR files through `amrsp inspect --json` (and every fourth through `amrsp render`
with the CPU integrator).

usage: FuzzDatasets.py AMRSP DATA_DIR WORK_DIR [--seed S] [--variants N] [--jobs J]

Each variant copies one dataset and damages it once, knowing the format: a number of a text
header (the Enzo hierarchy and parameter file, the AMReX Header and Cell_H, the FAB header line
of a Cell_D file, the .vthb/.vtm XML, a .vti piece's XML head) replaced by one of the values that
break readers (0, -1, -2, 1, 2^31 - 1, 1e9, 2e9, NaN, +-Inf, 1e300, 0.5), two numbers of a header
swapped, a file cut short, a few bytes of a binary file flipped, a file removed or emptied, or two
pieces swapped. The rule, for every variant: no signal, no hang (60 s), no more than 4 GB of memory
(RLIMIT_AS on the tool and what it starts), and either a result (exit 0 with inspect's JSON of at
least one level and one grid on stdout, or render's PNG file) or exactly one line
`amrsp: error: ...` on stderr that names a file or folder of the damaged copy. A variant that
breaks the rule fails the test with its seed, its damage and what happened.
"""
import argparse
import json
import os
import random
import re
import resource
import shutil
import subprocess
import sys
from concurrent.futures import ThreadPoolExecutor

TIME_LIMIT = 60
# what AddressSanitizer and UBSan print, and the exit code scripts/run-tests.sh gives ASan
SANITIZER_MARKS = ["Sanitizer", "runtime error:", "exit code 86"]
MEMORY_LIMIT = 4 << 30
BAD_NUMBERS = ["0", "-1", "-2", "1", "2147483647", "-2147483648", "1000000000", "2000000000",
               "nan", "inf", "-inf", "1e300", "0.5", "99999999999999999999"]
NUMBER = re.compile(rb"(?<![A-Za-z_0-9.])-?\d+(?:\.\d+)?(?:[eE][-+]?\d+)?(?![A-Za-z_0-9.])")

DATASETS = {
    # name: (folder under DATA_DIR, the path inspect opens relative to the copy, text files,
    # binary files)
    "enzo": ("enzo_moving7", "DD0010/moving7_0010.hierarchy",
             ["DD0010/moving7_0010.hierarchy", "DD0010/moving7_0010"],
             ["DD0010/moving7_0010.cpu0000"]),
    "amrex": ("amrex_plt1_Y", ".", ["Header", "Level_0/Cell_H", "Level_1/Cell_H",
                                     "Level_2/Cell_H"],
              ["Level_1/Cell_D_00000", "Level_2/Cell_D_00001"]),
    "vthb": ("vthb_hierarchicalbox", "HierarchicalBoxDataset.v1.1.vthb",
             ["HierarchicalBoxDataset.v1.1.vthb"],
             ["HierarchicalBoxDataset.v1.1/HierarchicalBoxDataset.v1.1_1.vti",
              "HierarchicalBoxDataset.v1.1/HierarchicalBoxDataset.v1.1_4.vti"]),
    "chombo": ("chombo3d_vtm", "chombo3d.vtm", ["chombo3d.vtm"],
               ["chombo3d_1.vti", "chombo3d_3.vti"]),
}


def mutate_number(path, rng, header_only=False):
    data = open(path, "rb").read()
    end = len(data)
    if header_only:
        # the text before a binary payload: a FAB header line, a .vti's XML head
        newline = data.find(b"\n")
        appended = data.find(b"<AppendedData")
        if path.endswith(".vti"):
            end = appended if appended > 0 else min(end, 4096)
        else:
            end = newline if newline > 0 else min(end, 4096)
    numbers = [m for m in NUMBER.finditer(data[:end])]
    if not numbers:
        return None
    m = rng.choice(numbers)
    if rng.random() < 0.2 and len(numbers) > 1:
        other = rng.choice(numbers)
        a, b = sorted([m, other], key=lambda x: x.start())
        if a.start() == b.start():
            return None
        out = data[:a.start()] + b.group() + data[a.end():b.start()] + a.group() + data[b.end():]
        what = "swapped %s and %s" % (a.group().decode(), b.group().decode())
    else:
        value = rng.choice(BAD_NUMBERS).encode()
        out = data[:m.start()] + value + data[m.end():]
        what = "%s -> %s at byte %d" % (m.group().decode(), value.decode(), m.start())
    open(path, "wb").write(out)
    return what


def damage(copy, spec, rng):
    """Damages the copy of a dataset in one way; returns the description (None: try again)."""
    _, _, texts, binaries = spec
    kind = rng.choice(["number", "number", "number", "header", "truncate", "flip", "remove",
                       "empty", "swap"])
    if kind == "number":
        f = rng.choice(texts)
        what = mutate_number(os.path.join(copy, f), rng)
        return what and "%s: %s" % (f, what)
    if kind == "header":
        f = rng.choice(binaries)
        what = mutate_number(os.path.join(copy, f), rng, header_only=True)
        return what and "%s header: %s" % (f, what)
    f = rng.choice(texts + binaries)
    path = os.path.join(copy, f)
    if kind == "truncate":
        size = os.path.getsize(path)
        cut = rng.randrange(0, max(1, size))
        with open(path, "r+b") as out:
            out.truncate(cut)
        return "%s cut at %d of %d bytes" % (f, cut, size)
    if kind == "flip":
        f = rng.choice(binaries)
        path = os.path.join(copy, f)
        data = bytearray(open(path, "rb").read())
        flips = []
        for _ in range(rng.randint(1, 8)):
            i = rng.randrange(len(data))
            data[i] ^= 1 << rng.randrange(8)
            flips.append(i)
        open(path, "wb").write(bytes(data))
        return "%s: bits flipped at bytes %s" % (f, flips)
    if kind == "remove":
        os.remove(path)
        return "%s removed" % f
    if kind == "empty":
        open(path, "wb").close()
        return "%s emptied" % f
    # swap two pieces of the same kind
    a, b = rng.sample(binaries, 2) if len(binaries) > 1 else (None, None)
    if not a:
        return None
    pa, pb = os.path.join(copy, a), os.path.join(copy, b)
    tmp = pa + ".swap"
    os.rename(pa, tmp)
    os.rename(pb, pa)
    os.rename(tmp, pb)
    return "%s and %s swapped" % (a, b)


def run_variant(amrsp, data, work, seed, index):
    rng = random.Random("%d-%d" % (seed, index))
    name = rng.choice(sorted(DATASETS))
    spec = DATASETS[name]
    source = os.path.join(data, spec[0])
    copy = os.path.join(work, "v%04d-%s" % (index, name))
    shutil.rmtree(copy, ignore_errors=True)
    what = None
    for _ in range(10):
        shutil.copytree(source, copy)
        for r, dirs, files in os.walk(copy):
            for x in dirs + files:
                os.chmod(os.path.join(r, x), 0o755 if x in dirs else 0o644)
        what = damage(copy, spec, rng)
        if what:
            break
        shutil.rmtree(copy)
    target = os.path.normpath(os.path.join(copy, spec[1]))
    label = "variant %d (%s, seed %d): %s" % (index, name, seed, what)
    # every fourth variant is rendered (the CPU integrator, 16x16), the rest inspected
    if index % 4 == 3:
        command = [amrsp, "render", target, "--method", "cpu-kdtree", "--size", "16x16", "-o",
                   copy + ".png", "--quiet", "--read-timeout", "20"]
        result = png_written(copy + ".png")
    else:
        command = [amrsp, "inspect", target, "--json", "--read-timeout", "20"]
        result = inspect_json
    outcome, detail = run_and_judge(command, copy, TIME_LIMIT, result)
    shutil.rmtree(copy, ignore_errors=True)
    if os.path.exists(copy + ".png"):
        os.remove(copy + ".png")
    return outcome, label, detail


def inspect_json(stdout):
    """Why inspect's standard output is not a result (None when it is one): a JSON object with
    at least one level and one grid."""
    try:
        j = json.loads(stdout)
    except ValueError as e:
        return "its output is not JSON (%s): %r" % (e, stdout[:80])
    if not isinstance(j, dict):
        return "its JSON is not an object: %r" % stdout[:80]
    for key in ("levels", "grids"):
        if not isinstance(j.get(key), int) or j[key] < 1:
            return "its JSON has %s = %r" % (key, j.get(key))
    return None


def png_written(path):
    """A result check of render: the image file exists and starts as a PNG."""
    def check(_stdout):
        try:
            with open(path, "rb") as f:
                head = f.read(8)
        except OSError:
            return "no image at %s" % path
        return None if head == b"\x89PNG\r\n\x1a\n" else "%s is not a PNG" % path
    return check


def run_and_judge(command, copy, time_limit, result):
    """Runs one command on a damaged copy; returns ("ok" | "error" | "FAIL", detail) by the rule.
    result(stdout) says why an exit 0 gave no result (None when it did)."""
    try:
        p = subprocess.run(command, stdout=subprocess.PIPE, stderr=subprocess.PIPE,
                           timeout=time_limit)
    except subprocess.TimeoutExpired:
        return "FAIL", "no end within %d s" % time_limit
    err = [l for l in p.stderr.decode(errors="replace").splitlines() if l.strip()]
    if p.returncode < 0:
        return "FAIL", "killed by signal %d: %s" % (-p.returncode, " | ".join(err[-3:]))
    text = "\n".join(err)
    if any(mark in text for mark in SANITIZER_MARKS):
        # a sanitizer's finding, in the tool or in its reading child (whose report the tool
        # turns into its error line)
        return "FAIL", "a sanitizer's finding: " + " | ".join(err[:4])
    if p.returncode == 0:
        missing = result(p.stdout.decode(errors="replace"))
        return ("FAIL", "exit 0 without a result: " + missing) if missing else ("ok", "")
    if len(err) != 1 or not err[0].startswith("amrsp: error: "):
        return "FAIL", "exit %d with %d stderr lines: %s" % (p.returncode, len(err),
                                                              " | ".join(err[:4]))
    if copy not in err[0]:
        return "FAIL", "the error names no file of the copy: " + err[0]
    return "error", err[0]


def judge_rejects_broken_behaviour():
    """The judge itself: each way a tool can break the rule must be judged FAIL (a signal, a hang,
    an error of two lines, an error that names no file), a one-line named error must not."""
    copy = "/data/copy"
    cases = [
        ("kill -ABRT $$", "FAIL"),
        ("kill -SEGV $$", "FAIL"),
        ("sleep 5", "FAIL"),
        ("echo 'amrsp: error: x' >&2; echo 'more' >&2; exit 1", "FAIL"),
        ("echo 'amrsp: error: vector::_M_default_append' >&2; exit 1", "FAIL"),
        ("echo 'Segmentation fault' >&2; exit 1", "FAIL"),
        ("echo 'amrsp: error: %s/Header: bad' >&2; exit 1" % copy, "error"),
        ("echo 'amrsp: error: reading %s/x: the reading process ended with exit code 86: "
         "ERROR: AddressSanitizer: heap-buffer-overflow' >&2; exit 70" % copy, "FAIL"),
        ("echo 'x.cxx:1:2: runtime error: signed integer overflow' >&2; exit 0", "FAIL"),
        ("exit 0", "FAIL"),
        ("echo '{\"levels\": 0, \"grids\": 0}'", "FAIL"),
        ("echo 'levels 3'", "FAIL"),
        ("echo '{\"levels\": 3, \"grids\": 10}'", "ok"),
    ]
    wrong = []
    for script, expected in cases:
        outcome, _ = run_and_judge(["sh", "-c", script], copy, 1, inspect_json)
        if outcome != expected:
            wrong.append("%r judged %s, expected %s" % (script, outcome, expected))
    return wrong


def main():
    parser = argparse.ArgumentParser()
    parser.add_argument("amrsp")
    parser.add_argument("data")
    parser.add_argument("work")
    parser.add_argument("--seed", type=int, default=2026)
    parser.add_argument("--variants", type=int, default=300)
    parser.add_argument("--jobs", type=int, default=max(1, os.cpu_count() or 1))
    a = parser.parse_args()
    missing = [s[0] for s in DATASETS.values() if not os.path.isdir(os.path.join(a.data, s[0]))]
    if missing:
        message = "the datasets %s are missing in %s" % (", ".join(missing), a.data)
        if os.environ.get("AMRSP_REQUIRE_GPU") == "1":
            print("FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: " + message)
            return 1
        print("SKIPPED: " + message)
        return 125
    wrong = judge_rejects_broken_behaviour()
    if wrong:
        print("FAIL: the judge does not reject broken behaviour: " + "; ".join(wrong))
        return 1
    os.makedirs(a.work, exist_ok=True)
    # the address space of this process and every process it starts (inherited); an
    # AddressSanitizer build reserves terabytes of address space: its peak resident memory is
    # judged instead
    linked = subprocess.run(["ldd", a.amrsp], stdout=subprocess.PIPE, stderr=subprocess.DEVNULL,
                            text=True).stdout
    if "libasan" in linked:
        print("AddressSanitizer build: no address-space limit, the peak resident memory is judged")
    else:
        resource.setrlimit(resource.RLIMIT_AS, (MEMORY_LIMIT, MEMORY_LIMIT))
    with ThreadPoolExecutor(a.jobs) as pool:
        results = list(pool.map(lambda i: run_variant(a.amrsp, a.data, a.work, a.seed, i),
                                range(a.variants)))
    peak = resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1e6
    counts = {"ok": 0, "error": 0, "FAIL": 0}
    for outcome, label, detail in results:
        counts[outcome] += 1
        if outcome == "FAIL":
            print("FAIL: %s: %s" % (label, detail))
    print("%d variants (seed %d): %d read, %d ended with one line naming the damaged file, %d "
          "broke the rule; the largest process used %.2f GB" % (a.variants, a.seed, counts["ok"],
                                                                counts["error"], counts["FAIL"],
                                                                peak))
    if peak > MEMORY_LIMIT / 1e9:
        print("FAIL: a process used more than %.1f GB" % (MEMORY_LIMIT / 1e9))
        return 1
    if counts["FAIL"]:
        return 1
    print("PASS")
    return 0


if __name__ == "__main__":
    sys.exit(main())
