# The labels that say which configurations run a test (scripts/configs.sh selects each
# configuration's tests by label; docs/testing.md, "Coverage matrix", says why). Besides the suite
# labels (core, tool, mapper, plugin, mpi, insitu, python, consumer), a test that meets something
# that differs between configurations carries one of these, and runs wherever that thing differs:
#   readers     VTK's AMR readers (each VTK version has its own) on real and damaged files
#   data-model  VTK's AMR data model as the mapper and the conversion read it (VTK 9.6 changed it)
#   context     the window system, the OpenGL context and what it offers (the backend, compute
#               shaders, bindless textures)
#   rendering   the mapper's draws through this VTK's OpenGL classes, against the CPU reference
#   vtk-amr     VTK's own vtkAMRVolumeMapper method, where the VTK has it
#   everywhere  the checks of the build and of the test selection themselves
# and one label that narrows instead:
#   plugin-datasets  a plugin test's run of another dataset in a mode whose Enzo run carries
#               `plugin`: the oldest ParaView's configuration runs them (the same plugin code,
#               another of VTK's readers, which the readers tests check in each VTK)

# amrsp_label_tests(LABEL TEST...): adds LABEL to each TEST, which this folder must have registered.
function (amrsp_label_tests label)
  foreach (test IN LISTS ARGN)
    if (NOT TEST "${test}")
      message(FATAL_ERROR "amrsp_label_tests(${label}): no test named '${test}' in this folder")
    endif ()
    set_property(TEST "${test}" APPEND PROPERTY LABELS "${label}")
  endforeach ()
endfunction ()

# The longest tests, with their seconds on the 2-core development machine (llvmpipe; the
# sanitizers build's where it runs them, 2-3x longer). CTest starts the costliest tests first;
# without these, a fresh build folder (no Testing/Temporary/CTestCostData.txt yet, as in CI) starts
# them in the order they were added, and the last long ones leave a core idle at the end.
set(amrsp_test_costs
  Mapper.ShaderVariants=15 Tool.CLI.Series=70 Tool.Fuzz=60 Tool.DamagedData=30
  Plugin.CheckedReader=26 Tool.GpuProfile=45 Plugin.Storage=19 Plugin.Defaults.ClientServer=17
  Mapper.PackingImage=16 Plugin.ClientServer.local.enzo=16 Plugin.Installed=15
  Plugin.Representation.enzo=15 Plugin.Representation.enzo-log=15 Plugin.Representation.amrex=14
  AMRSP::SinglePassAMRCxx-TestSinglePassAMRLevelSeams=15 Mapper.LinearImage=14
  Plugin.ClientServer.remote.amrex=14 Plugin.ClientServer.remote.enzo=14 Mapper.BindlessImage=12
  Plugin.DocumentedPvpython=12 Plugin.Defaults=11 Plugin.GuiSmoke=11 Tool.ProgressBar=9
  Mapper.MultiPassImage=9 Plugin.TimeSeries=10 Plugin.ClientServer.local.enzo-checked=9
  Plugin.ClientServer.local.amrex=9 Plugin.DataChange=9 Tool.CLI.Bench.counters=8)

# amrsp_apply_test_costs(): the COST of each test of this folder that the table above names.
function (amrsp_apply_test_costs)
  get_property(tests DIRECTORY PROPERTY TESTS)
  foreach (entry IN LISTS amrsp_test_costs)
    string(REPLACE "=" ";" pair "${entry}")
    list(GET pair 0 test)
    list(GET pair 1 seconds)
    if (test IN_LIST tests)
      set_property(TEST "${test}" PROPERTY COST "${seconds}")
    endif ()
  endforeach ()
endfunction ()

# amrsp_label_discovered_tests(TARGET [MATCHING REGEX] LABEL...): the labels of every test
# gtest_discover_tests found in TARGET whose name matches REGEX (every test without MATCHING; call
# it after gtest_discover_tests). Its PROPERTIES cannot carry a list: the discovery splits
# "tool;readers" into two words. The tests exist only when ctest reads the discovery's file, so a
# file ctest includes after it sets them.
function (amrsp_label_discovered_tests target)
  set(labels ${ARGN})
  set(regex ".")
  if (ARGV1 STREQUAL "MATCHING")
    list(GET labels 1 regex)
    list(REMOVE_AT labels 0 1)
  endif ()
  string(MD5 key "${regex} ${labels}")
  set(file "${CMAKE_CURRENT_BINARY_DIR}/${target}_labels_${key}.cmake")
  file(WRITE "${file}" "foreach (amrsp_test IN LISTS ${target}_TESTS)\n"
    "  if (amrsp_test MATCHES [=[${regex}]=])\n"
    "    set_tests_properties(\"\${amrsp_test}\" PROPERTIES LABELS \"${labels}\")\n"
    "  endif ()\n"
    "endforeach ()\n")
  set_property(DIRECTORY APPEND PROPERTY TEST_INCLUDE_FILES "${file}")
endfunction ()
