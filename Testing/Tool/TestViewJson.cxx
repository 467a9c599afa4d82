// SPDX-License-Identifier: BSD-3-Clause
// amrsp --view-json: a camera and transfer functions given explicitly (as the ParaView tests write
// them) must give exactly the settings, and the image, that the conventions give when the file
// holds the conventions' own camera and preset.
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspCommands.h"
#include "AmrspDataset.h"

#include "amrsp/Render.h"

#include <gtest/gtest.h>

#include <cstdio>
#include <fstream>
#include <string>

namespace
{
using amrsp::tool::Arguments;

amrsp::Hierarchy LoadPulse()
{
  amrsp::harness::DatasetRequest request;
  request.Spec = "synthetic:pulse";
  return amrsp::harness::LoadDataset(request).Data;
}

std::string WriteTemporary(const std::string& name, const std::string& text)
{
  const std::string path = testing::TempDir() + name;
  std::ofstream(path) << text;
  return path;
}

Arguments ViewArguments(const std::string& viewJson)
{
  Arguments a;
  a.Positional = { "reference", "synthetic:pulse" };
  a.Options["size"] = "48x40";
  a.Options["scale"] = "linear";
  if (!viewJson.empty())
  {
    a.Options["view-json"] = viewJson;
  }
  return a;
}

} // namespace

TEST(ViewJson, ConventionsWrittenOutGiveTheSameImage)
{
  amrsp::Hierarchy h = LoadPulse();
  const amrsp::RenderSettings conventions = amrsp::tool::MakeSettings(h, ViewArguments(""));

  nlohmann::json j;
  const amrsp::Camera& c = conventions.View;
  j["camera"] = { { "position", { c.Position.x, c.Position.y, c.Position.z } },
    { "focal_point", { c.FocalPoint.x, c.FocalPoint.y, c.FocalPoint.z } },
    { "view_up", { c.ViewUp.x, c.ViewUp.y, c.ViewUp.z } }, { "view_angle", c.ViewAngle } };
  nlohmann::json rgb = nlohmann::json::array(), opacity = nlohmann::json::array();
  // written in reverse order: the reader sorts the points
  for (auto it = conventions.Transfer.Color.rbegin(); it != conventions.Transfer.Color.rend(); ++it)
  {
    rgb.push_back({ it->X, it->Rgb.r, it->Rgb.g, it->Rgb.b });
  }
  for (const auto& p : conventions.Transfer.Opacity)
  {
    opacity.push_back({ p.X, p.Opacity });
  }
  j["transfer_function"] = { { "rgb_points", rgb }, { "opacity_points", opacity },
    { "unit_distance", conventions.Transfer.UnitDistance } };
  j["background"] = { 0.0, 0.0, 0.0 };
  const std::string path = WriteTemporary("amrsp-view.json", j.dump(17));

  amrsp::Hierarchy h2 = LoadPulse();
  const amrsp::RenderSettings fromFile = amrsp::tool::MakeSettings(h2, ViewArguments(path));
  EXPECT_EQ(fromFile.View.Position, conventions.View.Position);
  EXPECT_EQ(fromFile.View.FocalPoint, conventions.View.FocalPoint);
  EXPECT_EQ(fromFile.View.ViewUp, conventions.View.ViewUp);
  EXPECT_EQ(fromFile.View.ViewAngle, conventions.View.ViewAngle);
  ASSERT_EQ(fromFile.Transfer.Color.size(), conventions.Transfer.Color.size());
  for (std::size_t i = 0; i < fromFile.Transfer.Color.size(); ++i)
  {
    EXPECT_EQ(fromFile.Transfer.Color[i].X, conventions.Transfer.Color[i].X);
    EXPECT_EQ(fromFile.Transfer.Color[i].Rgb, conventions.Transfer.Color[i].Rgb);
  }
  EXPECT_EQ(fromFile.Transfer.UnitDistance, conventions.Transfer.UnitDistance);

  const amrsp::Image a = amrsp::RenderReference(h, conventions);
  const amrsp::Image b = amrsp::RenderReference(h2, fromFile);
  EXPECT_EQ(amrsp::Rmse(a, b), 0.0);
  std::remove(path.c_str());
}

TEST(ViewJson, ExplicitTransferFunctionMeansLinearScale)
{
  // positive data over more than three decades would be shown in log10 by --scale auto; a
  // transfer function from a file is in the data's own values, so the values stay linear
  amrsp::Hierarchy h = LoadPulse();
  Arguments a = ViewArguments(WriteTemporary("amrsp-tf.json",
    R"({"transfer_function": {"rgb_points": [[0, 0, 0, 0], [1, 1, 1, 1]],
        "opacity_points": [[0, 0], [1, 0.5]]}})"));
  a.Options.erase("scale");
  glm::dvec2 range;
  const amrsp::RenderSettings s = amrsp::tool::MakeSettings(h, a, &range);
  EXPECT_EQ(h.ArrayName.find("log10"), std::string::npos);
  EXPECT_EQ(s.Transfer.Opacity.back().Opacity, 0.5);
  EXPECT_GT(s.Transfer.UnitDistance, 0.0); // the usual default: diagonal / 100
}

TEST(ViewJson, Errors)
{
  amrsp::Hierarchy h = LoadPulse();
  const auto message = [&](const std::string& text, const char* extra = nullptr)
  {
    Arguments a = ViewArguments(WriteTemporary("amrsp-bad.json", text));
    if (extra)
    {
      a.Options[extra] = "10";
    }
    try
    {
      amrsp::tool::MakeSettings(h, a);
    }
    catch (const amrsp::tool::UsageError& e)
    {
      return e.Message;
    }
    return std::string("no error");
  };
  EXPECT_NE(message("{").find("not valid JSON"), std::string::npos);
  EXPECT_NE(message("[1, 2]").find("must hold a JSON object"), std::string::npos);
  EXPECT_NE(message(R"({"camera": {"position": [0, 0, 1], "focal_point": [0, 0]}})")
              .find("camera.focal_point"),
    std::string::npos);
  EXPECT_NE(message(R"({"camera": {"position": [0, 0, 1], "focal_point": [0, 0, 1],
                       "view_up": [0, 1, 0]}})")
              .find("degenerate"),
    std::string::npos);
  EXPECT_NE(
    message(R"({"transfer_function": {"rgb_points": [[0, 1]], "opacity_points": [[0, 1]]}})")
      .find("[x, r, g, b]"),
    std::string::npos);
  EXPECT_NE(message(R"({"camera": {"position": [0, 0, 1], "focal_point": [0, 0, 0],
                       "view_up": [0, 1, 0]}})",
              "azimuth")
              .find("cannot change a --view-json camera"),
    std::string::npos);
  Arguments missing = ViewArguments("/nonexistent/view.json");
  EXPECT_THROW(amrsp::tool::MakeSettings(h, missing), amrsp::tool::UsageError);
}
