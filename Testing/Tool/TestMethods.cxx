// SPDX-License-Identifier: BSD-3-Clause
// The tool's method registry (AmrspMethods.h): the names each command accepts, the lists its
// messages and help show (a contract of the command line), and the GPU flag. No OpenGL.
#include "AmrspMethods.h"

#include <gtest/gtest.h>

#include <sstream>
#include <string>

using namespace amrsp::tool;

TEST(Methods, ListsAsTheCommandsPrintThem)
{
  EXPECT_EQ(MethodList(RenderCommand),
    "cpu-kdtree, cpu-packing, packing[:CASTER[-LOOP]], bindless[:CASTER[-LOOP]], "
    "linear[:CASTER[-LOOP]], auto-storage[:CASTER[-LOOP]], multipass");
  EXPECT_EQ(MethodList(BenchCommand),
    "cpu-kdtree, packing[:CASTER[-LOOP]], bindless[:CASTER[-LOOP]], linear[:CASTER[-LOOP]], "
    "auto-storage[:CASTER[-LOOP]], multipass, uniform-gpu[:LEVEL], vtk-amr-resample[:N|:finest]");
  EXPECT_EQ(DefaultBenchMethods(),
    "cpu-kdtree,packing,bindless,linear,multipass,uniform-gpu,vtk-amr-resample,"
    "vtk-amr-resample:finest");
}

TEST(Methods, FindsNamesAndParameters)
{
  ASSERT_NE(FindMethod("packing", RenderCommand), nullptr);
  EXPECT_EQ(FindMethod("packing", RenderCommand)->Kind, MethodKind::Packing);
  EXPECT_EQ(FindMethod("cpu-packing", BenchCommand), nullptr);
  EXPECT_EQ(FindMethod("uniform-gpu", RenderCommand), nullptr);
  ASSERT_NE(FindMethod("uniform-gpu:2", BenchCommand), nullptr);
  EXPECT_EQ(FindMethod("uniform-gpu:2", BenchCommand)->Kind, MethodKind::UniformGpu);
  EXPECT_EQ(FindMethod("vtk-amr-resample:finest", BenchCommand)->Kind, MethodKind::AmrResample);
  EXPECT_EQ(FindMethod("cpu-kdtree:2", RenderCommand), nullptr); // takes no parameter
  EXPECT_EQ(FindMethod("uniform-gpux", BenchCommand), nullptr);
  EXPECT_EQ(FindMethod("raytrace", RenderCommand | BenchCommand), nullptr);
}

TEST(Methods, GpuMethodsHaveARenderer)
{
  for (const Method& m : Methods())
  {
    EXPECT_EQ(m.NeedsGpu, m.Make != nullptr) << m.Name;
    EXPECT_FALSE(m.Forms.empty()) << m.Name;
  }
  EXPECT_THROW(MakeGpuRenderer("cpu-kdtree", RenderCommand,
                 MethodRequest{ amrsp::Hierarchy(), amrsp::RenderSettings(), ViewAngles() }),
    GpuError);
}

TEST(Methods, HelpHasEveryFormOnce)
{
  std::ostringstream help;
  PrintMethodHelp(help, BenchCommand);
  const std::string text = help.str();
  for (const char* form : { "  cpu-kdtree ", "  uniform-gpu[:LEVEL] ", "  vtk-amr-resample[:N] ",
         "  vtk-amr-resample:finest " })
  {
    EXPECT_NE(text.find(form), std::string::npos) << form;
  }
  EXPECT_EQ(text.find("cpu-packing"), std::string::npos);
  std::istringstream lines(text);
  for (std::string line; std::getline(lines, line);)
  {
    EXPECT_LE(line.size(), 101u) << line; // 100 columns (a UTF-8 '§' takes two bytes)
  }
}
