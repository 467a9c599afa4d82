// SPDX-License-Identifier: BSD-3-Clause
// first: see AmrspJson.h
#include "AmrspJson.h"

#include "AmrspBenchPlot.h"

#include "vtkImageData.h"
#include "vtkNew.h"
#include "vtkPNGWriter.h"
#include "vtkPointData.h"
#include "vtkTextProperty.h"
#include "vtkTextRenderer.h"
#include "vtkUnsignedCharArray.h"

#include <algorithm>
#include <cmath>
#include <fstream>
#include <iomanip>
#include <sstream>
#include <stdexcept>

namespace amrsp
{
namespace tool
{

namespace
{

/// An RGB image with boxes and text; (0,0) is the lower left pixel, as in vtkImageData.
class Canvas
{
public:
  Canvas(int w, int h)
    : Width(w)
    , Height(h)
  {
    this->Data->SetDimensions(w, h, 1);
    this->Data->AllocateScalars(VTK_UNSIGNED_CHAR, 3);
    this->Box(0, 0, w, h, 255, 255, 255);
  }

  /// Fills [x0, x1) x [y0, y1), clipped to the canvas.
  void Box(int x0, int y0, int x1, int y1, int r, int g, int b)
  {
    unsigned char* p = static_cast<unsigned char*>(this->Data->GetScalarPointer());
    for (int y = std::max(y0, 0); y < std::min(y1, this->Height); ++y)
    {
      for (int x = std::max(x0, 0); x < std::min(x1, this->Width); ++x)
      {
        unsigned char* d = p + 3 * (static_cast<std::size_t>(y) * this->Width + x);
        d[0] = static_cast<unsigned char>(r);
        d[1] = static_cast<unsigned char>(g);
        d[2] = static_cast<unsigned char>(b);
      }
    }
  }

  /// Draws `text` with its lower left corner at (x, y) (right-aligned at x when `alignRight`,
  /// vertically centred on y when `centreY`). Returns the text's width in pixels.
  int Text(const std::string& text, int x, int y, int size, bool bold = false,
    bool alignRight = false, bool centreY = false, int grey = 0)
  {
    vtkTextRenderer* tr = vtkTextRenderer::GetInstance();
    if (!tr || text.empty())
    {
      return 0;
    }
    vtkNew<vtkTextProperty> tp;
    tp->SetFontFamilyToArial();
    tp->SetFontSize(size);
    tp->SetBold(bold ? 1 : 0);
    tp->SetColor(grey / 255.0, grey / 255.0, grey / 255.0);
    vtkNew<vtkImageData> glyphs;
    int dims[2] = { 0, 0 };
    if (!tr->RenderString(tp, text, glyphs, dims, 72))
    {
      throw std::runtime_error("cannot render the text '" + text + "' (FreeType)");
    }
    if (alignRight)
    {
      x -= dims[0];
    }
    if (centreY)
    {
      y -= dims[1] / 2;
    }
    int ext[6];
    glyphs->GetExtent(ext);
    unsigned char* dst = static_cast<unsigned char*>(this->Data->GetScalarPointer());
    for (int j = ext[2]; j <= ext[3]; ++j)
    {
      for (int i = ext[0]; i <= ext[1]; ++i)
      {
        const int px = x + i - ext[0], py = y + j - ext[2];
        if (px < 0 || py < 0 || px >= this->Width || py >= this->Height)
        {
          continue;
        }
        const unsigned char* src =
          static_cast<unsigned char*>(glyphs->GetScalarPointer(i, j, ext[4]));
        const double a = src[3] / 255.0;
        unsigned char* d = dst + 3 * (static_cast<std::size_t>(py) * this->Width + px);
        for (int c = 0; c < 3; ++c)
        {
          d[c] = static_cast<unsigned char>(std::lround((1.0 - a) * d[c] + a * src[c]));
        }
      }
    }
    return dims[0];
  }

  void Write(const std::string& path)
  {
    {
      std::ofstream probe(path, std::ios::binary);
      if (!probe)
      {
        throw std::runtime_error("cannot write the plot file '" + path + "'");
      }
    }
    vtkNew<vtkPNGWriter> writer;
    writer->SetFileName(path.c_str());
    writer->SetInputData(this->Data);
    writer->Write();
    if (writer->GetErrorCode() != 0)
    {
      throw std::runtime_error("writing the plot file '" + path + "' failed");
    }
  }

private:
  vtkNew<vtkImageData> Data;
  int Width, Height;
};

std::string Short(double v)
{
  std::ostringstream s;
  const double a = std::abs(v);
  s << std::setprecision(a >= 100 ? 0 : a >= 10 ? 1 : a >= 1 ? 2 : 3) << std::fixed << v;
  return s.str();
}

struct Panel
{
  std::string Title;
  std::string Key;  // JSON field of a method
  double Scale;     // multiplies the value
  std::string Unit; // appended to the value label
};

} // namespace

void WriteBenchPlot(const BenchJson& bench, const std::string& path, int width, int height)
{
  if (width < 300 || height < 200)
  {
    throw std::runtime_error("--plot-size must be at least 300x200");
  }
  Canvas c(width, height);
  const int titleSize = std::max(10, std::min(22, height / 30));
  std::ostringstream title;
  std::string name = bench["dataset"].get<std::string>();
  if (name.rfind("synthetic:", 0) != 0 && name.find('/') != std::string::npos)
  {
    name = name.substr(name.find_last_of('/') + 1); // the file, not its folders
  }
  title << "amrsp bench: " << name << ", " << bench["image"][0] << "x" << bench["image"][1] << ", "
        << bench["frames"] << " frames";
  c.Text(title.str(), 10, height - titleSize - 8, titleSize, true);

  const std::vector<Panel> panels = { { "frames per second (higher is better)", "fps", 1.0, "" },
    { "GPU memory, MB (lower is better)", "gpu_bytes", 1e-6, " MB" },
    { "RMSE of frame 0 vs CPU reference, 0-255 (lower is better)", "rmse", 1.0, "" } };
  const BenchJson& methods = bench["methods"];
  const int n = std::max<int>(1, static_cast<int>(methods.size()));
  const int top = height - titleSize - 16;
  const int panelHeight = top / static_cast<int>(panels.size());
  const int rowHeight = std::max(6, (panelHeight - 2 * titleSize - 6) / n);
  const int fontSize = std::max(8, std::min(16, rowHeight * 2 / 3));
  const int labelWidth = std::min(width / 3, 12 * fontSize);
  const int barLeft = labelWidth + 14, barRight = width - 8 * fontSize;
  const int colours[3][3] = { { 66, 114, 196 }, { 237, 125, 49 }, { 112, 173, 71 } };

  for (std::size_t p = 0; p < panels.size(); ++p)
  {
    const Panel& panel = panels[p];
    const int y1 = top - static_cast<int>(p) * panelHeight; // panel's upper edge
    c.Text(panel.Title, barLeft, y1 - titleSize - 4, titleSize - 2, true);
    double maxValue = 0.0;
    for (const auto& m : methods.items())
    {
      if (m.value().contains(panel.Key))
      {
        maxValue = std::max(maxValue, m.value()[panel.Key].get<double>() * panel.Scale);
      }
    }
    const int rowsTop = y1 - titleSize - 10;
    // the axis
    c.Box(barLeft - 1, rowsTop - n * rowHeight, barLeft, rowsTop, 0, 0, 0);
    int row = 0;
    for (const auto& m : methods.items())
    {
      const int y = rowsTop - (row + 1) * rowHeight;
      const int mid = y + rowHeight / 2;
      c.Text(m.key(), barLeft - 6, mid, fontSize, false, true, true);
      const BenchJson& r = m.value();
      if (!r.contains(panel.Key))
      {
        c.Text(r.contains("error") ? "cannot run" : "n/a", barLeft + 6, mid, fontSize, false, false,
          true, 128);
      }
      else
      {
        const double v = r[panel.Key].get<double>() * panel.Scale;
        const int length =
          maxValue > 0.0 ? static_cast<int>(std::lround((barRight - barLeft) * v / maxValue)) : 0;
        const int* col = colours[p];
        c.Box(barLeft, y + rowHeight / 6, barLeft + std::max(length, 1),
          y + rowHeight - rowHeight / 6, col[0], col[1], col[2]);
        c.Text(Short(v) + panel.Unit, barLeft + std::max(length, 1) + 4, mid, fontSize, false,
          false, true);
      }
      ++row;
    }
  }
  c.Write(path);
}

} // namespace tool
} // namespace amrsp
