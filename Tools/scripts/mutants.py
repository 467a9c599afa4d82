#!/usr/bin/env python3
# SPDX-License-Identifier: BSD-3-Clause
"""A mutation campaign against the test suite: each mutant changes one rule (in the shader and
its CPU mirror alike where both have it, or in the mapper's own code), is built, and the tests
that should notice it are run; a mutant the tests pass "survived". The project's reviewers keep
their own mutants outside the project; this is how we look for the holes first.

    Tools/scripts/mutants.py [--build DIR] [--only NAME,...] [--json OUT]

It works on a git worktree of HEAD of its own (DIR/src; the working tree is never touched),
configured like `scripts/build.sh vtk` in DIR/build, and restores each file after its mutant.
Runs for about 3 minutes per mutant on 2 cores after a first build of 10. Needs DISPLAY (Xvfb).
Exit code: the number of mutants that survived (0: the suite killed every one).
"""
import argparse
import json
import os
import subprocess
import sys
import time

REPO = os.path.dirname(os.path.dirname(os.path.dirname(os.path.abspath(__file__))))
BASELINES = r"SinglePassAMRCxx|Mapper\.Analytic"

# name, what the mutant breaks, [(file, text, replacement)], ctest -R of the tests that should fail
MUTANTS = [
    ("opacity-correction", "the opacity correction's exponent halved (shader, multipass, mirror)", [
        ("Shaders/RaySteps.glsl", "amrspSegExponent = amrspSegDt / amrspUnitDistance;",
         "amrspSegExponent = amrspSegDt / (2.0 * amrspUnitDistance);"),
        ("Core/src/RayIntegration.h", "static_cast<T>(dt / tf.UnitDistance)",
         "static_cast<T>(dt / (2.0 * tf.UnitDistance))"),
    ], BASELINES),
    ("compositing-order", "samples added without the transmittance in front (shader and mirror)", [
        ("Shaders/RaySteps.glsl", "amrspColour += (1.0 - amrspAlpha) * a * tf.rgb;",
         "amrspColour += a * tf.rgb;"),
        ("Core/src/RayIntegration.h", "Color += (T(1) - Alpha) * a * c;", "Color += a * c;"),
    ], BASELINES),
    ("specular-light-vector", "the specular term with the light vector for the half vector", [
        ("Shaders/Shading.glsl", "dot(n, normalize(l + towardEye))", "dot(n, l)"),
        ("Core/src/Shading.cxx", "const glm::dvec3 h = glm::normalize(l + towardEye);",
         "const glm::dvec3 h = l;"),
    ], BASELINES),
    ("gradient-stencil-at-sample", "nearest cells' gradient stencil at the sample, not its cell", [
        ("Shaders/Shading.glsl", "vec3 b = (floor(p / cellSize) + 0.5) * cellSize;", "vec3 b = p;"),
        ("Core/src/Shading.cxx",
         "const glm::dvec3 b = c.CellStencil ? (glm::floor(p / cellSize) + 0.5) * cellSize : p;",
         "const glm::dvec3 b = p;"),
    ], BASELINES),
    ("shadow-exponent", "shadow rays' opacity correction halved (shader and mirror)", [
        ("Shaders/Shading.glsl", "float exponent = amrspShadowStep / amrspUnitDistance;",
         "float exponent = 0.5 * amrspShadowStep / amrspUnitDistance;"),
        ("Core/src/Shading.cxx", "const double exponent = light.ShadowStep / c.Transfer->UnitDistance;",
         "const double exponent = 0.5 * light.ShadowStep / c.Transfer->UnitDistance;"),
    ], BASELINES),
    ("iso-hit-near-end", "the iso-surface hit at the near end of the bisection (shader, mirror)", [
        ("Shaders/Shading.glsl", "    vec3 cellSize;\n    float vh;\n",
         "    b = a;\n    vec3 cellSize;\n    float vh;\n"),
        ("Core/src/Shading.cxx", "      glm::dvec3 cellSize;\n      double vh = F(b, cellSize);",
         "      b = a;\n      glm::dvec3 cellSize;\n      double vh = F(b, cellSize);"),
    ], BASELINES),
    ("mip-last-sample", "maximum intensity keeps the last sample (shader and mirror)", [
        ("Shaders/RaySteps.glsl", "amrspKept = amrspAnySample ? max(amrspKept, scalar) : scalar;",
         "amrspKept = scalar;"),
        ("Core/src/RayIntegration.h",
         "Extremum = std::isnan(Extremum) ? scalar : std::max(Extremum, scalar);",
         "Extremum = scalar;"),
    ], BASELINES),
    ("refresh-keeps-old-values", "a new time step of the same structure never uploads its values", [
        ("Mapper/vtkSinglePassAMRVolumeMapper.cxx",
         "in.PendingValuesUpload = !in.PendingUpload;", "in.PendingValuesUpload = false;"),
    ], r"Mapper\.TimeSteps"),
    ("kept-step-key-without-mtime", "a kept step found by the input object alone", [
        ("Mapper/vtkSinglePassAMRVolumeMapper.cxx",
         "{ return k.Input == amr && k.InputMTime == amr->GetMTime(); });",
         "{ return k.Input == amr; });"),
    ], r"Mapper\.TimeSteps"),
    ("rope-clamp", "a rope-entered segment not clamped to the ray's end (traversal)", [
        ("Core/src/KdTraversal.cxx",
         "fromRope ? std::min(ExitDistance(ropeLo, ropeHi, origin, direction), tEnd)",
         "fromRope ? ExitDistance(ropeLo, ropeHi, origin, direction)"),
    ], r"Core\."),
]


# the worktree lies elsewhere: the tests find the shared data through the AMRSP_DATA_DIR setting
DATA = os.environ.get("AMRSP_DATA_DIR", os.path.join(os.path.dirname(REPO), "shared", "data"))
ENV = dict(os.environ)


def sh(command, cwd, log, timeout):
    with open(log, "a") as out:
        out.write("$ %s\n" % " ".join(command))
        out.flush()
        return subprocess.run(command, cwd=cwd, stdout=out, stderr=subprocess.STDOUT,
                              timeout=timeout, env=ENV).returncode


def failed_checks(build):
    """Which tests failed in the last ctest run, and how many of their checks against the CPU
    reference and against the stored baseline images failed (from ctest's own logs)."""
    temporary = os.path.join(build, "Testing", "Temporary")
    failed = []
    try:
        with open(os.path.join(temporary, "LastTestsFailed.log")) as f:
            failed = [line.strip().split(":", 1)[-1] for line in f if line.strip()]
    except OSError:
        pass
    reference = baseline = skipped = 0
    try:
        with open(os.path.join(temporary, "LastTest.log"), errors="replace") as f:
            for line in f:
                if line.startswith("SKIPPED"):
                    skipped += 1
                if line.startswith("FAILED") and "CPU reference" in line:
                    reference += 1
                if "Failed Image Test" in line or "FAILED: GPU image vs stored baseline" in line:
                    baseline += 1
    except OSError:
        pass
    return {"failed_tests": failed, "reference_checks_failed": reference,
            "baseline_images_failed": baseline, "skipped_tests": skipped}


def main():
    parser = argparse.ArgumentParser(description=__doc__.split("\n")[0])
    parser.add_argument("--build", default="/tmp/amrsp-mutants")
    parser.add_argument("--only", default="")
    parser.add_argument("--json", default="")
    args = parser.parse_args()
    src, build = os.path.join(args.build, "src"), os.path.join(args.build, "build")
    log = os.path.join(args.build, "mutants.log")
    os.makedirs(args.build, exist_ok=True)
    if not os.path.isdir(src):
        subprocess.run(["git", "-C", REPO, "worktree", "add", "--detach", src, "HEAD"], check=True)
    else:
        subprocess.run(["git", "-C", src, "checkout", "--detach", "-f",
                        subprocess.check_output(["git", "-C", REPO, "rev-parse", "HEAD"],
                                                text=True).strip()], check=True)
    prefix = os.environ.get("AMRSP_VTK91_PREFIX", "/opt/amrsp/vtk-9.1")
    configure = ["cmake", "-S", src, "-B", build, "-DCMAKE_BUILD_TYPE=Release",
                 "-DAMRSP_WITH_PARAVIEW=OFF", "-DAMRSP_DATA_DIR=%s" % DATA,
                 "-DVTK_DIR=%s/usr/lib/x86_64-linux-gnu/cmake/vtk-9.1" % prefix]
    if sh(configure, src, log, 600) or sh(["cmake", "--build", build, "-j2"], src, log, 3600):
        print("the unmutated tree does not build: see %s" % log)
        return 100
    chosen = [m for m in MUTANTS if not args.only or m[0] in args.only.split(",")]
    results = []
    for name, what, edits, tests in chosen:
        start = time.time()
        originals = {}
        applied = True
        for path, old, new in edits:
            full = os.path.join(src, path)
            text = originals.get(path) or open(full).read()
            originals.setdefault(path, text)
            current = open(full).read()
            if current.count(old) != 1:
                applied = False
                break
            open(full, "w").write(current.replace(old, new))
        verdict = "not applied (the text is not there once)"
        evidence = {}
        if applied:
            if sh(["cmake", "--build", build, "-j2"], src, log, 3600):
                verdict = "killed (does not build)"
            else:
                failed = sh(["ctest", "-R", tests, "-j2", "--timeout", "600"], build, log, 3600)
                evidence = failed_checks(build)
                verdict = "killed" if failed else "SURVIVED"
                if not failed and evidence["skipped_tests"]:
                    verdict = "inconclusive (%d tests skipped)" % evidence["skipped_tests"]
        for path, text in originals.items():
            open(os.path.join(src, path), "w").write(text)
        seconds = time.time() - start
        print("%-28s %-9s %5.0f s  %s" % (name, verdict.split(" ")[0], seconds, what), flush=True)
        results.append({"mutant": name, "breaks": what, "verdict": verdict, "tests": tests,
                        "seconds": round(seconds), **evidence})
        if evidence.get("skipped_tests"):
            print("    %d tests skipped" % evidence["skipped_tests"], flush=True)
        if evidence.get("failed_tests"):
            print("    failed: %s" % ", ".join(evidence["failed_tests"]), flush=True)
            print("    against the CPU reference: %d failed checks, against the stored baselines: "
                  "%d" % (evidence["reference_checks_failed"], evidence["baseline_images_failed"]),
                  flush=True)
    sh(["cmake", "--build", build, "-j2"], src, log, 3600)  # leave the tree built unmutated
    if args.json:
        with open(args.json, "w") as f:
            json.dump(results, f, indent=1)
    survived = [r["mutant"] for r in results if r["verdict"] == "SURVIVED"]
    print("%d mutants, %d killed, %d survived %s" % (len(results), len(results) - len(survived),
                                                     len(survived), survived))
    return len(survived)


if __name__ == "__main__":
    sys.exit(main())
