// Built only by the test Testing.StrictWarnings, which expects this build to fail: an unused
// parameter is a warning under -Wextra, and AMRSP_STRICT_WARNINGS makes every warning an error.
int AmrspStrictWarningsProbe(int unused)
{
  return 0;
}
