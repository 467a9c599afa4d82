// SPDX-License-Identifier: BSD-3-Clause
/**
 * @class   vtkSinglePassAMRComputeProgram
 * @brief   a compute-shader program with vtkShaderProgram's uniform setters (private)
 *
 * VTK's shader cache compiles vertex, fragment and geometry stages; VTK before 9.4 has no compute
 * stage at all. This program compiles one compute shader itself and is otherwise a
 * vtkShaderProgram: its handle, link state and uniform lookups are the base class's, so the code
 * that sets the single-pass shader's uniforms (SetUniformi, IsUniformUsed, ...) serves both
 * casters unchanged. Free deletes the program.
 */
#ifndef vtkSinglePassAMRComputeProgram_h
#define vtkSinglePassAMRComputeProgram_h

#include "vtkShaderProgram.h"

#include <string>

class vtkOpenGLRenderWindow;
class vtkWindow;

/// The compute caster's work groups: Width x Height pixels each (one SIMT group of 32 on NVIDIA
/// GPUs, the 8 x 4 tile the work counters model; amrsp/WorkCounters.h).
namespace vtkSinglePassAMRComputeGroup
{
constexpr int Width = 8;
constexpr int Height = 4;
/// Groups of `size` pixels that cover `pixels` (> 0).
inline unsigned int Count(int pixels, int size)
{
  return static_cast<unsigned int>((pixels + size - 1) / size);
}
} // namespace vtkSinglePassAMRComputeGroup

class vtkSinglePassAMRComputeProgram : public vtkShaderProgram
{
public:
  static vtkSinglePassAMRComputeProgram* New();
  vtkTypeMacro(vtkSinglePassAMRComputeProgram, vtkShaderProgram);

  /// Compiles and links `source` as the compute shader of a new program in the current context
  /// (the previous program of this object, if any, is deleted). False with the compiler's or
  /// linker's log in `error`.
  bool Build(vtkOpenGLRenderWindow* renWin, const std::string& source, std::string& error);
  /// The source of the last successful Build (empty before).
  const std::string& GetComputeSource() const { return this->ComputeSource; }

  /// Makes the program current. The shader cache forgets the program it had bound, so that VTK
  /// binds its own again at its next draw.
  void Use(vtkOpenGLRenderWindow* renWin);
  /// Runs groupsX x groupsY work groups, then makes image writes visible to texture fetches
  /// (the composite reads the image next).
  void Dispatch(unsigned int groupsX, unsigned int groupsY);
  /// Unbinds the program.
  void Unuse();

  /// Deletes the program of `window`'s context (the shader cache forgets its bound program
  /// first, as the deletion unbinds whatever is bound).
  void Free(vtkWindow* window);

protected:
  vtkSinglePassAMRComputeProgram() = default;
  ~vtkSinglePassAMRComputeProgram() override = default;

private:
  vtkSinglePassAMRComputeProgram(const vtkSinglePassAMRComputeProgram&) = delete;
  void operator=(const vtkSinglePassAMRComputeProgram&) = delete;

  std::string ComputeSource;
};

#endif
