#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""The independent reference shares no rule with the kD-tree integrator (the shader's mirror).

Usage: CheckReferenceIndependence.py NM REFERENCE_SOURCE_DIR --reference OBJ... --mirror OBJ...

1. Every quoted #include of the reference's sources names one of its own files or one of the
   headers it may share with the mirror: data loading, the hierarchy, the camera, the settings
   and the row scheduler (SHARED_HEADERS). amrsp/Render.h, amrsp/Shading.h, amrsp/SampleStep.h,
   amrsp/VertexData.h, amrsp/TransferFunction.h (directly) and src/RayIntegration.h are the
   mirror's rules and may not appear.
2. Every amrsp:: name in the reference's object files (what they define, call or instantiate, from
   `nm -C`) is the reference's own or a shared type (SHARED_NAMES). Calling
   TransferFunction::EvaluateColor, ShadeSample, Gradient, the iso-surface tracker, LevelSampleStep,
   InterpolateVertices or ClipInterval, or instantiating integration::Accumulator, fails.
3. The check is not vacuous: the reference's objects define its own rules
   (amrsp::reference::ColourOf, CorrectedOpacity, FindCrossings, Shader::Gradient), and the same
   check rejects the mirror's objects (KdTreeIntegrator.cxx) naming the rule they share.
Prints PASS or FAIL lines; exits 1 on any failure.
"""
import os
import re
import subprocess
import sys

SHARED_HEADERS = {
    "amrsp/ReferenceRender.h",
    "amrsp/FinestCellLocator.h",
    "amrsp/Hierarchy.h",
    "amrsp/Image.h",
    "amrsp/PointLookup.h",
    "amrsp/RenderSettings.h",
    "amrsp/Camera.h",
    "amrsp/ParallelFor.h",
    "amrsp/Progress.h",
}

# names (regular expressions over the amrsp:: token) the reference may use besides its own
SHARED_NAMES = [
    r"amrsp::reference(::.*)?",
    r"amrsp::\(anonymous namespace\)::.*",  # defined in the reference's own translation units
    r"amrsp::RenderReference",
    r"amrsp::ReferencePointLookup",
    r"amrsp::FinestCellLocator(::.*)?",
    r"amrsp::CellValue",
    r"amrsp::(Hierarchy|Box|Grid|GridValues)(::.*)?",
    r"amrsp::Camera(::.*)?",
    r"amrsp::Image(::.*)?",
    r"amrsp::(ProgressTicker|ParallelForInterleaved|ParallelFor|RunWorkers)(::.*)?",
    r"amrsp::(RenderSettings|RenderStats|Lighting|BlendMode|RayLoop|RayCaster)(::.*)?",
    # the transfer function's data, not its evaluation
    r"amrsp::TransferFunction(::(ColorPoint|OpacityPoint|TransferFunction|~TransferFunction))?",
]
OWN_RULES = [
    "amrsp::reference::ColourOf",
    "amrsp::reference::OpacityOf",
    "amrsp::reference::CorrectedOpacity",
    "amrsp::reference::FindCrossings",
    "amrsp::reference::Shader::Gradient",
    "amrsp::reference::Shader::Transmittance",
    "amrsp::reference::Field::At",
]
TOKEN = re.compile(r"amrsp::(?:\(anonymous namespace\)::)?[A-Za-z_~][\w:~]*|amrsp::\(anonymous namespace\)::\S*")


def symbols(nm, obj):
    out = subprocess.run([nm, "-C", obj], check=True, capture_output=True, text=True).stdout
    return [line.split(" ", 2)[-1] for line in out.splitlines() if line.strip()]


def foreign_names(nm, objects):
    """(object, amrsp:: name, symbol) for every name outside SHARED_NAMES."""
    allowed = [re.compile(p + "$") for p in SHARED_NAMES]
    found = []
    for obj in objects:
        for sym in symbols(nm, obj):
            for name in TOKEN.findall(sym):
                name = name.rstrip(":")
                if not any(a.match(name) for a in allowed):
                    found.append((os.path.basename(obj), name, sym))
    return found


def main(argv):
    nm, source_dir = argv[1], argv[2]
    rest = argv[3:]
    reference = rest[rest.index("--reference") + 1 : rest.index("--mirror")]
    mirror = [o for o in rest[rest.index("--mirror") + 1 :] if "KdTreeIntegrator" in o]
    failures = 0

    own = set(os.listdir(source_dir))
    for name in sorted(own):
        if not name.endswith((".cxx", ".h")):
            continue
        text = open(os.path.join(source_dir, name), encoding="utf-8").read()
        for inc in re.findall(r'^\s*#\s*include\s+"([^"]+)"', text, re.M):
            if inc not in own and inc not in SHARED_HEADERS:
                print(f"FAIL: {name} includes \"{inc}\", a header the reference may not share")
                failures += 1
    if not failures:
        print(f"PASS: the reference's {len(own)} sources include only their own files and "
              f"{len(SHARED_HEADERS)} shared headers (data, hierarchy, camera, settings, rows)")

    if not reference:
        print("FAIL: no reference object files were given")
        return 1
    foreign = foreign_names(nm, reference)
    for obj, name, sym in foreign[:20]:
        print(f"FAIL: {obj} uses {name} (in {sym})")
    failures += len(foreign)
    if not foreign:
        print(f"PASS: every amrsp:: name in the reference's {len(reference)} objects is its own "
              "or shared data/hierarchy/camera/scheduling")

    defined = set()
    for obj in reference:
        out = subprocess.run([nm, "-C", "--defined-only", obj], check=True, capture_output=True,
                             text=True).stdout
        defined.update(TOKEN.findall(out))
    missing = [r for r in OWN_RULES if r not in defined]
    if missing:
        print(f"FAIL: the reference's objects do not define its own rules {missing}: the symbol "
              "check would pass vacuously")
        failures += 1
    else:
        print(f"PASS: the reference's objects define its own rules ({', '.join(OWN_RULES)})")

    if len(mirror) != 1:
        print(f"FAIL: expected the mirror's KdTreeIntegrator object, got {mirror}")
        failures += 1
    else:
        shared = sorted({name for _, name, _ in foreign_names(nm, mirror)})
        rules = [n for n in shared if re.search(
            r"ShadeSample|IsoSurfaceTracker|integration::Accumulator|EvaluateOpacity", n)]
        if rules:
            print(f"PASS: the same check rejects the mirror's KdTreeIntegrator object "
                  f"({len(shared)} foreign names, e.g. {', '.join(rules[:4])})")
        else:
            print(f"FAIL: the check does not reject the mirror's object (foreign: {shared[:8]})")
            failures += 1
    return 1 if failures else 0


if __name__ == "__main__":
    sys.exit(main(sys.argv))
