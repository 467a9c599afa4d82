#!/usr/bin/env bash
# Renders with the bundled amrsp on an NVIDIA GPU through EGL (no X server) and prints what the
# README's GPU figures are made of: every method against the CPU reference on the real datasets,
# the shading features, then the paper's dataset 3 and a billion cells with times and peak memory.
#
#   ./gpu-check.sh [quick]        (in the folder scripts/gpu-bundle.sh made; about 5 min, quick 40 s)
#   ./gpu-check.sh profile [OUT.json]
#                                 the GPU profile (docs/performance.md, "The GPU profile"): the
#                                 target table at 1024x1024 (the fragment and the compute caster,
#                                 each with nested and flat ray loops, against multipass on the
#                                 paper's datasets 1-3 and a billion cells; bench --rounds 3,
#                                 orbits of 8 frames, GPU time from timer queries, the cost-model
#                                 counters and the occupancy probe), the other storages and the
#                                 automatic choices on dataset 3, a time series of dataset 2
#                                 (bench --time-series, 512x512), the real datasets and ablations
#                                 on dataset 3, in one JSON (default gpu-profile.json); fits 9
#                                 minutes (AMRSP_PROFILE_SECONDS, default 500, bounds the run)
#
# Test hooks (Tool.GpuProfile runs the profile's logic on this machine): AMRSP_PROFILE_TOOL runs
# that amrsp instead of the bundled one (no EGL vendor file needed), AMRSP_PROFILE_DATA is the
# real data's folder instead of the bundle's, and AMRSP_PROFILE_SMOKE=1 shrinks every run (small
# synthetic sets, 32x32, one frame).
#
# A machine whose driver is not under /usr/local/nvidia: set AMRSP_EGL_VENDOR_JSON to its
# glvnd vendor file (10_nvidia.json).
set -uo pipefail
here=$(cd "$(dirname "$0")" && pwd)
nv=/usr/local/nvidia
if [ -n "${AMRSP_PROFILE_TOOL:-}" ]; then
  amrsp=("$AMRSP_PROFILE_TOOL")
else
  export __EGL_VENDOR_LIBRARY_FILENAMES=${AMRSP_EGL_VENDOR_JSON:-$nv/share/glvnd/egl_vendor.d/10_nvidia.json}
  [ -f "$__EGL_VENDOR_LIBRARY_FILENAMES" ] || { echo "FAIL: no EGL vendor file $__EGL_VENDOR_LIBRARY_FILENAMES"; exit 1; }
  unset DISPLAY
  amrsp=("$here/lib/ld-linux-x86-64.so.2" --library-path "$here/lib:$nv/lib64:$nv/lib:/usr/lib/x86_64-linux-gnu" "$here/amrsp")
fi
data=${AMRSP_PROFILE_DATA:-$here/data}
keep='^device\|^storage\|^mapper\|^frames\|^rmse\|error\|warn\|Not a valid'
# peak resident memory of one command (python's getrusage of its child)
peak() {
  python3 -c 'import resource, subprocess, sys, time
t = time.time(); r = subprocess.run(sys.argv[1:])
print("wall %.2f s, peak RSS %.3f GB, exit %d" % (time.time() - t, resource.getrusage(resource.RUSAGE_CHILDREN).ru_maxrss / 1e6, r.returncode))' "$@"
}
enzo=$data/enzo_moving7/DD0010/moving7_0010.hierarchy
if [ "${1:-}" = profile ]; then
  out=${2:-$PWD/gpu-profile.json}
  work=$(mktemp -d)
  budget=${AMRSP_PROFILE_SECONDS:-500}
  start=$SECONDS
  ds1=synthetic:cosmo:grids=2666,levels=4,cells=19M
  ds2=synthetic:cosmo:grids=18528,levels=4,cells=33M
  ds3=synthetic:cosmo:grids=39061,levels=13,cells=140M
  billion=synthetic:cosmo:grids=280000,levels=13,cells=1000M
  size=1024x1024 frames=8 few=4 seriesSize=512x512
  if [ "${AMRSP_PROFILE_SMOKE:-0}" = 1 ]; then
    ds1=synthetic:cosmo:grids=30,levels=3,cells=60k ds2=synthetic:cosmo:grids=40,levels=2,cells=50k
    ds3=synthetic:cosmo:grids=60,levels=5,cells=80k billion=synthetic:cosmo:grids=20,levels=2,cells=20k
    size=32x32 frames=1 few=1 seriesSize=32x32
  fi
  target=(--size "$size" --sample-factor 1 --rounds 3 --frames "$frames" --no-compare)
  # the target table: both casters with both ray loops against multipass, the packed atlas
  casters=packing:fragment-nested,packing:fragment-flat,packing:compute-nested,packing:compute-flat,multipass
  # the other storages and the automatic choices, with the compute caster
  storages=bindless:compute-flat,linear:compute-flat,auto-storage:auto-auto,multipass
  # one bench run: NAME LIMIT_S ARGS...; its JSON and log land in $work, the run list in runs.tsv
  bench() {
    local name=$1 limit=$2 left
    shift 2
    left=$((budget - (SECONDS - start)))
    [ "$left" -lt "$limit" ] && limit=$left
    if [ "$limit" -lt 15 ]; then
      printf '%s\t%s\t%s\t%s\n' "$name" skipped 0 "$*" >>"$work/runs.tsv"
      echo "--- $name: skipped, the profile's $budget s are spent"
      return
    fi
    echo "--- $name (at most $limit s): bench $*"
    local t0=$SECONDS rc=0
    timeout "$limit" "${amrsp[@]}" bench "$@" --json "$work/$name.json" --quiet \
      >"$work/$name.log" 2>&1 || rc=$?
    printf '%s\t%s\t%s\t%s\n' "$name" "$rc" "$((SECONDS - t0))" "$*" >>"$work/runs.tsv"
    tail -n 3 "$work/$name.log"
  }
  : >"$work/runs.tsv"
  # the target table, the most important first: GPU time from timer queries, the cost-model
  # counters, and the occupancy probe (how many SMs and warps each caster's rays ran on)
  bench dataset3 110 "$ds3" --methods "$casters" "${target[@]}" --counters --occupancy
  bench billion 170 "$billion" --methods "$casters" --size "$size" --sample-factor 1 \
    --rounds 2 --frames "$few" --no-compare --counters --occupancy
  bench dataset2 60 "$ds2" --methods "$casters" "${target[@]}" --counters --occupancy
  bench dataset1 45 "$ds1" --methods "$casters" "${target[@]}" --counters --occupancy
  bench storages-dataset3 70 "$ds3" --methods "$storages" "${target[@]}" --counters
  # time series: a step switch (new values, same hierarchy) against a regrid, dataset 2 at 512x512
  # over 8 steps (the time-series issue's target: step_switch_s <= 0.5 x rebuild_s)
  bench time-series-dataset2 40 "$ds2,steps=8,regrid=4" --time-series \
    --methods packing:auto-auto,bindless:auto-auto,linear:auto-auto,multipass --size "$seriesSize"
  for d in "$enzo" "$data/amrex_plt1_Y" "$data"/vthb_hierarchicalbox/*.vthb \
    "$data"/chombo3d_vtm/chombo3d.vtm; do
    [ -e "$d" ] && bench "real-$(basename "$d" | cut -d. -f1)" 25 "$d" \
      --methods packing:compute-flat,packing:fragment-nested,multipass "${target[@]}"
  done
  # ablations on dataset 3 (the cost of each part) with the compute caster: orbits of 4 frames,
  # two rounds
  ablate=(--size "$size" --sample-factor 1 --rounds 2 --frames "$few" --no-compare --caster compute)
  bench ablation-traversal-only 45 "$ds3" --methods packing,bindless,linear "${ablate[@]}" \
    --loop flat --ablation traversal-only --counters
  bench ablation-sampling-only 45 "$ds3" --methods packing,bindless,linear "${ablate[@]}" \
    --loop flat --ablation sampling-only:256 --counters
  bench ablation-no-ropes 45 "$ds3" --methods packing:compute-flat,packing:compute-nested,multipass \
    "${ablate[@]}" --ropes off --counters
  bench ablation-no-skipping 35 "$ds3" --methods packing:compute-flat,multipass "${ablate[@]}" \
    --empty-space-skipping off
  bench ablation-no-termination 35 "$ds3" --methods packing:compute-flat,multipass "${ablate[@]}" \
    --opacity-threshold 1
  driver=$(nvidia-smi --query-gpu=name,driver_version --format=csv,noheader 2>/dev/null | head -n 1)
  python3 - "$work" "$out" "$here/VERSION" "$driver" "$budget" "$((SECONDS - start))" <<'PY'
import json, os, sys, time
work, out, version, driver, budget, spent = sys.argv[1:7]
profile = {"profile": {
    "commit": open(version).read().strip() if os.path.exists(version) else "unknown",
    "date": time.strftime("%Y-%m-%d %H:%M:%S UTC", time.gmtime()),
    "nvidia_smi": driver, "budget_s": int(budget), "seconds": int(spent),
    "target": "1024x1024, nearest, sample factor 1, bench --rounds 3 orbits of 8 frames"},
  "runs": {}}
for line in open(os.path.join(work, "runs.tsv")):
    name, rc, seconds, args = line.rstrip("\n").split("\t", 3)
    run = {"args": args, "exit": rc, "seconds": int(seconds)}
    path = os.path.join(work, name + ".json")
    if rc == "skipped":
        run["error"] = "not run: the profile's time was spent"
    elif os.path.exists(path) and os.path.getsize(path) > 0:
        run["bench"] = json.load(open(path))
    else:
        log = open(os.path.join(work, name + ".log"), errors="replace").read()
        run["error"] = ("timed out" if rc == "124" else "exit " + rc) + ": " + log[-2000:]
    profile["runs"][name] = run
# The target table (issue "The whole GPU"): per dataset and method the GPU time per frame (the
# median over the rounds of the timer queries), frames a second from it, the ratio to multipass,
# the lockstep steps per pixel of the cost model and where the rays ran (the occupancy probe).
table = {}
for run in ("dataset3", "billion", "dataset2", "dataset1"):
    methods = profile["runs"].get(run, {}).get("bench", {}).get("methods", {})
    rows = {}
    multipass = methods.get("multipass", {}).get("gpu_ms_rounds_median")
    for name, m in methods.items():
        if "error" in m:
            rows[name] = {"error": m["error"]}
            continue
        gpu = m.get("gpu_ms_rounds_median")
        row = {"caster": m.get("caster"), "loop": m.get("loop"), "gpu_ms": gpu,
               "fps": 1000.0 / gpu if gpu else None,
               "vs_multipass": multipass / gpu if gpu and multipass else None,
               "lockstep_steps_per_pixel": m.get("work", {}).get(
                   "flat_loop_lockstep_steps_per_pixel" if m.get("loop") == "flat"
                   else "lockstep_steps_per_pixel")}
        occupancy = m.get("occupancy")
        if occupancy:
            row["sms"] = occupancy.get("sms") if occupancy.get("available") else None
            row["warps"] = occupancy.get("warps") if occupancy.get("available") else None
        rows[name] = row
    table[run] = rows
profile["target_table"] = table


def best(run):
    rows = [r for n, r in table.get(run, {}).items() if n != "multipass" and r.get("fps")]
    return max(rows, key=lambda r: r["fps"]) if rows else None


targets = {}
for run, fps in (("dataset3", 60.0), ("billion", 20.0)):
    b = best(run)
    targets["%s_fps_at_least_%d" % (run, fps)] = {"met": bool(b and b["fps"] >= fps),
                                                    "best": b}
for run in ("dataset1", "dataset2", "dataset3", "billion"):
    b = best(run)
    targets["%s_single_pass_3x_multipass" % run] = {
        "met": bool(b and b.get("vs_multipass") and b["vs_multipass"] >= 3.0),
        "vs_multipass": b.get("vs_multipass") if b else None}
compute_sms = [r.get("sms") for rows in table.values() for r in rows.values()
               if r.get("caster") == "compute" and r.get("sms") is not None]
targets["compute_on_100_sms"] = {"met": bool(compute_sms and min(compute_sms) >= 100),
                                 "sms": compute_sms}
profile["targets"] = targets
json.dump(profile, open(out, "w"), indent=1)
for run, rows in table.items():
    for name, r in rows.items():
        if "error" in r:
            print("%-9s %-24s error: %s" % (run, name, r["error"][:80]))
            continue
        print("%-9s %-24s gpu %s ms, %s fps, x%s multipass, %s lockstep steps/px, %s SMs, %s warps"
              % (run, name, r["gpu_ms"], r["fps"] and round(r["fps"], 1),
                 r["vs_multipass"] and round(r["vs_multipass"], 2),
                 r["lockstep_steps_per_pixel"], r.get("sms"), r.get("warps")))
for name, target in targets.items():
    print("target %-40s %s" % (name, "met" if target["met"] else "NOT met"))
print("wrote", out)
PY
  exit 0
fi
echo "=== real datasets, 256x256: RMSE (0-255) against the CPU reference and the CPU kD-tree"
for d in "$enzo" "$here/data/amrex_plt1_Y" "$here"/data/vthb_hierarchicalbox/*.vthb synthetic:pulse; do
  for m in packing bindless linear multipass; do
    echo "--- $(basename "$d") $m"
    timeout 120 "${amrsp[@]}" render "$d" --method "$m" --size 256x256 --compare --quiet 2>&1 | grep -i "$keep"
  done
done
echo "=== features (Enzo, bindless)"
for o in "--shade on" "--blend iso --iso 0.3,0.6" "--shadows 0.05" "--interpolation smooth" "--blend maximum" "--centering vertex" "--bindless-access waterfall"; do
  echo "--- $o"
  # shellcheck disable=SC2086
  timeout 120 "${amrsp[@]}" render "$enzo" --method bindless --size 256x256 --compare --quiet $o 2>&1 | grep -i "rmse\|error\|Not a valid"
done
[ "${1:-}" = quick ] && exit 0
echo "=== paper dataset 3, 512x512, 5 frames"
for m in packing bindless linear multipass; do
  echo "--- $m"
  timeout 300 peak "${amrsp[@]}" render synthetic:cosmo:grids=39061,levels=13,cells=140M --method "$m" --size 512x512 --repeat 5 --quiet 2>&1 | grep -i "$keep\|peak"
done
echo "=== a billion cells, 512x512, 3 frames"
for m in packing bindless linear multipass; do
  echo "--- $m"
  timeout 300 peak "${amrsp[@]}" render synthetic:cosmo:grids=280000,levels=13,cells=1000M --method "$m" --size 512x512 --repeat 3 --quiet 2>&1 | grep -i "$keep\|peak"
done
