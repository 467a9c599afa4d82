#!/usr/bin/env bash
# Install what the project needs on Debian 13 trixie (ParaView 5.13 with its bundled VTK 9.3, and
# Debian's plain VTK 9.3 in a private prefix) or on Debian testing forky (ParaView 6.1 on the system
# VTK 9.6, plus plain VTK 9.6). Run as root; idempotent (a second run only refreshes the package
# lists once a day and installs what is missing).
# scripts/install-deps.sh runs this on those systems; scripts/debian-root.sh runs it inside a root.
#
# trixie's python3-paraview Conflicts with python3-vtk9, as on Debian 12: the trixie-vtk configuration
# builds against VTK 9.3 unpacked into $AMRSP_VTK93_PREFIX (default /opt/amrsp/vtk-9.3) by
# scripts/vtk-private-prefix.sh.
# Besides the packages it repairs two things the Debian packages need (see fix_python_suffixes and
# osmesa_prefix below):
#   - paraview-dev's CMake files (5.13 and 6.1) name ParaView's and VTK's Python modules without their
#     ABI suffix, so find_package(ParaView) fails: a symbolic link per module, named as CMake expects;
#   - forky: Mesa 25.1 dropped OSMesa, so Debian 13's libosmesa6 (Mesa 25.0) and the two libraries
#     it needs that forky no longer has are unpacked into $AMRSP_OSMESA_PREFIX (default
#     /opt/amrsp/osmesa), never installed: VTK 9.6 loads libOSMesa.so.8 at run time when
#     VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow and LD_LIBRARY_PATH names that folder.
set -Eeuo pipefail
SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
. "$SCRIPT_DIR/configs.sh"
log() { printf '[install-deps] %s\n' "$*"; }
die() { printf '[install-deps] ERROR: %s\n' "$*" >&2; exit 1; }
[ "$(id -u)" = 0 ] || die "must run as root (it uses apt-get)"
suite=$(amrsp_host_suite)
multiarch=$(amrsp_multiarch)
export DEBIAN_FRONTEND=noninteractive
APT=(apt-get -q -y -o DPkg::Lock::Timeout=600 -o Acquire::Check-Valid-Until=false)
T_START=$SECONDS

# Build and test tools, and the X server used by ParaView builds that render through GLX only.
PKGS=(cmake g++ make ninja-build pkg-config patchelf file libgtest-dev libgmock-dev libglm-dev
  nlohmann-json3-dev python3-numpy xvfb xauth x11-utils mesa-utils
  # glslangValidator (Mapper.ShaderVariants)
  glslang-tools
  # Mesa: llvmpipe through GLX and EGL, zink on lavapipe (bindless textures) through Vulkan
  libgl1-mesa-dri libglx-mesa0 libegl-mesa0 libegl1 libgl-dev libegl-dev libopengl-dev
  mesa-vulkan-drivers
  # ParaView, and what find_package(ParaView) loads when a plugin configures: Qt 6, MPI, HDF5,
  # Python, the XML documentation tools
  paraview paraview-dev python3-paraview mpi-default-bin mpi-default-dev python3-dev python3-mpi4py
  libhdf5-openmpi-dev xsltproc qt6-base-dev qt6-base-dev-tools qt6-svg-dev qt6-tools-dev
  qt6-5compat-dev libqt6opengl6-dev)
case "$suite" in
  # ParaView 5.13's bundled VTK asks for these when a plugin configures
  # (paraview-5.13/vtk/VTK-vtk-module-find-packages.cmake)
  trixie) PKGS+=(libutfcpp-dev libeigen3-dev libboost-dev libexpat1-dev liblzma-dev liblz4-dev
    libdouble-conversion-dev libjpeg-dev libtiff-dev libfreetype-dev zlib1g-dev libpng-dev libxml2-dev
    libtheora-dev libogg-dev libgl2ps-dev libnetcdf-dev libglew-dev libx11-dev libxt-dev) ;;
  forky) PKGS+=(libvtk9-dev) ;;  # plain VTK 9.6: the VTK ParaView 6.1 is built on
  *) die "$(amrsp_unsupported)" ;;
esac

missing=()
for p in "${PKGS[@]}"; do
  [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$p" 2>/dev/null)" = "ii " ] || missing+=("$p")
done
stamp=/var/lib/apt/amrsp-updated
if [ "${#missing[@]}" -gt 0 ] || [ -z "$(find "$stamp" -mmin -1440 2>/dev/null)" ]; then
  log "apt-get update ($suite)"
  "${APT[@]}" update >/tmp/amrsp-apt-update.log 2>&1 || { tail -n 20 /tmp/amrsp-apt-update.log >&2; die "apt-get update failed"; }
  touch "$stamp"
fi
if [ "${#missing[@]}" -gt 0 ]; then
  log "installing ${#missing[@]} packages: ${missing[*]}"
  t=$SECONDS
  "${APT[@]}" install --no-install-recommends "${missing[@]}" >/tmp/amrsp-apt-install.log 2>&1 \
    || { tail -n 30 /tmp/amrsp-apt-install.log >&2; die "apt-get install failed (log: /tmp/amrsp-apt-install.log)"; }
  log "installed in $((SECONDS - t)) s"
else
  log "all ${#PKGS[@]} packages already installed"
fi

# paraview-dev's imported targets name Python extension modules as .../NAME.so while the packages
# ship .../NAME.cpython-3XY-<multiarch>.so: CMake checks that every imported file exists, so
# find_package(ParaView) fails. Each such missing file becomes a link to the module that exists.
fix_python_suffixes() {
  local f missing_so real n=0
  while IFS= read -r f; do
    missing_so=$f
    [ -e "$missing_so" ] && continue
    real=$(ls "${missing_so%.so}".cpython-*.so 2>/dev/null | head -n 1 || true)
    [ -n "$real" ] || continue
    ln -s "$(basename "$real")" "$missing_so"
    n=$((n + 1))
  done < <(grep -rhoE '"\$\{_IMPORT_PREFIX\}/lib/python3/dist-packages/[^"]+\.so"' \
             /usr/lib/"$multiarch"/cmake/paraview-* /usr/lib/"$multiarch"/cmake/vtk* 2>/dev/null \
           | tr -d '"' | sed 's|${_IMPORT_PREFIX}|/usr|' | sort -u)
  log "python module links made for paraview-dev's CMake files: $n"
}
fix_python_suffixes

# forky: Debian 13's libOSMesa in a private prefix (see the header). Package lists of trixie are kept
# apart from the system's (own sources, lists and cache folders), so the system's apt state is untouched.
osmesa_prefix() {
  local prefix=$AMRSP_OSMESA_PREFIX dir=/var/cache/amrsp/trixie-apt mirror deb
  if [ -e "$prefix/usr/lib/$multiarch/libOSMesa.so.8" ]; then
    log "OSMesa: $prefix already unpacked"
    return 0
  fi
  mirror=$(awk '$1 == "deb" {print $2; exit}' /etc/apt/sources.list 2>/dev/null || true)
  [ -n "$mirror" ] || mirror=$(awk '/^URIs:/{print $2; exit}' /etc/apt/sources.list.d/*.sources 2>/dev/null || true)
  [ -n "$mirror" ] || die "OSMesa: no Debian mirror found in the apt sources"
  mkdir -p "$dir/lists/partial" "$dir/cache/archives/partial" "$dir/debs"
  printf 'deb %s trixie main\n' "$mirror" >"$dir/sources.list"
  local opts=(-o "Dir::Etc::sourcelist=$dir/sources.list" -o Dir::Etc::sourceparts=- \
    -o "Dir::State::Lists=$dir/lists" -o "Dir::Cache=$dir/cache" -o Acquire::Check-Valid-Until=false)
  log "OSMesa: Debian 13's libosmesa6 into $prefix"
  apt-get -q "${opts[@]}" update >/tmp/amrsp-osmesa-apt.log 2>&1 \
    || { tail -n 20 /tmp/amrsp-osmesa-apt.log >&2; die "OSMesa: apt-get update of trixie's lists failed"; }
  # libosmesa6 and the libraries of its dependencies that forky does not have under the same soname
  (cd "$dir/debs" && rm -f ./*.deb && apt-get -q "${opts[@]}" download libosmesa6 libllvm19 libxml2 \
     >>/tmp/amrsp-osmesa-apt.log 2>&1) \
    || { tail -n 20 /tmp/amrsp-osmesa-apt.log >&2; die "OSMesa: apt-get download failed"; }
  rm -rf "$prefix.tmp"
  mkdir -p "$prefix.tmp"
  for deb in "$dir"/debs/*.deb; do dpkg -x "$deb" "$prefix.tmp"; done
  rm -rf "$prefix"
  mkdir -p "$(dirname "$prefix")"
  mv "$prefix.tmp" "$prefix"
  local unresolved
  unresolved=$(LD_LIBRARY_PATH="$prefix/usr/lib/$multiarch" ldd "$prefix/usr/lib/$multiarch/libOSMesa.so.8" | grep 'not found' || true)
  [ -z "$unresolved" ] || die "OSMesa: libOSMesa.so.8 does not resolve: $unresolved"
  log "OSMesa: LD_LIBRARY_PATH=$prefix/usr/lib/$multiarch VTK_DEFAULT_OPENGL_WINDOW=vtkOSOpenGLRenderWindow"
}
[ "$suite" != forky ] || osmesa_prefix
# trixie: Debian's VTK 9.3 in the trixie-vtk configuration's private prefix (configs.sh names it)
read -r private_vtk private_prefix <<<"$(amrsp_private_vtk trixie-vtk)"
if [ "$suite" = trixie ]; then
  "$SCRIPT_DIR/vtk-private-prefix.sh" "$private_vtk" "$private_prefix" | sed 's/^/[install-deps] /'
fi

log "all done in $((SECONDS - T_START)) s"
log "ParaView $(dpkg-query -W -f='${Version}' paraview), VTK $(dpkg-query -W -f='${Version}' libvtk9-dev 2>/dev/null || echo "bundled with ParaView; plain VTK in $private_prefix")"
