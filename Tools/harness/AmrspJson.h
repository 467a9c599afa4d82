// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// The tool's JSON library: the system's nlohmann/json. Include this header FIRST in a translation
/// unit that uses JSON, before any VTK header.
///
/// VTK 9.3 (ParaView 5.13) vendors its own copy: its vtk_nlohmannjson.h does
/// `#define nlohmann vtknlohmann`, and vtkAbstractArray.h then includes the vendored json_fwd.hpp,
/// whose include guard is the system copy's. With the system json read first the vendored one is
/// skipped, and the macro would turn every later `nlohmann::` into an undeclared `vtknlohmann::`.
/// So the VTK header is read here, once (it has an include guard), and its macro removed: all
/// `nlohmann::` names are the system library's. VTK's JSON-returning members are only declared in
/// the headers the tool includes; the tool never calls them.

#include <nlohmann/json.hpp>

#if defined(__has_include)
#if __has_include("vtk_nlohmannjson.h")
#include "vtk_nlohmannjson.h"
#ifdef nlohmann
#undef nlohmann
#endif
#endif
#endif
