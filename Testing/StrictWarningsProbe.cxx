// Built only by the test Testing.StrictWarnings: an unused parameter is a warning under -Wextra;
// with AMRSP_STRICT_WARNINGS every warning is an error and the build must fail, without it the
// build must pass and show the warning.
int AmrspStrictWarningsProbe(int unused)
{
  return 0;
}
