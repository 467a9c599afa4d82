#!/usr/bin/env bash
# Debian's own plain VTK in a private prefix, beside a ParaView whose python3-paraview Conflicts with
# python3-vtk9 (Debian 12: VTK 9.1 beside ParaView 5.11; Debian 13: VTK 9.3 beside ParaView 5.13).
# The six VTK packages are unpacked (dpkg-deb -x), never installed; their other dependencies are
# installed with apt, which may remove nothing. Run as root; idempotent (a complete prefix is reused).
#   scripts/vtk-private-prefix.sh 9.1 /opt/amrsp/vtk-9.1   # install-deps.sh, on Debian 12
#   scripts/vtk-private-prefix.sh 9.3 /opt/amrsp/vtk-9.3   # install-deps-newer.sh, on Debian 13
#   AMRSP_VTK_PREFIX_REFRESH=1   download and unpack again even if the prefix is complete
#   AMRSP_DEPS_LOG_DIR           where the apt logs go (default /tmp/amrsp-install-deps-logs)
# Then VTK_DIR=PREFIX/usr/lib/<multiarch>/cmake/vtk-VERSION, and PREFIX/.amrsp/stamp holds the
# packages' Debian version (scripts/build.sh pins the Debian package's Depends to it).
set -Eeuo pipefail
version=${1:?usage: vtk-private-prefix.sh VTK_VERSION PREFIX (e.g. 9.1 /opt/amrsp/vtk-9.1)}
prefix=${2:?usage: vtk-private-prefix.sh VTK_VERSION PREFIX}
prefix=${prefix%/}
log() { printf '[vtk%s] %s\n' "$version" "$*"; }
die() { printf '[vtk%s] ERROR: %s\n' "$version" "$*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "must run as root (it uses apt-get and writes $prefix)"
case "$prefix" in /?*) ;; *) die "the prefix must be an absolute path, got '$prefix'" ;; esac
case "$version" in [0-9].[0-9]*) ;; *) die "VTK_VERSION must be MAJOR.MINOR, got '$version'" ;; esac
multiarch=$(dpkg-architecture -qDEB_HOST_MULTIARCH 2>/dev/null || echo x86_64-linux-gnu)
vtk_dir=$prefix/usr/lib/$multiarch/cmake/vtk-$version
meta=$prefix/.amrsp
log_dir=${AMRSP_DEPS_LOG_DIR:-/tmp/amrsp-install-deps-logs}
mkdir -p "$log_dir"
export DEBIAN_FRONTEND=noninteractive
apt_common=(-q -o DPkg::Lock::Timeout=600 -o Acquire::Check-Valid-Until=false)
apt_install=("${apt_common[@]}" -y --no-install-recommends
  -o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold)
t0=$SECONDS

# VTK-targets.cmake checks that every imported file exists, and those files come from all six
# (python3-vtk9: the Python modules and vtkWrapPython; vtk9: vtkWrapHierarchy; libvtk9-java:
# vtkWrapJava/vtkParseJava; the -qt package: the Qt libraries).
packages=(libvtk9-dev "libvtk$version" "libvtk$version-qt" vtk9 python3-vtk9 libvtk9-java)
# Dependencies of those six that apt does not install: the VTK packages themselves, and default-jdk
# (a Depends of libvtk9-dev for Java wrapping only: vtk-config.cmake never loads VTKJava-targets.cmake,
# so no JDK is needed to configure or build against this VTK).
deps_exclude="^(libvtk9(\\.${version#*.})?(-dev|-java|-qt)?|vtk9|python3-vtk9|default-jdk)( |$)"

candidate() {
  apt-cache policy libvtk9-dev 2>/dev/null | sed -n 's/^ *Candidate: //p'
}

prefix_complete() {
  [ -f "$meta/stamp" ] && [ -f "$meta/apt-deps.txt" ] && [ -f "$vtk_dir/vtk-config.cmake" ]
}

unpack() {
  local debian_version tmp dl p f n=0 args=()
  debian_version=$(candidate)
  if [ -z "$debian_version" ] || [ "$debian_version" = "(none)" ]; then
    apt-get "${apt_common[@]}" update >"$log_dir/apt-update-vtk$version.log" 2>&1 \
      || die "apt-get update failed (log: $log_dir/apt-update-vtk$version.log)"
    debian_version=$(candidate)
  fi
  [ -n "$debian_version" ] && [ "$debian_version" != "(none)" ] || die "no candidate for libvtk9-dev in the apt lists"
  case "$debian_version" in "$version".*|*really"$version".*) ;;
    *) die "libvtk9-dev's candidate is $debian_version, expected VTK $version" ;; esac
  log "downloading ${packages[*]} = $debian_version"
  dl=$(mktemp -d "/tmp/amrsp-vtk$version-debs.XXXXXX")
  chmod 755 "$dl"; chown _apt "$dl" 2>/dev/null || true  # apt downloads sandboxed as _apt
  for p in "${packages[@]}"; do args+=("$p=$debian_version"); done
  if ! (cd "$dl" && apt-get "${apt_common[@]}" download "${args[@]}") >"$log_dir/apt-download-vtk$version.log" 2>&1; then
    tail -n 20 "$log_dir/apt-download-vtk$version.log" >&2
    die "apt-get download failed (log: $log_dir/apt-download-vtk$version.log)"
  fi
  tmp="$prefix.tmp.$$"
  rm -rf "$tmp"; mkdir -p "$tmp/.amrsp"
  log "unpacking into $prefix"
  for p in "${packages[@]}"; do dpkg-deb -x "$dl/${p}_"*.deb "$tmp"; done
  # their dependencies, less the excluded ones, as one `apt-get satisfy` string (versions and
  # alternatives as the packages state them)
  for p in "${packages[@]}"; do dpkg-deb -f "$dl/${p}_"*.deb Depends | tr ',' '\n'; done \
    | sed 's/^ *//; s/ *$//' | grep -v '^$' | grep -vE "$deps_exclude" | sort -u | paste -sd, - \
    >"$tmp/.amrsp/apt-deps.txt"
  # Debian's VTK libraries have no RUNPATH (they live in /usr/lib): their own dependencies
  # (libvtkCommonCore -> libvtksys ...) would not be found from the prefix. $ORIGIN makes it
  # self-contained, with no LD_LIBRARY_PATH (the prefix's bin/ tools have $ORIGIN/../lib/<multiarch>).
  while IFS= read -r -d '' f; do
    patchelf --set-rpath '$ORIGIN' "$f"; n=$((n + 1))
  done < <(find "$tmp/usr/lib/$multiarch" -maxdepth 1 -type f -name 'libvtk*.so.*' -print0)
  log "set RUNPATH \$ORIGIN on $n libraries"
  printf 'version=%s\npackages=%s\nrunpath=$ORIGIN\n' "$debian_version" "${packages[*]}" >"$tmp/.amrsp/stamp"
  rm -rf "$prefix"
  mkdir -p "$(dirname "$prefix")"
  mv "$tmp" "$prefix"
  rm -rf "$dl"
}

log "Debian's VTK $version in the private prefix $prefix"
if prefix_complete && [ "${AMRSP_VTK_PREFIX_REFRESH:-0}" != 1 ]; then
  log "prefix already complete ($(sed -n 's/^version=//p' "$meta/stamp"))"
else
  unpack
fi
deps=$(cat "$meta/apt-deps.txt")
# `apt-get satisfy` takes the Depends syntax as is; a simulation tells whether anything is missing
if ! sim=$(apt-get -s "${apt_install[@]}" satisfy "$deps" 2>&1); then
  apt-get "${apt_common[@]}" update >"$log_dir/apt-update-vtk$version.log" 2>&1 || true
  sim=$(apt-get -s "${apt_install[@]}" satisfy "$deps" 2>&1) \
    || { printf '%s\n' "$sim" | tail -n 20 >&2; die "apt cannot satisfy the dependencies of VTK $version"; }
fi
removed=$(printf '%s\n' "$sim" | awk '/^Remv /{print $2}' | tr '\n' ' ')
[ -z "$removed" ] || die "its dependencies would REMOVE: $removed-- refusing (a conflict with ParaView?)"
if printf '%s\n' "$sim" | grep -q '^Inst '; then
  log "installing its dependencies: $(printf '%s\n' "$sim" | awk '/^Inst /{print $2}' | tr '\n' ' ')"
  apt-get "${apt_install[@]}" satisfy "$deps" >"$log_dir/apt-vtk$version-deps.log" 2>&1 \
    || { tail -n 30 "$log_dir/apt-vtk$version-deps.log" >&2; die "apt-get failed (log: $log_dir/apt-vtk$version-deps.log)"; }
else
  log "its dependencies are already installed"
fi
# every library resolves, and none of ParaView's own VTK (libvtk*-pvX.Y) comes in
lib=$prefix/usr/lib/$multiarch
bad=$(ldd "$lib/libvtkRenderingOpenGL2-$version.so.1" "$lib/libvtkIOAMR-$version.so.1" | grep -E 'not found|-pv[0-9]' || true)
[ -z "$bad" ] || die "the libraries do not resolve cleanly: $bad"
log "VTK_DIR=$vtk_dir"
log "done in $((SECONDS - t0)) s"
