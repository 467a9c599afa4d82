// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The name table of a setting: each enumerator with the one word that the amrsp tool, its bench
/// JSON, the ParaView plugin and the docs use for it. Every setting's header (amrsp/DataStorage.h,
/// RayLoop.h, RayCaster.h, BlendMode.h) holds its enumeration and its table; these functions read
/// any table, so a word is written once and parsed back by the same table.

#include <cstddef>
#include <cstring>
#include <string>

namespace amrsp
{

/// One row of a name table.
template <typename Enum>
struct SettingName
{
  Enum Value;
  const char* Word;
};

/// `value`'s word in `table`, or `otherwise` when the table has no row for it.
template <typename Enum, std::size_t N>
const char* NameIn(const SettingName<Enum> (&table)[N], Enum value, const char* otherwise = "none")
{
  for (const SettingName<Enum>& row : table)
  {
    if (row.Value == value)
    {
      return row.Word;
    }
  }
  return otherwise;
}

/// The value whose word is `word` (exact, case-sensitive); false, `value` unchanged, for any
/// other word or null.
template <typename Enum, std::size_t N>
bool ParseIn(const SettingName<Enum> (&table)[N], const char* word, Enum& value)
{
  for (const SettingName<Enum>& row : table)
  {
    if (word && std::strcmp(word, row.Word) == 0)
    {
      value = row.Value;
      return true;
    }
  }
  return false;
}

/// The table's words as a usage message lists them: "a, b or c".
template <typename Enum, std::size_t N>
std::string WordsOf(const SettingName<Enum> (&table)[N])
{
  std::string words;
  for (std::size_t i = 0; i < N; ++i)
  {
    words += (i == 0 ? "" : i + 1 == N ? " or " : ", ") + std::string(table[i].Word);
  }
  return words;
}

} // namespace amrsp
