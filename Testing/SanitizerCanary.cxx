// SPDX-License-Identifier: BSD-3-Clause
// A program with the faults the sanitizer build must report: `heap-overflow` reads one element
// past a heap array (AddressSanitizer), `signed-overflow` adds 1 to INT_MAX (UndefinedBehavior-
// Sanitizer); `clean` does neither. Without a report it says so and exits 0.
#include <climits>
#include <cstdio>
#include <cstring>

int main(int argc, char** argv)
{
  const char* what = argc > 1 ? argv[1] : "clean";
  volatile int sink = 0;
  if (std::strcmp(what, "heap-overflow") == 0)
  {
    int* values = new int[4]{ 1, 2, 3, 4 };
    volatile int past = 4 + (argc > 5); // not known to the compiler
    sink = values[past];
    delete[] values;
  }
  else if (std::strcmp(what, "signed-overflow") == 0)
  {
    volatile int big = INT_MAX;
    sink = big + 1;
  }
  std::printf("%s: this canary ran without a report (%d)\n", what, static_cast<int>(sink));
  return 0;
}
