// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The small readers the file checks of every format share (AmrspFileChecks.cxx): not a public
/// interface of the harness.

#include <filesystem>
#include <string>

namespace amrsp
{
namespace harness
{
namespace filechecks
{

/// The whole file as bytes ("" when it cannot be read).
std::string ReadWhole(const std::filesystem::path& path);

/// "1,408,396 bytes".
std::string Bytes(unsigned long long n);

/// The file's size in bytes, 0 when it cannot be had.
unsigned long long FileSize(const std::filesystem::path& path);

/// Little-endian unsigned integer of `n` bytes at `p`.
unsigned long long LittleEndian(const unsigned char* p, int n);

/// `s` without leading and trailing blanks.
std::string Trim(const std::string& s);

} // namespace filechecks
} // namespace harness
} // namespace amrsp
