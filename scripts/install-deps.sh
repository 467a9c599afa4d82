#!/usr/bin/env bash
# shellcheck disable=SC1091,SC2015,SC2016  # os-release sourced on purpose; '$ORIGIN' is literal on purpose
# Install everything this project needs on Debian 12 (bookworm). Run as root; idempotent; no prompts.
# On Debian 13 (trixie) or Debian testing (forky) it runs scripts/install-deps-newer.sh instead.
#
#   scripts/install-deps.sh            # install / check (a second run only checks: a few seconds)
#   scripts/install-deps.sh --verify   # also build and run the tiny CMake projects (VTK 9.1 and ParaView 5.11)
#
# Parts, in the order they run (all bookworm packages first, the Mesa upgrade from backports last):
#   1. Debian packages: build tools, GoogleTest, Xvfb, ParaView 5.11 (+ its bundled VTK 9.2) and every -dev
#      package that ParaView's CMake config asks for at configure time of a plugin.
#   2. Debian's plain VTK 9.1 (libvtk9-dev) unpacked into a private prefix (it conflicts with python3-paraview,
#      so it cannot be installed normally); its non-conflicting dependencies are installed with apt
#      (scripts/vtk-private-prefix.sh, which Debian 13's VTK 9.3 shares).
#      VTK_DIR=$AMRSP_VTK91_PREFIX/usr/lib/<multiarch>/cmake/vtk-9.1
#   3. Mesa 25 from bookworm-backports (zink on lavapipe: GL 4.6 + GL_ARB_bindless_texture), checked with glxinfo.
# Nothing is ever removed: every apt step is simulated first and refused if it would remove a package.
# See scripts/DEPENDENCIES.md for the CMake usage and what was measured.
#
# Environment:
#   AMRSP_VTK91_PREFIX    prefix for VTK 9.1 (default /opt/amrsp/vtk-9.1)
#   AMRSP_VTK91_REFRESH=1 re-download and re-unpack VTK 9.1 even if the prefix is complete
#   AMRSP_ENZO_HIERARCHY  Enzo file read by --verify (default <repo>/../shared/data/enzo_moving7/DD0010/moving7_0010.hierarchy)
#   AMRSP_DEPS_LOG_DIR    where apt/cmake logs go (default /tmp/amrsp-install-deps-logs)
set -Eeuo pipefail

SCRIPT_DIR=$(cd "$(dirname "${BASH_SOURCE[0]}")" && pwd)
REPO_DIR=$(cd "$SCRIPT_DIR/.." && pwd)
VERIFY=0
for arg in "$@"; do
  case "$arg" in
    --verify) VERIFY=1 ;;
    -h|--help) sed -n '3,/^set -Eeuo/p' "${BASH_SOURCE[0]}" | sed '$d; s/^# \{0,1\}//'; exit 0 ;;
    *) echo "install-deps: unknown argument '$arg' (try --help)" >&2; exit 2 ;;
  esac
done

log() { printf '[install-deps] %s\n' "$*"; }
die() { printf '[install-deps] ERROR: %s\n' "$*" >&2; exit 1; }
on_err() { printf '[install-deps] ERROR: command failed (exit %s) at line %s: %s\n' "$1" "$2" "$3" >&2; exit "$1"; }
trap 'on_err $? $LINENO "$BASH_COMMAND"' ERR

[ "$(id -u)" = 0 ] || die "must run as root (it uses apt-get and writes ${AMRSP_VTK91_PREFIX:-/opt/amrsp/vtk-9.1})"
. /etc/os-release
case "${VERSION_CODENAME:-}" in
  bookworm) ;;
  # Debian 13 and testing have their own package lists (ParaView 5.13; ParaView 6.1 on VTK 9.6)
  trixie|forky) exec "$SCRIPT_DIR/install-deps-newer.sh" "$@" ;;
  *) die "this is '${PRETTY_NAME:-unknown}'; supported: Debian 12 bookworm, Debian 13 trixie, Debian testing forky" ;;
esac
case "$(dpkg --print-architecture)" in
  amd64) MULTIARCH=x86_64-linux-gnu ;;
  arm64) MULTIARCH=aarch64-linux-gnu ;;
  *) die "unsupported architecture $(dpkg --print-architecture)" ;;
esac

export DEBIAN_FRONTEND=noninteractive
VTK91_PREFIX=${AMRSP_VTK91_PREFIX:-/opt/amrsp/vtk-9.1}
VTK91_PREFIX=${VTK91_PREFIX%/}
case "$VTK91_PREFIX" in /?*) ;; *) die "AMRSP_VTK91_PREFIX must be an absolute path, got '$VTK91_PREFIX'" ;; esac
VTK91_DIR=$VTK91_PREFIX/usr/lib/$MULTIARCH/cmake/vtk-9.1
LOG_DIR=${AMRSP_DEPS_LOG_DIR:-/tmp/amrsp-install-deps-logs}
mkdir -p "$LOG_DIR"
BACKPORTS_LIST=/etc/apt/sources.list.d/amrsp-bookworm-backports.list
APT_COMMON=(-q -o DPkg::Lock::Timeout=600)
APT_INSTALL=("${APT_COMMON[@]}" -y --no-install-recommends
             -o Dpkg::Options::=--force-confdef -o Dpkg::Options::=--force-confold)
T_START=$SECONDS

# ---------------------------------------------------------------------------------------------------- packages
# Build and test tools.
PKGS_BUILD=(cmake g++ make ninja-build pkg-config patchelf clang-format libgtest-dev libgmock-dev libglm-dev nlohmann-json3-dev)
# glslangValidator: Mapper.ShaderVariants checks every single-pass shader variant with it.
PKGS_BUILD+=(glslang-tools)
# The Debian 13 and testing roots of scripts/debian-root.sh (configurations trixie-*, forky-*).
PKGS_BUILD+=(debootstrap)
# The vtk configuration's Python wrapping (Wrapping/Python: Python.h) and its test (numpy), for
# the system python3 that Debian's python3-vtk9 is built for
PKGS_BUILD+=(python3-dev python3-numpy)
# Headless GLX rendering.
PKGS_X=(xvfb xauth x11-utils mesa-utils)
# ParaView 5.11 (with its own VTK 9.2); mpi-default-bin gives mpiexec for pvbatch (a Recommends of paraview).
PKGS_PARAVIEW=(paraview paraview-dev python3-paraview mpi-default-bin)
# What find_package(ParaView) (paraview-config.cmake -> *-vtk-module-find-packages.cmake) looks for when a
# plugin project configures, package by package (checked with the --verify projects on a bare bookworm):
#   Qt5 Core/Gui/Network/Widgets/Svg/Help/OpenGL, xmlpatterns (server-manager XML documentation),
#   Boost 1.74 EXACT, HDF5 C+HL, MPI C, Python3 Development, OpenGL/GLX, GLEW, X11, EXPAT, LZMA, LZ4,
#   double-conversion, JPEG, TIFF, Freetype, ZLIB, PNG, LibXml2, utf8cpp, Eigen3, THEORA, FFMPEG, GL2PS,
#   NetCDF, GDAL, mpi4py.
PKGS_PARAVIEW_CMAKE=(qtbase5-dev libqt5svg5-dev qttools5-dev libqt5opengl5-dev qtxmlpatterns5-dev-tools
  libboost-dev libhdf5-dev mpi-default-dev python3-dev python3-mpi4py
  libgl-dev libglx-dev libopengl-dev libglew-dev libx11-dev libxt-dev
  libexpat1-dev liblzma-dev liblz4-dev libdouble-conversion-dev libjpeg-dev libtiff-dev libfreetype-dev
  zlib1g-dev libpng-dev libxml2-dev libutfcpp-dev libeigen3-dev libtheora-dev libogg-dev
  libavformat-dev libavcodec-dev libavutil-dev libswscale-dev libswresample-dev
  libgl2ps-dev libnetcdf-dev libgdal-dev)
# Mesa from bookworm-backports (installed with -t bookworm-backports).
PKGS_MESA=(libgl1-mesa-dri libglx-mesa0 libegl-mesa0 mesa-vulkan-drivers)
MESA_MIN_VERSION=25
# ---------------------------------------------------------------------------------------------------- helpers
APT_UPDATED=0
apt_update_once() {
  [ "$APT_UPDATED" = 1 ] && return 0
  log "apt-get update"
  if ! apt-get "${APT_COMMON[@]}" update >"$LOG_DIR/apt-update.log" 2>&1; then
    tail -n 20 "$LOG_DIR/apt-update.log" >&2
    die "apt-get update failed (log: $LOG_DIR/apt-update.log)"
  fi
  APT_UPDATED=1
}

is_installed() { [ "$(dpkg-query -W -f='${db:Status-Abbrev}' "$1" 2>/dev/null)" = "ii " ]; }

missing_packages() {  # prints the packages of "$@" that are not installed (one dpkg-query for all)
  local p installed
  installed=$(dpkg-query -W -f='${Package} ${db:Status-Abbrev}\n' "$@" 2>/dev/null | awk '$2 == "ii" {print $1}' || true)
  for p in "$@"; do grep -qxF "$p" <<<"$installed" || printf '%s\n' "$p"; done
}

# apt_run LABEL APT-GET-ARGS...: simulate first and refuse anything that would remove a package (e.g. ParaView);
# then download (timed) and install (timed), with the output in log files.
apt_run() {
  local label=$1; shift
  local sim removed t
  if ! sim=$(apt-get -s "${APT_INSTALL[@]}" "$@" 2>&1); then
    printf '%s\n' "$sim" | tail -n 25 >&2
    die "apt cannot satisfy $label (simulation failed)"
  fi
  removed=$(printf '%s\n' "$sim" | awk '/^Remv /{print $2}' | tr '\n' ' ')
  [ -z "$removed" ] || die "installing $label would REMOVE: $removed-- refusing (check for a conflict with ParaView)"
  log "$label: $(printf '%s\n' "$sim" | grep -cE '^Inst ') packages to install/upgrade"
  t=$SECONDS
  if ! apt-get "${APT_INSTALL[@]}" --download-only "$@" >"$LOG_DIR/apt-$label-download.log" 2>&1; then
    tail -n 25 "$LOG_DIR/apt-$label-download.log" >&2
    die "apt-get download failed for $label (log: $LOG_DIR/apt-$label-download.log)"
  fi
  log "$label: downloaded in $((SECONDS - t)) s ($(grep -oE '^Fetched .*' "$LOG_DIR/apt-$label-download.log" || echo 'nothing fetched'))"
  t=$SECONDS
  if ! apt-get "${APT_INSTALL[@]}" "$@" >"$LOG_DIR/apt-$label.log" 2>&1; then
    tail -n 25 "$LOG_DIR/apt-$label.log" >&2
    die "apt-get failed for $label (log: $LOG_DIR/apt-$label.log)"
  fi
  log "$label: installed in $((SECONDS - t)) s"
}

# Run a command with a working X display: the caller's DISPLAY if it answers, else a private xvfb-run server.
display_works() {
  [ -n "${DISPLAY:-}" ] && env -u MESA_LOADER_DRIVER_OVERRIDE -u LIBGL_ALWAYS_SOFTWARE xdpyinfo >/dev/null 2>&1
}
with_x() {
  if display_works; then "$@"; else xvfb-run -a -s "-screen 0 1280x1024x24" "$@"; fi
}

mesa_is_new_enough() {
  local p v
  for p in "${PKGS_MESA[@]}"; do
    v=$(dpkg-query -W -f='${Version}' "$p" 2>/dev/null) || return 1
    is_installed "$p" || return 1
    dpkg --compare-versions "$v" ge "$MESA_MIN_VERSION" || return 1
  done
}

backports_configured() {
  local f
  for f in /etc/apt/sources.list /etc/apt/sources.list.d/*.list; do
    [ -f "$f" ] && grep -qE '^[[:space:]]*deb[[:space:]].*[[:space:]]bookworm-backports([[:space:]]|$)' "$f" && return 0
  done
  for f in /etc/apt/sources.list.d/*.sources; do
    [ -f "$f" ] && grep -qE '^[[:space:]]*Suites:.*[[:space:]]bookworm-backports([[:space:]]|$)' "$f" && return 0
  done
  return 1
}

# ---------------------------------------------------------------------------------------------------- part 1
part_packages() {
  local t0=$SECONDS missing
  log "[packages] Debian packages (build tools, GoogleTest, Xvfb, ParaView 5.11 + its CMake dependencies)"
  mapfile -t missing < <(missing_packages "${PKGS_BUILD[@]}" "${PKGS_X[@]}" "${PKGS_PARAVIEW[@]}" "${PKGS_PARAVIEW_CMAKE[@]}")
  if [ "${#missing[@]}" -eq 0 ]; then
    log "[packages] all $(( ${#PKGS_BUILD[@]} + ${#PKGS_X[@]} + ${#PKGS_PARAVIEW[@]} + ${#PKGS_PARAVIEW_CMAKE[@]} )) packages already installed"
  else
    apt_update_once
    log "[packages] installing ${#missing[@]} packages: ${missing[*]}"
    apt_run packages install "${missing[@]}"
  fi
  is_installed python3-paraview || die "python3-paraview is not installed after part 1"
  log "[packages] done in $((SECONDS - t0)) s"
}

# ---------------------------------------------------------------------------------------------------- part 2
part_mesa() {
  local t0=$SECONDS
  log "[mesa] Mesa >= $MESA_MIN_VERSION from bookworm-backports (zink + lavapipe)"
  if ! backports_configured; then
    log "[mesa] adding $BACKPORTS_LIST"
    echo 'deb [signed-by=/usr/share/keyrings/debian-archive-keyring.gpg] http://deb.debian.org/debian bookworm-backports main' \
      >"$BACKPORTS_LIST"
    APT_UPDATED=0
  fi
  if mesa_is_new_enough; then
    log "[mesa] Mesa $(dpkg-query -W -f='${Version}' libgl1-mesa-dri) already installed"
  else
    if ! apt-cache policy libgl1-mesa-dri 2>/dev/null | grep -q bookworm-backports; then APT_UPDATED=0; fi
    apt_update_once
    log "[mesa] installing -t bookworm-backports ${PKGS_MESA[*]}"
    apt_run mesa install -t bookworm-backports "${PKGS_MESA[@]}"
    mesa_is_new_enough || die "Mesa is still older than $MESA_MIN_VERSION after the install: $(dpkg-query -W -f='${Version}' libgl1-mesa-dri)"
  fi
  is_installed python3-paraview || die "ParaView was removed by the Mesa upgrade"

  log "[mesa] checking GL under X with glxinfo"
  local xdg out core ext
  xdg=$(mktemp -d /tmp/amrsp-xdg.XXXXXX); chmod 700 "$xdg"
  out=$(with_x env -u MESA_LOADER_DRIVER_OVERRIDE -u LIBGL_ALWAYS_SOFTWARE glxinfo -B 2>&1) \
    || { printf '%s\n' "$out" >&2; rm -rf "$xdg"; die "glxinfo failed (plain Mesa)"; }
  core=$(printf '%s\n' "$out" | sed -n 's/^OpenGL core profile version string: //p')
  printf '%s\n' "$out" | grep -q 'OpenGL renderer string: llvmpipe' && [[ $core == 4.5* || $core == 4.6* ]] \
    || { printf '%s\n' "$out" >&2; rm -rf "$xdg"; die "plain Mesa is not llvmpipe with GL >= 4.5"; }
  log "[mesa] plain: $(printf '%s\n' "$out" | sed -n 's/^OpenGL renderer string: //p'), core $core"
  out=$(with_x env MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1 XDG_RUNTIME_DIR="$xdg" glxinfo 2>&1) \
    || { printf '%s\n' "$out" | tail -n 20 >&2; rm -rf "$xdg"; die "glxinfo failed with zink"; }
  rm -rf "$xdg"
  core=$(printf '%s\n' "$out" | sed -n 's/^OpenGL core profile version string: //p')
  # Extensions of the core profile context only (glxinfo also lists the compatibility profile's).
  ext=$(printf '%s\n' "$out" | awk '/^OpenGL core profile extensions:/{f=1;next} /^OpenGL version string/{f=0} f')
  [[ $core == 4.6* ]] || { printf '%s\n' "$out" | grep -E 'renderer|version' >&2; die "zink does not give GL 4.6 core (got '$core')"; }
  for e in GL_ARB_bindless_texture GL_ARB_shader_ballot; do
    printf '%s\n' "$ext" | grep -qw "$e" || die "zink core profile lacks $e"
  done
  log "[mesa] zink: $(printf '%s\n' "$out" | sed -n 's/^OpenGL renderer string: //p'), core $core, bindless + ballot present"
  log "[mesa] done in $((SECONDS - t0)) s"
}

# ---------------------------------------------------------------------------------------------------- part 3
# Debian 12's plain VTK 9.1 in its private prefix (python3-paraview Conflicts with python3-vtk9)
part_vtk91() {
  AMRSP_VTK_PREFIX_REFRESH=${AMRSP_VTK91_REFRESH:-0} AMRSP_DEPS_LOG_DIR=$LOG_DIR \
    "$SCRIPT_DIR/vtk-private-prefix.sh" 9.1 "$VTK91_PREFIX" | sed 's/^/[install-deps] /'
}

# ---------------------------------------------------------------------------------------------------- verify
write_verify_projects() {  # $1 = directory
  local d=$1
  mkdir -p "$d/mod/Trivial" "$d/v91" "$d/pvmod" "$d/pvplug/Plugin"
  cat >"$d/mod/Trivial/vtk.module" <<'EOF'
NAME
  AMRSP::Trivial
LIBRARY_NAME
  amrspTrivial
DEPENDS
  VTK::CommonDataModel
  VTK::CommonExecutionModel
PRIVATE_DEPENDS
  VTK::CommonCore
EOF
  cat >"$d/mod/Trivial/CMakeLists.txt" <<'EOF'
vtk_module_add_module(AMRSP::Trivial CLASSES vtkAmrspTrivialSource)
EOF
  cat >"$d/mod/Trivial/vtkAmrspTrivialSource.h" <<'EOF'
#ifndef vtkAmrspTrivialSource_h
#define vtkAmrspTrivialSource_h
#include "amrspTrivialModule.h" // export macro
#include "vtkPolyDataAlgorithm.h"
class AMRSPTRIVIAL_EXPORT vtkAmrspTrivialSource : public vtkPolyDataAlgorithm
{
public:
  static vtkAmrspTrivialSource* New();
  vtkTypeMacro(vtkAmrspTrivialSource, vtkPolyDataAlgorithm);
  vtkSetMacro(NumberOfPoints, int);
  vtkGetMacro(NumberOfPoints, int);

protected:
  vtkAmrspTrivialSource();
  ~vtkAmrspTrivialSource() override = default;
  int RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector*) override;
  int NumberOfPoints = 3;

private:
  vtkAmrspTrivialSource(const vtkAmrspTrivialSource&) = delete;
  void operator=(const vtkAmrspTrivialSource&) = delete;
};
#endif
EOF
  cat >"$d/mod/Trivial/vtkAmrspTrivialSource.cxx" <<'EOF'
#include "vtkAmrspTrivialSource.h"
#include "vtkInformationVector.h"
#include "vtkObjectFactory.h"
#include "vtkPoints.h"
#include "vtkPolyData.h"
vtkStandardNewMacro(vtkAmrspTrivialSource);
vtkAmrspTrivialSource::vtkAmrspTrivialSource() { this->SetNumberOfInputPorts(0); }
int vtkAmrspTrivialSource::RequestData(vtkInformation*, vtkInformationVector**, vtkInformationVector* out)
{
  vtkPolyData* pd = vtkPolyData::GetData(out);
  vtkPoints* pts = vtkPoints::New();
  for (int i = 0; i < this->NumberOfPoints; ++i)
  {
    pts->InsertNextPoint(i, 0, 0);
  }
  pd->SetPoints(pts);
  pts->Delete();
  return 1;
}
EOF
  # --- plain VTK 9.1
  cat >"$d/v91/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(amrsp_verify_vtk91 C CXX) # C: VTK's FindHDF5 try_compiles a C file
find_package(VTK 9.1 REQUIRED COMPONENTS CommonCore CommonDataModel CommonExecutionModel
  FiltersAMR IOAMR IOXML IOImage IOLegacy RenderingCore RenderingOpenGL2 RenderingVolume
  RenderingVolumeOpenGL2 InteractionStyle RenderingUI TestingRendering TestingCore FiltersSources)
message(STATUS "VTK_VERSION=${VTK_VERSION}")
set(BUILD_SHARED_LIBS ON)
include(GNUInstallDirs)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR})
set(CMAKE_LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR})
vtk_module_scan(MODULE_FILES ${CMAKE_CURRENT_SOURCE_DIR}/../mod/Trivial/vtk.module
  REQUEST_MODULES AMRSP::Trivial PROVIDES_MODULES amrsp_modules ENABLE_TESTS OFF)
vtk_module_build(MODULES ${amrsp_modules})
add_executable(check91 check91.cxx)
target_link_libraries(check91 PRIVATE AMRSP::Trivial ${VTK_LIBRARIES})
vtk_module_autoinit(TARGETS check91 MODULES ${VTK_LIBRARIES})
EOF
  cat >"$d/v91/check91.cxx" <<'EOF'
#include "vtkAMREnzoReader.h"
#include "vtkAMRGaussianPulseSource.h"
#include "vtkAMReXGridReader.h"
#include "vtkActor.h"
#include "vtkAmrspTrivialSource.h"
#include "vtkCubeSource.h"
#include "vtkNew.h"
#include "vtkOverlappingAMR.h"
#include "vtkPNGWriter.h"
#include "vtkPolyData.h"
#include "vtkPolyDataMapper.h"
#include "vtkRenderWindow.h"
#include "vtkRenderer.h"
#include "vtkVersion.h"
#include "vtkWindowToImageFilter.h"
#include <cstdio>
#include <cstring>
int main(int argc, char** argv)
{
  if (argc < 3) { std::printf("usage: check91 ENZO_HIERARCHY|- OUT.png\n"); return 2; }
  std::printf("VTK version %s\n", vtkVersion::GetVTKVersion());
  vtkNew<vtkAmrspTrivialSource> src;
  src->SetNumberOfPoints(5);
  src->Update();
  std::printf("trivial source points %lld\n", static_cast<long long>(src->GetOutput()->GetNumberOfPoints()));
  vtkNew<vtkAMRGaussianPulseSource> pulse;
  pulse->Update();
  auto* pamr = vtkOverlappingAMR::SafeDownCast(pulse->GetOutputDataObject(0));
  std::printf("vtkAMRGaussianPulseSource levels %u blocks %u\n", pamr->GetNumberOfLevels(), pamr->GetTotalNumberOfBlocks());
  vtkNew<vtkAMReXGridReader> amrex;
  std::printf("vtkAMReXGridReader exists: %s\n", amrex->GetClassName());
  if (std::strcmp(argv[1], "-") != 0)
  {
    vtkNew<vtkAMREnzoReader> r;
    r->SetFileName(argv[1]);
    r->SetMaxLevel(30);
    r->UpdateInformation();
    r->SetCellArrayStatus("Density", 1);
    r->Update();
    auto* amr = vtkOverlappingAMR::SafeDownCast(r->GetOutputDataObject(0));
    if (!amr) { std::printf("Enzo reader gave no vtkOverlappingAMR\n"); return 1; }
    std::printf("Enzo levels %u blocks %u\n", amr->GetNumberOfLevels(), amr->GetTotalNumberOfBlocks());
    if (amr->GetNumberOfLevels() != 8 || amr->GetTotalNumberOfBlocks() != 10) return 1;
  }
  vtkNew<vtkCubeSource> cube;
  vtkNew<vtkPolyDataMapper> mapper;
  mapper->SetInputConnection(cube->GetOutputPort());
  vtkNew<vtkActor> actor;
  actor->SetMapper(mapper);
  actor->RotateX(30);
  actor->RotateY(40);
  vtkNew<vtkRenderer> ren;
  ren->AddActor(actor);
  ren->SetBackground(0.1, 0.2, 0.4);
  vtkNew<vtkRenderWindow> win;
  win->SetOffScreenRendering(1);
  win->AddRenderer(ren);
  win->SetSize(200, 200);
  win->Render();
  std::printf("render window %s\n", win->GetClassName());
  vtkNew<vtkWindowToImageFilter> w2i;
  w2i->SetInput(win);
  w2i->Update();
  vtkNew<vtkPNGWriter> png;
  png->SetFileName(argv[2]);
  png->SetInputConnection(w2i->GetOutputPort());
  png->Write();
  return 0;
}
EOF
  # --- ParaView's VTK 9.2: the same module, built with vtk_module_scan/vtk_module_build
  cat >"$d/pvmod/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(amrsp_verify_pvmod C CXX)
find_package(ParaView REQUIRED)
message(STATUS "ParaView_VERSION=${ParaView_VERSION} VTK_VERSION=${VTK_VERSION}")
set(BUILD_SHARED_LIBS ON)
include(GNUInstallDirs)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR})
set(CMAKE_LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR})
vtk_module_scan(MODULE_FILES ${CMAKE_CURRENT_SOURCE_DIR}/../mod/Trivial/vtk.module
  REQUEST_MODULES AMRSP::Trivial PROVIDES_MODULES amrsp_modules ENABLE_TESTS OFF)
vtk_module_build(MODULES ${amrsp_modules})
add_executable(checkpv checkpv.cxx)
target_link_libraries(checkpv PRIVATE AMRSP::Trivial VTK::CommonCore VTK::RenderingOpenGL2
  VTK::RenderingVolumeOpenGL2 VTK::RenderingVolumeAMR)
vtk_module_autoinit(TARGETS checkpv MODULES VTK::RenderingOpenGL2 VTK::RenderingVolumeOpenGL2)
EOF
  cat >"$d/pvmod/checkpv.cxx" <<'EOF'
#include "vtkAMRVolumeMapper.h"
#include "vtkAmrspTrivialSource.h"
#include "vtkNew.h"
#include "vtkPolyData.h"
#include "vtkVersion.h"
#include <cstdio>
int main()
{
  std::printf("VTK version %s\n", vtkVersion::GetVTKVersion());
  vtkNew<vtkAmrspTrivialSource> src;
  src->SetNumberOfPoints(4);
  src->Update();
  vtkNew<vtkAMRVolumeMapper> amrMapper;
  std::printf("trivial source points %lld, %s exists\n",
    static_cast<long long>(src->GetOutput()->GetNumberOfPoints()), amrMapper->GetClassName());
  return src->GetOutput()->GetNumberOfPoints() == 4 ? 0 : 1;
}
EOF
  # --- ParaView plugin wrapping the module, with one server-manager XML
  cat >"$d/pvplug/CMakeLists.txt" <<'EOF'
cmake_minimum_required(VERSION 3.16)
project(amrsp_verify_pvplug C CXX)
find_package(ParaView REQUIRED)
set(BUILD_SHARED_LIBS ON)
include(GNUInstallDirs)
set(CMAKE_RUNTIME_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_BINDIR})
set(CMAKE_LIBRARY_OUTPUT_DIRECTORY ${CMAKE_BINARY_DIR}/${CMAKE_INSTALL_LIBDIR})
paraview_plugin_scan(PLUGIN_FILES ${CMAKE_CURRENT_SOURCE_DIR}/Plugin/paraview.plugin
  PROVIDES_PLUGINS amrsp_plugins ENABLE_BY_DEFAULT ON)
paraview_plugin_build(PLUGINS ${amrsp_plugins}
  RUNTIME_DESTINATION ${CMAKE_INSTALL_BINDIR} LIBRARY_DESTINATION ${CMAKE_INSTALL_LIBDIR}
  LIBRARY_SUBDIRECTORY paraview-plugins)
EOF
  cat >"$d/pvplug/Plugin/paraview.plugin" <<'EOF'
NAME
  AmrspTrivialPlugin
DESCRIPTION
  Trivial plugin that checks the ParaView plugin toolchain.
REQUIRES_MODULES
  VTK::CommonDataModel
  VTK::CommonExecutionModel
EOF
  cat >"$d/pvplug/Plugin/CMakeLists.txt" <<'EOF'
paraview_add_plugin(AmrspTrivialPlugin
  VERSION "1.0"
  MODULES AMRSP::Trivial
  MODULE_FILES "${CMAKE_CURRENT_SOURCE_DIR}/../../mod/Trivial/vtk.module"
  SERVER_MANAGER_XML AmrspTrivial.xml)
EOF
  cat >"$d/pvplug/Plugin/AmrspTrivial.xml" <<'EOF'
<ServerManagerConfiguration>
  <ProxyGroup name="sources">
    <SourceProxy name="AmrspTrivialSource" class="vtkAmrspTrivialSource" label="AMRSP Trivial Source">
      <IntVectorProperty name="NumberOfPoints" command="SetNumberOfPoints" number_of_elements="1" default_values="3">
      </IntVectorProperty>
    </SourceProxy>
  </ProxyGroup>
</ServerManagerConfiguration>
EOF
  cat >"$d/pvplug/load.py" <<'EOF'
import sys
from paraview.simple import *
LoadPlugin(sys.argv[1], remote=False, ns=globals())
# paraview.simple names the function after the proxy's *label* with spaces removed: "AMRSP Trivial Source"
s = AMRSPTrivialSource(NumberOfPoints=7)
s.UpdatePipeline()
n = s.GetDataInformation().GetNumberOfPoints()
print("plugin source points", n)
sys.exit(0 if n == 7 else 1)
EOF
}

cmake_build() {  # $1 = label, $2 = source dir, rest = extra configure args
  local label=$1 src=$2; shift 2
  local gen=()
  command -v ninja >/dev/null 2>&1 && gen=(-G Ninja)
  if ! cmake -S "$src" -B "$src/build" "${gen[@]}" -DCMAKE_BUILD_TYPE=Release "$@" >"$LOG_DIR/verify-$label-configure.log" 2>&1; then
    tail -n 30 "$LOG_DIR/verify-$label-configure.log" >&2; die "verify: configure of $label failed (log: $LOG_DIR/verify-$label-configure.log)"
  fi
  if ! cmake --build "$src/build" -j "$(nproc)" >"$LOG_DIR/verify-$label-build.log" 2>&1; then
    tail -n 30 "$LOG_DIR/verify-$label-build.log" >&2; die "verify: build of $label failed (log: $LOG_DIR/verify-$label-build.log)"
  fi
}

verify() {
  local t0=$SECONDS d out enzo plugin
  d=$(mktemp -d /tmp/amrsp-verify.XXXXXX)
  log "verify: building the check projects in $d"
  write_verify_projects "$d"

  enzo=${AMRSP_ENZO_HIERARCHY:-$REPO_DIR/../shared/data/enzo_moving7/DD0010/moving7_0010.hierarchy}
  if [ ! -f "$enzo" ]; then
    log "verify: WARNING: $enzo not found, skipping the Enzo read (set AMRSP_ENZO_HIERARCHY)"
    enzo=-
  fi
  cmake_build vtk91 "$d/v91" -DVTK_DIR="$VTK91_DIR"
  out=$(with_x "$d/v91/build/bin/check91" "$enzo" "$d/cube91.png" 2>&1) || { printf '%s\n' "$out" >&2; die "verify: check91 failed"; }
  printf '%s\n' "$out" | sed 's/^/[install-deps]   vtk91: /'
  printf '%s\n' "$out" | grep -q '^VTK version 9\.1\.' || die "verify: check91 did not run VTK 9.1"
  if ldd "$d/v91/build/bin/check91" | grep -E 'not found|pv5\.11'; then die "verify: check91 links something wrong (above)"; fi
  ldd "$d/v91/build/bin/check91" | grep -q "$VTK91_PREFIX/usr/lib/$MULTIARCH/libvtkCommonCore-9.1.so" \
    || die "verify: check91 does not load libvtkCommonCore from $VTK91_PREFIX"
  [ -s "$d/cube91.png" ] || die "verify: no PNG written"
  log "verify: VTK 9.1 OK (module built, libraries from $VTK91_PREFIX, PNG $d/cube91.png)"

  cmake_build pvmod "$d/pvmod"
  out=$(with_x "$d/pvmod/build/bin/checkpv" 2>&1) || { printf '%s\n' "$out" >&2; die "verify: checkpv failed"; }
  printf '%s\n' "$out" | sed 's/^/[install-deps]   paraview-vtk: /'
  printf '%s\n' "$out" | grep -q '^VTK version 9\.2\.' || die "verify: checkpv did not run ParaView's VTK 9.2"
  log "verify: module against ParaView's VTK OK"

  cmake_build pvplug "$d/pvplug"
  plugin=$(find "$d/pvplug/build" -name 'AmrspTrivialPlugin.so' | head -n 1)
  [ -n "$plugin" ] || die "verify: plugin library not found"
  out=$(with_x pvpython "$d/pvplug/load.py" "$plugin" 2>&1) || { printf '%s\n' "$out" >&2; die "verify: pvpython LoadPlugin failed"; }
  printf '%s\n' "$out" | sed 's/^/[install-deps]   pvpython: /'
  log "verify: ParaView plugin builds and loads in pvpython ($plugin)"
  log "verify: done in $((SECONDS - t0)) s (projects left in $d)"
}

# ---------------------------------------------------------------------------------------------------- main
# Order matters: everything from plain bookworm first, the Mesa upgrade from backports last (a bookworm -dev
# package installed after it could want the old Mesa's exact version).
part_packages
part_vtk91
part_mesa
if [ "$VERIFY" = 1 ]; then verify; fi
log "all done in $((SECONDS - T_START)) s"
log "VTK 9.1:       -DVTK_DIR=$VTK91_DIR"
log "ParaView 5.11: find_package(ParaView) finds /usr/lib/$MULTIARCH/cmake/paraview-5.11 by itself"
log "headless GL:   . scripts/start-xvfb.sh   (zink: MESA_LOADER_DRIVER_OVERRIDE=zink LIBGL_ALWAYS_SOFTWARE=1 XDG_RUNTIME_DIR=<private dir>)"
