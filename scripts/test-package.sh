#!/usr/bin/env bash
# Installs the Debian package of one configuration (scripts/package.sh CONFIG) the way a user would,
# `apt-get install ./<package>.deb`, into a copy of a *clean* root of the configuration's release
# (debootstrap minbase and nothing else: scripts/debian-root.sh SUITE clean-ensure), and renders
# with what it installed. Run as root on a Debian 12 host.
#   scripts/test-package.sh CONFIG   # paraview, vtk, trixie-paraview, trixie-vtk, forky-paraview, forky-vtk
# Checks (each prints ok or FAIL; the last line is the summary for scripts/test.sh):
#   install   apt-get resolves the package's exact ParaView/VTK dependency from the release
#             (`apt-get satisfy` of its Depends in the clean root) and then `apt-get install ./x.deb`
#             adds the package and nothing else, with --no-install-recommends: the Depends alone
#             must make the checks below pass (a user's default install also brings the
#             Recommends; half the packages, half the time)
#   files     `dpkg -L` lists nothing outside /usr/{bin,include,lib,share} and /etc/profile.d
#             (the check is first shown to reject a list with a file in /opt)
#   pvpython  ParaView packages: python3-paraview installs (pvpython is the checks' tool; paraview
#             only Recommends it, and the plugin needs only paraview)
#   plugin    ParaView packages: pvpython, started from a login shell (/etc/profile.d) with no
#             LoadPlugin, has the plugin and renders the image the build tree's plugin renders
#             (Testing/Package/CheckPluginPackage.py; it rejects the camera turned by 2 degrees);
#             the same pvpython started without the login shell does not have it (control)
#   python    VTK packages: the README's VTK Python example, run as written with the installed
#             `singlepassamr`, against `amrsp reference` of the installed tool (RMSE bound and its
#             two controls: Testing/Python/TestDocumentedVtkPython.py)
#   tool      VTK packages: the installed `amrsp render --compare` within Tool.CLI.RenderPacking's
#             bounds of its CPU reference
# The package's dependencies are installed once into a copy of the clean root, its *dependencies
# root* ($AMRSP_ROOTS_DIR/deps-CONFIG), with `apt-get satisfy` of the package's Depends field; the
# checks run in a throwaway layer over it (an overlay mount; a full copy where overlays cannot be
# mounted), deleted afterwards (AMRSP_KEEP_PACKAGE_ROOT=1 keeps a copy instead). The dependencies
# root is made again whenever the clean root or the Depends field changes, so every run installs
# the package into exactly the root a first run would: its install check then requires that the
# package is the only package apt adds. It is deleted after the test when less than
# AMRSP_DEPS_ROOT_MIN_FREE_GB (default 20) GB stay free. Package downloads go to the build root's
# apt cache (the host's for Debian 12), so they happen once.
set -Eeuo pipefail
repo=$(cd "$(dirname "${BASH_SOURCE[0]}")/.." && pwd)
. "$repo/scripts/configs.sh"
config=${1:?usage: scripts/test-package.sh CONFIG}
suite=$(amrsp_config_suite "$config") || { echo "[package-test] unknown configuration $config" >&2; exit 2; }
[ "$config" != sanitizers ] || { echo "[package-test] sanitizers has no package" >&2; exit 2; }
summary=${AMRSP_SUMMARY_FILE:-$repo/build/test-summary.txt}
roots=${AMRSP_ROOTS_DIR:-/var/cache/amrsp/roots}
out="$repo/build/packages/$config"
log="$out/test.log"
t0=$SECONDS
passed=0 failed=0
mkdir -p "$out"
: >"$log"
say() { echo "$*" | tee -a "$log"; }
check() {  # NAME DESCRIPTION: records the result of the command that just ran ($rc)
  if [ "$rc" = 0 ]; then passed=$((passed + 1)); say "ok: $1: $2"; else failed=$((failed + 1)); say "FAIL: $1: $2"; fi
}
finish() {
  local total=$((passed + failed))
  local line="[summary] $config package: $passed passed, $failed failed, 0 skipped of $total checks in $((SECONDS - t0)) s ($deb_name in a clean $suite root)"
  echo "$line" | tee -a "$log"
  echo "$line" >>"$summary"
  [ "${AMRSP_KEEP_PACKAGE_ROOT:-0}" = 1 ] || remove_scratch
  # a dependencies root (1 to 2.5 GB) is kept only where the disk keeps room for the others
  local free_gb
  free_gb=$(df -P -BG "$roots" 2>/dev/null | awk 'NR == 2 {sub("G", "", $4); print $4}')
  if [ -d "$deps" ] && [ "${free_gb:-0}" -lt "${AMRSP_DEPS_ROOT_MIN_FREE_GB:-20}" ]; then
    rm -rf "$deps"
    say "dependencies root deleted: ${free_gb:-?} GB free, under AMRSP_DEPS_ROOT_MIN_FREE_GB=${AMRSP_DEPS_ROOT_MIN_FREE_GB:-20} (the next run makes it again)"
  fi
  [ "$failed" = 0 ] && [ "$total" -gt 0 ]
}
scratch=$roots/package-test-$config
deps=$roots/deps-$config
remove_scratch() {  # the throwaway layer: unmounted first, so that nothing below it is touched
  ! mountpoint -q "$scratch" 2>/dev/null || umount "$scratch" || umount -l "$scratch"
  rm -rf "$scratch" "$scratch.upper" "$scratch.work"
}
deb_name="no package"
if [ "$(amrsp_host_suite)" != bookworm ]; then
  echo "[package-test] clean roots are made on a Debian 12 host; this is $(amrsp_host_suite)" >&2
  exit 2
fi
debs=("$out"/*.deb)
if [ ! -f "${debs[0]}" ]; then
  rc=1; check install "no .deb in $out (scripts/package.sh $config)"; finish; exit 1
fi
deb=${debs[0]}
deb_name=$(basename "$deb")
package=$(dpkg-deb -f "$deb" Package)

"$repo/scripts/debian-root.sh" "$suite" clean-ensure >>"$log" 2>&1 \
  || { rc=1; check install "the clean $suite root could not be made (log: $log)"; finish; exit 1; }
if [ "$suite" = bookworm ]; then archives=/var/cache/apt/archives; else archives=$roots/$suite/var/cache/apt/archives; fi
apt_in() {  # ROOT ARGS...: apt-get ARGS inside ROOT
  local dir=$1; shift
  AMRSP_ROOT_DIR=$dir AMRSP_ROOT_APT_ARCHIVES=$archives "$repo/scripts/debian-root.sh" "$suite" run \
    env DEBIAN_FRONTEND=noninteractive apt-get -q -y -o Acquire::Check-Valid-Until=false "$@"
}
in_root() { AMRSP_ROOT_DIR=$scratch AMRSP_ROOT_APT_ARCHIVES=$archives "$repo/scripts/debian-root.sh" "$suite" run "$@"; }
set +e

# the dependencies root: the clean root with the package's Depends, as apt resolves them there
depends=$(dpkg-deb -f "$deb" Depends)
clean=$roots/clean-$suite
key="clean root made $(stat -c %y "$clean/.amrsp-clean" 2>/dev/null); Depends: $depends"
t=$SECONDS
if [ "$(cat "$deps/.amrsp-deps-key" 2>/dev/null)" = "$key" ]; then
  deps_how="reused (made $(stat -c %y "$deps/.amrsp-deps-key" | cut -d. -f1))"
else
  rm -rf "$deps" "$deps.new"
  cp -a "$clean" "$deps.new"
  apt_in "$deps.new" satisfy --no-install-recommends "$depends" >"$out/apt-deps.log" 2>&1
  rc=$?
  deps_how="made: $(grep -oE '^[0-9]+ upgraded, [0-9]+ newly installed' "$out/apt-deps.log" || echo 'see apt-deps.log') in $((SECONDS - t)) s"
  if [ "$rc" != 0 ]; then
    check install "apt-get satisfy --no-install-recommends '$depends' in a copy of the clean $suite root failed"
    tail -n 20 "$out/apt-deps.log" | tee -a "$log"; rm -rf "$deps.new"; finish; exit 1
  fi
  printf '%s\n' "$key" >"$deps.new/.amrsp-deps-key"
  mv "$deps.new" "$deps"
fi
say "dependencies root $deps: $deps_how"

# the throwaway layer the checks change
remove_scratch
layer="a copy of it"
if [ "${AMRSP_KEEP_PACKAGE_ROOT:-0}" != 1 ] && mkdir -p "$scratch" "$scratch.upper" "$scratch.work" \
    && mount -t overlay amrsp-package-test -o "lowerdir=$deps,upperdir=$scratch.upper,workdir=$scratch.work" \
      "$scratch" 2>/dev/null; then
  layer="an overlay over it"
else
  remove_scratch
  cp -a "$deps" "$scratch"
fi
trap remove_scratch EXIT
[ "${AMRSP_KEEP_PACKAGE_ROOT:-0}" != 1 ] || trap - EXIT
mkdir -p "$scratch/tmp/package"
cp "$deb" "$scratch/tmp/package/"

# install: the package is all that apt adds to its dependencies root
t=$SECONDS
apt_in "$scratch" install --no-install-recommends "/tmp/package/$deb_name" >"$out/apt-install.log" 2>&1
rc=$?
added=$(grep -oE '^[0-9]+ upgraded, [0-9]+ newly installed' "$out/apt-install.log")
[ "$rc" != 0 ] || [ "$added" = "0 upgraded, 1 newly installed" ] || rc=1
check install "apt-get install --no-install-recommends ./$deb_name into the clean root with its Depends ($deps_how), in $layer: ${added:-see apt-install.log} in $((SECONDS - t)) s (Depends: $depends)"
[ "$rc" = 0 ] || { tail -n 20 "$out/apt-install.log" | tee -a "$log"; finish; exit 1; }

# files: only the usual places, the filter itself shown to reject a file in /opt
usual='^/(\.|usr|usr/(bin|include|lib|share)(/.*)?|etc|etc/profile\.d(/.*)?)$'
unusual=$( (in_root dpkg -L "$package"; echo /opt/amrsp/control-entry) | grep -vE "$usual")
if [ "$unusual" = /opt/amrsp/control-entry ]; then rc=0; unusual=; else rc=1; fi
check files "dpkg -L $package: $(in_root dpkg -L "$package" | wc -l) entries, none outside /usr/{bin,include,lib,share} and /etc/profile.d (the filter rejects /opt/amrsp/control-entry)${unusual:+; found: $unusual}"

display_env=()
case "$suite" in
  forky) display_env=(VTK_DEFAULT_OPENGL_WINDOW=vtkEGLRenderWindow) ;;  # no X server
  *) . "$repo/scripts/start-xvfb.sh" >/dev/null 2>&1; display_env=("DISPLAY=$DISPLAY") ;;
esac
require=()
[ "${CI:-}" != true ] || require=(AMRSP_REQUIRE_GPU=1)
case "$config" in
  *paraview)
    # the build tree's plugin renders the expected images, in the build's own environment
    plugin=$(cd "$repo" && ls build/"$config"/lib/paraview-*/plugins/SinglePassAMRPlugin/SinglePassAMRPlugin.so)
    if [ "$suite" = bookworm ]; then
      env "${display_env[@]}" pvpython --force-offscreen-rendering Testing/Package/CheckPluginPackage.py \
        build "$repo/$plugin" "$out/check" >"$out/build-render.log" 2>&1
    else
      "$repo/scripts/debian-root.sh" "$suite" run env "${display_env[@]}" pvpython --force-offscreen-rendering \
        Testing/Package/CheckPluginPackage.py build "$plugin" "build/packages/$config/check" >"$out/build-render.log" 2>&1
    fi
    rc=$?
    check plugin-build-render "the build tree's plugin rendered build.png and build-turned.png"
    [ "$rc" = 0 ] || tail -n 20 "$out/build-render.log" | tee -a "$log"
    # the checks' tool (the plugin needs only paraview): pvpython is in python3-paraview, which
    # paraview only Recommends
    apt_in "$scratch" install --no-install-recommends python3-paraview >>"$out/apt-install.log" 2>&1
    rc=$?
    check pvpython "python3-paraview for pvpython (the checks' tool, not the package's: paraview only Recommends it)"
    # control: a pvpython that did not read /etc/profile.d; it must have run (its FOUND: line)
    probe=$(in_root env "${display_env[@]}" pvpython --force-offscreen-rendering \
      Testing/Package/CheckPluginPackage.py probe 2>&1)
    control=$(printf '%s\n' "$probe" | sed -n 's/^FOUND: //p')
    if ! printf '%s\n' "$probe" | grep -q '^FOUND:'; then
      rc=1; control="no FOUND: line, pvpython did not run: $(printf '%s\n' "$probe" | tail -n 1)"
    else
      [ -z "$control" ]; rc=$?
    fi
    check plugin-control "pvpython started without a login shell has no plugin (found: ${control:-nothing})"
    in_root env "${display_env[@]}" "${require[@]}" bash -lc "pvpython --force-offscreen-rendering \
      Testing/Package/CheckPluginPackage.py installed build/packages/$config/check" >"$out/installed-render.log" 2>&1
    rc=$?
    sed 's/^/  /' "$out/installed-render.log" | grep -E 'proxies|PV_PLUGIN|RMSE|covers|FAIL|Error' | tee -a "$log"
    check plugin "pvpython from a login shell loads the installed plugin at start and renders the build's image" ;;
  *vtk)
    # the check's own tool (the example does not need it): numpy for the image comparison
    apt_in "$scratch" install --no-install-recommends python3-numpy >>"$out/apt-install.log" 2>&1
    rc=$?
    check numpy "python3-numpy for the image comparison (the checks' tool, not the package's)"
    in_root env "${display_env[@]}" "${require[@]}" python3 -c \
      'import singlepassamr, sys; print(singlepassamr.__file__); sys.exit(not singlepassamr.__file__.startswith("/usr/lib/python3/dist-packages/"))' \
      >"$out/import.log" 2>&1
    rc=$?
    check import "python3 imports singlepassamr from $(tail -n 1 "$out/import.log")"
    in_root env "${display_env[@]}" "${require[@]}" python3 Testing/Python/TestDocumentedVtkPython.py \
      README.md /usr/bin/amrsp /amrsp/shared/data /tmp/package/python >"$out/python.log" 2>&1
    rc=$?
    grep -E '^(ok|FAIL)' "$out/python.log" | sed 's/^/  /' | tee -a "$log"
    check python "the README's VTK Python example with the installed package, against the installed amrsp reference"
    in_root env "${display_env[@]}" sh Testing/Tool/expect-at-most.sh "method: packing" "vs cpu-reference:=9" \
      "vs cpu-kdtree:=0.05" -- amrsp render synthetic:pulse --method packing --size 64x64 --compare \
      -o /tmp/package/pulse.png >"$out/tool.log" 2>&1
    rc=$?
    grep -E 'vs cpu|backend:|FAIL' "$out/tool.log" | sed 's/^/  /' | tee -a "$log"
    check tool "the installed amrsp renders within its CPU reference's bounds" ;;
esac
set -e
finish
