// SPDX-License-Identifier: BSD-3-Clause
#pragma once
/// @file
/// `--driver`: which Mesa driver the tool's OpenGL contexts use. Must be applied before the first
/// context is created (Mesa reads its environment when it loads the driver).

#include <string>

namespace amrsp
{
namespace tool
{

/// "default" leaves the environment as it is (the system's driver: llvmpipe under Xvfb here, the
/// GPU's driver on a GPU machine). "zink" selects Mesa's zink on the Vulkan device (lavapipe on a
/// CPU-only machine), which offers GL_ARB_bindless_texture and GL_ARB_shader_ballot with Mesa 25:
/// it sets MESA_LOADER_DRIVER_OVERRIDE=zink and LIBGL_ALWAYS_SOFTWARE=1 (zink refuses a CPU
/// Vulkan device without it), and XDG_RUNTIME_DIR to a private folder when none exists.
/// @throws std::invalid_argument for another name or when the runtime folder cannot be made.
void SelectDriver(const std::string& name);

/// The option's help line.
extern const char* const DriverHelp;

} // namespace tool
} // namespace amrsp
