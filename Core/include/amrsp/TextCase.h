// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// Case folding for the words the core and the tool parse (setting names, dataset parameters,
/// file extensions): ASCII only, the same whatever the process's C locale (VTK and ParaView may
/// set one); other bytes are left as they are.

#include <string>

namespace amrsp
{

/// `text` with A-Z turned into a-z.
inline std::string LowerAscii(std::string text)
{
  for (char& c : text)
  {
    if (c >= 'A' && c <= 'Z')
    {
      c = static_cast<char>(c - 'A' + 'a');
    }
  }
  return text;
}

} // namespace amrsp
