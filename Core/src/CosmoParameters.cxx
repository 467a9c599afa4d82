// SPDX-License-Identifier: BSD-3-Clause
// The synthetic cosmology's parameters: synthetic:cosmo:grids=N,levels=L,cells=C,... parsing.
#include "amrsp/SyntheticCosmo.h"
#include "amrsp/TextCase.h"

#include <algorithm>
#include <cstddef>
#include <limits>
#include <sstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace amrsp
{

// ------------------------------------------------------------------------------------------------
// Parameters.

namespace
{

std::string Trim(const std::string& s)
{
  const char* ws = " \t\r\n";
  const std::size_t b = s.find_first_not_of(ws);
  if (b == std::string::npos)
  {
    return std::string();
  }
  const std::size_t e = s.find_last_not_of(ws);
  return s.substr(b, e - b + 1);
}

[[noreturn]] void BadValue(const std::string& key, const std::string& value, const std::string& why)
{
  throw std::invalid_argument(
    "cosmo parameters: bad value '" + value + "' for key '" + key + "': " + why);
}

/// Parses an unsigned integer; with `suffixes`, also "<digits>[.<digits>](k|K|M)" whose value
/// must be an integer. Overflow-checked.
uint64_t ParseUnsigned(const std::string& key, const std::string& value, bool suffixes)
{
  const uint64_t maxValue = std::numeric_limits<uint64_t>::max();
  std::size_t i = 0;
  uint64_t intPart = 0;
  std::size_t digits = 0;
  for (; i < value.size() && value[i] >= '0' && value[i] <= '9'; ++i, ++digits)
  {
    const uint64_t d = static_cast<uint64_t>(value[i] - '0');
    if (intPart > (maxValue - d) / 10)
    {
      BadValue(key, value, "number too large");
    }
    intPart = intPart * 10 + d;
  }
  if (digits == 0)
  {
    BadValue(key, value,
      suffixes ? "expected a non-negative integer, optionally with a k, M or G suffix"
               : "expected a non-negative integer");
  }
  uint64_t fracPart = 0;
  uint64_t fracScale = 1;
  bool hasFraction = false;
  if (suffixes && i < value.size() && value[i] == '.')
  {
    hasFraction = true;
    ++i;
    std::size_t fracDigits = 0;
    for (; i < value.size() && value[i] >= '0' && value[i] <= '9'; ++i, ++fracDigits)
    {
      if (fracDigits >= 6)
      {
        BadValue(key, value, "too many decimals");
      }
      fracPart = fracPart * 10 + static_cast<uint64_t>(value[i] - '0');
      fracScale *= 10;
    }
    if (fracDigits == 0)
    {
      BadValue(key, value, "expected digits after the decimal point");
    }
  }
  uint64_t multiplier = 1;
  if (suffixes && i < value.size())
  {
    if (value[i] == 'k' || value[i] == 'K')
    {
      multiplier = 1000;
      ++i;
    }
    else if (value[i] == 'M')
    {
      multiplier = 1000000;
      ++i;
    }
    else if (value[i] == 'G')
    {
      multiplier = 1000000000;
      ++i;
    }
  }
  if (i != value.size())
  {
    BadValue(key, value,
      suffixes ? "expected a non-negative integer, optionally with a k, M or G suffix (e.g. 19M)"
               : "expected a non-negative integer");
  }
  if (hasFraction && multiplier == 1)
  {
    BadValue(key, value, "a decimal number needs a k, M or G suffix");
  }
  if (intPart > maxValue / multiplier)
  {
    BadValue(key, value, "number too large");
  }
  const uint64_t whole = intPart * multiplier;
  // fracPart < fracScale <= 10^6, multiplier <= 10^9: no overflow.
  const uint64_t fracScaled = fracPart * multiplier;
  if (fracScaled % fracScale != 0)
  {
    BadValue(key, value, "not an integer");
  }
  if (whole > maxValue - fracScaled / fracScale)
  {
    BadValue(key, value, "number too large");
  }
  return whole + fracScaled / fracScale;
}

int64_t ParseSigned(const std::string& key, const std::string& value, bool suffixes,
  int64_t minValue, int64_t maxValue)
{
  const uint64_t v = ParseUnsigned(key, value, suffixes);
  if (v > static_cast<uint64_t>(maxValue) || static_cast<int64_t>(v) < minValue)
  {
    BadValue(key, value,
      "must be between " + std::to_string(minValue) + " and " + std::to_string(maxValue));
  }
  return static_cast<int64_t>(v);
}

} // namespace

CosmoParameters ParseCosmoParameters(const std::string& spec)
{
  CosmoParameters p;
  const std::string all = Trim(spec);
  if (all.empty())
  {
    return p;
  }
  std::vector<std::string> seen;
  std::size_t start = 0;
  for (;;)
  {
    const std::size_t comma = all.find(',', start);
    const std::string item =
      Trim(all.substr(start, comma == std::string::npos ? std::string::npos : comma - start));
    if (item.empty())
    {
      throw std::invalid_argument("cosmo parameters: empty item in '" + spec + "'");
    }
    const std::size_t eq = item.find('=');
    if (eq == std::string::npos)
    {
      throw std::invalid_argument("cosmo parameters: item '" + item +
        "' is not key=value (keys: grids, levels, cells, seed, roots, values, steps, regrid, "
        "step)");
    }
    const std::string key = LowerAscii(Trim(item.substr(0, eq)));
    const std::string value = Trim(item.substr(eq + 1));
    if (std::find(seen.begin(), seen.end(), key) != seen.end())
    {
      throw std::invalid_argument("cosmo parameters: key '" + key + "' given twice");
    }
    seen.push_back(key);
    const int64_t maxCount = int64_t(1) << 50;
    if (key == "grids")
    {
      p.Grids = ParseSigned(key, value, true, 1, maxCount);
    }
    else if (key == "levels")
    {
      p.Levels = static_cast<int>(ParseSigned(key, value, false, 1, 30));
    }
    else if (key == "cells")
    {
      p.Cells = ParseSigned(key, value, true, 1, maxCount);
    }
    else if (key == "seed")
    {
      p.Seed = ParseUnsigned(key, value, false);
    }
    else if (key == "roots")
    {
      p.RootGrids = ParseSigned(key, value, true, 0, maxCount);
    }
    else if (key == "steps")
    {
      p.Steps = static_cast<int>(ParseSigned(key, value, false, 1, 1000000));
    }
    else if (key == "step")
    {
      p.Step = static_cast<int>(ParseSigned(key, value, false, 0, 1000000));
    }
    else if (key == "regrid")
    {
      p.RegridEvery = static_cast<int>(ParseSigned(key, value, false, 0, 1000000));
    }
    else if (key == "values")
    {
      const std::string v = LowerAscii(value);
      if (v == "1" || v == "true" || v == "on" || v == "yes")
      {
        p.GenerateValues = true;
      }
      else if (v == "0" || v == "false" || v == "off" || v == "no")
      {
        p.GenerateValues = false;
      }
      else
      {
        BadValue(key, value, "expected 0 or 1");
      }
    }
    else
    {
      throw std::invalid_argument("cosmo parameters: unknown key '" + key +
        "' (keys: grids, levels, cells, seed, roots, values, steps, regrid, step)");
    }
    if (comma == std::string::npos)
    {
      break;
    }
    start = comma + 1;
  }
  return p;
}

std::string FormatCosmoParameters(const CosmoParameters& p)
{
  std::ostringstream s;
  s << "grids=" << p.Grids << ",levels=" << p.Levels << ",cells=" << p.Cells << ",seed=" << p.Seed
    << ",roots=" << p.RootGrids << ",values=" << (p.GenerateValues ? 1 : 0);
  if (p.Steps != 1 || p.RegridEvery != 0 || p.Step != 0)
  {
    s << ",steps=" << p.Steps << ",regrid=" << p.RegridEvery << ",step=" << p.Step;
  }
  return s.str();
}

} // namespace amrsp
