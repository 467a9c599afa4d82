# A test whose program or data is missing on this machine: `cmake -DWHAT=... -P` this file.
# It reports SKIPPED (CTest's SKIP_REGULAR_EXPRESSION) for people running ctest by hand, and FAILS
# naming what is missing with AMRSP_REQUIRE_GPU=1 (CI, where everything is installed).
if ("$ENV{AMRSP_REQUIRE_GPU}" STREQUAL "1")
  message(FATAL_ERROR "FAIL: required here (AMRSP_REQUIRE_GPU=1) but missing: ${WHAT}")
endif ()
message("SKIPPED: ${WHAT}")
