# CPack: one Debian package of this build (scripts/package.sh runs cpack; docs/packages.md).
#   ParaView configuration: singlepassamr-paraview-plugin, the plugin (its folder in ParaView's
#     plugin folder, SinglePassAMR.plugins.xml beside it, and /etc/profile.d/singlepassamr-paraview.sh
#     which adds that file to PV_PLUGIN_CONFIG_FILE for login shells: autoload)
#   VTK configuration: singlepassamr-vtk, the VTK module (library, headers, CMake package), its
#     Python package `singlepassamr` and the `amrsp` tool
# Each depends on the exact Debian version of the ParaView or VTK it was built against, read from
# dpkg at configure time (the package owning VTK's CommonCore library, or Debian's `paraview`).
# A VTK that dpkg does not know (a private prefix) names its packages through
# AMRSP_DEBIAN_VTK_DEPENDS; without either the package gets no version pin, and configure says so.
set(AMRSP_DEBIAN_VTK_DEPENDS "" CACHE STRING
  "Debian Depends of the VTK package when dpkg does not own the VTK built against, e.g. \
'libvtk9.1 (= V), python3-vtk9 (= V)'")

# The Debian version of PACKAGE, or "" when dpkg does not have it installed.
function (amrsp_debian_installed_version package out)
  execute_process(COMMAND dpkg-query -W -f=\${Version} "${package}"
    OUTPUT_VARIABLE version ERROR_QUIET RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
  if (NOT rc EQUAL 0)
    set(version "")
  endif ()
  set("${out}" "${version}" PARENT_SCOPE)
endfunction ()

# The Debian package that owns FILE (symbolic links resolved), or "".
function (amrsp_debian_owner file out)
  set(owner "")
  if (EXISTS "${file}")
    get_filename_component(real "${file}" REALPATH)
    execute_process(COMMAND dpkg-query -S "${real}"
      OUTPUT_VARIABLE line ERROR_QUIET RESULT_VARIABLE rc OUTPUT_STRIP_TRAILING_WHITESPACE)
    if (rc EQUAL 0 AND line MATCHES "^([^:,]+)(:[a-z0-9]+)?: ")
      set(owner "${CMAKE_MATCH_1}")
    endif ()
  endif ()
  set("${out}" "${owner}" PARENT_SCOPE)
endfunction ()

set(amrsp_debian_depends "")
if (AMRSP_WITH_PARAVIEW)
  set(CPACK_PACKAGE_NAME "singlepassamr-paraview-plugin")
  set(amrsp_summary "AMR volume rendering for ParaView ${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR} (single-pass GPU kD-tree raycaster)")
  amrsp_debian_installed_version(paraview amrsp_paraview_version)
  if (amrsp_paraview_version)
    set(amrsp_debian_depends "paraview (= ${amrsp_paraview_version})")
  endif ()
  # the plugin, its module libraries and the .plugins file; not the client-server static libraries
  # (component development) nor the tool (the VTK package has it)
  set(CPACK_COMPONENTS_ALL Unspecified runtime paraview_autoload)
  # where the package puts it (SinglePassAMRDebianStaging.cmake moves the plugin folder there)
  set(amrsp_plugins_xml
    "/usr/lib/${CMAKE_LIBRARY_ARCHITECTURE}/paraview-${ParaView_VERSION_MAJOR}.${ParaView_VERSION_MINOR}/plugins/SinglePassAMR.plugins.xml")
  configure_file("${CMAKE_CURRENT_LIST_DIR}/singlepassamr-paraview.sh.in"
    "${CMAKE_CURRENT_BINARY_DIR}/singlepassamr-paraview.sh" @ONLY)
  # only in the package (cpack installs the component by name); `cmake --install` leaves /etc alone
  install(FILES "${CMAKE_CURRENT_BINARY_DIR}/singlepassamr-paraview.sh"
    DESTINATION /etc/profile.d COMPONENT paraview_autoload EXCLUDE_FROM_ALL)
  # dpkg keeps a file under /etc that the administrator changed (Debian policy: a conffile)
  file(WRITE "${CMAKE_CURRENT_BINARY_DIR}/debian-control/conffiles" "/etc/profile.d/singlepassamr-paraview.sh\n")
  set(CPACK_DEBIAN_PACKAGE_CONTROL_EXTRA "${CMAKE_CURRENT_BINARY_DIR}/debian-control/conffiles")
else ()
  set(CPACK_PACKAGE_NAME "singlepassamr-vtk")
  set(amrsp_summary "AMR volume mapper for VTK ${VTK_VERSION_MAJOR}.${VTK_VERSION_MINOR}, its Python package and the amrsp tool")
  if (AMRSP_DEBIAN_VTK_DEPENDS)
    set(amrsp_debian_depends "${AMRSP_DEBIAN_VTK_DEPENDS}")
  else ()
    get_target_property(amrsp_vtk_core VTK::CommonCore LOCATION)
    amrsp_debian_owner("${amrsp_vtk_core}" amrsp_vtk_package)
    if (amrsp_vtk_package)
      amrsp_debian_installed_version("${amrsp_vtk_package}" amrsp_vtk_version)
      set(amrsp_debian_depends "${amrsp_vtk_package} (= ${amrsp_vtk_version})")
      if (amrsp_python)
        string(APPEND amrsp_debian_depends ", python3-vtk9 (= ${amrsp_vtk_version})")
      endif ()
    endif ()
  endif ()
  set(CPACK_COMPONENTS_ALL Unspecified runtime development python tool)
endif ()
if (amrsp_debian_depends)
  message(STATUS "SinglePassAMR: the Debian package depends on ${amrsp_debian_depends}")
else ()
  message(STATUS "SinglePassAMR: dpkg does not know the ParaView/VTK built against: "
    "a Debian package of this build would have no version pin (scripts/package.sh refuses it)")
endif ()
set(AMRSP_DEBIAN_DEPENDS_RESOLVED "${amrsp_debian_depends}" CACHE INTERNAL "")

set(CPACK_GENERATOR DEB)
set(CPACK_PACKAGE_VERSION "${PROJECT_VERSION}")
set(CPACK_PACKAGE_VENDOR "SinglePassAMR")
set(CPACK_PACKAGE_CONTACT "SinglePassAMR developers <singlepassamr@localhost>")
set(CPACK_PACKAGE_DESCRIPTION_SUMMARY "${amrsp_summary}")
set(CPACK_PACKAGE_DESCRIPTION
  "Kaehler and Abel's single-pass GPU raycasting of structured adaptive-mesh-refinement data \
(vtkOverlappingAMR) at its native resolution.")
# Debian's prefix whatever the build's; the layout under it is the build's LIBDIR (lib), except the
# plugin folder (SinglePassAMRDebianStaging.cmake)
set(CPACK_PACKAGING_INSTALL_PREFIX "/usr")
set(CPACK_AMRSP_MULTIARCH "${CMAKE_LIBRARY_ARCHITECTURE}")
set(CPACK_DEB_COMPONENT_INSTALL ON)
set(CPACK_COMPONENTS_GROUPING ALL_COMPONENTS_IN_ONE)
set(CPACK_DEBIAN_FILE_NAME DEB-DEFAULT)
set(CPACK_DEBIAN_PACKAGE_SECTION science)
set(CPACK_DEBIAN_PACKAGE_DEPENDS "${amrsp_debian_depends}")
set(CPACK_DEBIAN_PACKAGE_HOMEPAGE "https://localhost/singlepassamr")
set(CPACK_DEBIAN_COMPRESSION_TYPE gzip)
# the staged tree: the plugin folder in ParaView's, run paths without the build machine's folders
set(CPACK_PRE_BUILD_SCRIPTS "${CMAKE_CURRENT_LIST_DIR}/SinglePassAMRDebianStaging.cmake")
include(CPack)
