// SPDX-License-Identifier: BSD-3-Clause
#include "vtkAMRMapperTransferFunctionTable.h"

#include "vtkColorTransferFunction.h"
#include "vtkOpenGLRenderWindow.h"
#include "vtkPiecewiseFunction.h"
#include "vtkVolumeProperty.h"
#include "vtkAMRMapperOpenGL.h"

#include <algorithm>
#include <cfloat>
#include <cmath>

namespace
{
/// `rgb` (3 per entry) and `alpha` (1 per entry), vtkAMRMapperTransferFunctionTable::Size
/// entries over [range[0], range[1]]: evenly spaced scalars, or log-spaced ones when `logarithmic`.
/// Without `colour` the grey function gives all three channels.
void Tabulate(vtkColorTransferFunction* colour, vtkPiecewiseFunction* greyFunction,
  vtkPiecewiseFunction* opacity, const double range[2], bool logarithmic, std::vector<float>& rgb,
  std::vector<float>& alpha)
{
  const int n = vtkAMRMapperTransferFunctionTable::Size;
  if (logarithmic)
  {
    // entry i at 10^(log a + i (log b - log a) / (n - 1)), as vtkColorTransferFunction::GetTable
    // samples a log-scaled function; each function evaluated with its own interpolation
    const double l0 = std::log10(range[0]), l1 = std::log10(range[1]);
    for (int i = 0; i < n; ++i)
    {
      const double x = i == 0 ? range[0]
        : i == n - 1          ? range[1]
                              : std::pow(10.0, l0 + i * (l1 - l0) / (n - 1));
      double c[3];
      if (colour)
      {
        colour->vtkColorTransferFunction::GetTable(x, x, 1, c);
      }
      else
      {
        c[0] = c[1] = c[2] = greyFunction->GetValue(x);
      }
      for (int k = 0; k < 3; ++k)
      {
        rgb[static_cast<std::size_t>(3 * i + k)] = static_cast<float>(c[k]);
      }
      alpha[static_cast<std::size_t>(i)] = static_cast<float>(opacity->GetValue(x));
    }
  }
  else
  {
    if (colour)
    {
      colour->GetTable(range[0], range[1], n, rgb.data());
    }
    else
    {
      greyFunction->GetTable(range[0], range[1], n, rgb.data(), 3);
      for (int i = 0; i < n; ++i)
      {
        rgb[3 * i + 1] = rgb[3 * i + 2] = rgb[3 * i];
      }
    }
    opacity->GetTable(range[0], range[1], n, alpha.data());
  }
}
} // namespace

//------------------------------------------------------------------------------
bool vtkAMRMapperTransferFunctionTable::Update(vtkOpenGLRenderWindow* renWin,
  vtkVolumeProperty* property, const double scalarRange[2], const vtkTimeStamp& dataTime)
{
  if (this->Texture && this->Texture->GetContext() == renWin && this->Property == property &&
    this->PropertyMTime == property->GetMTime() && this->Time > dataTime)
  {
    return true;
  }
  const bool grey = property->GetColorChannels(0) == 1;
  vtkColorTransferFunction* colour = grey ? nullptr : property->GetRGBTransferFunction(0);
  vtkPiecewiseFunction* greyFunction = grey ? property->GetGrayTransferFunction(0) : nullptr;
  vtkPiecewiseFunction* opacity = property->GetScalarOpacity(0);

  // tabulate over the union of the functions' ranges; beyond it both clamp to their end points
  double range[2] = { std::numeric_limits<double>::max(), -std::numeric_limits<double>::max() };
  auto extend = [&range](const double* r, int points)
  {
    if (points > 0)
    {
      range[0] = std::min(range[0], r[0]);
      range[1] = std::max(range[1], r[1]);
    }
  };
  if (colour)
  {
    extend(colour->GetRange(), colour->GetSize());
  }
  if (greyFunction)
  {
    extend(greyFunction->GetRange(), greyFunction->GetSize());
  }
  extend(opacity->GetRange(), opacity->GetSize());
  if (!(range[1] > range[0]))
  {
    range[0] = std::min(range[0], scalarRange[0]);
    range[1] = std::max(range[1], scalarRange[1]);
    if (!(range[1] > range[0]))
    {
      range[1] = range[0] + 1.0;
    }
  }

  // log-scaled colours or opacities (docs/paraview.md): the table is indexed by log10 of the
  // scalar, its entries at log-spaced scalars; that needs a positive range
  const bool logRequested = (colour && colour->GetScale() == VTK_CTF_LOG10) ||
    (greyFunction && greyFunction->GetUseLogScale()) || opacity->GetUseLogScale();
  this->Logarithmic = logRequested && range[0] > 0.0;
  this->Warning.clear();
  // a log scale over a range that is not positive: copies of the functions on a linear scale
  // (VTK 9.3 and later tabulate a log-scaled map over such a range as NaN)
  vtkNew<vtkColorTransferFunction> linearColour;
  vtkNew<vtkPiecewiseFunction> linearGrey, linearOpacity;
  if (logRequested && !this->Logarithmic)
  {
    std::ostringstream msg;
    msg << "the log-scaled transfer function spans [" << range[0] << ", " << range[1]
        << "], which is not positive: it is drawn on a linear scale";
    this->Warning = msg.str();
    if (colour)
    {
      linearColour->DeepCopy(colour);
      linearColour->SetScaleToLinear();
      colour = linearColour;
    }
    if (greyFunction)
    {
      linearGrey->DeepCopy(greyFunction);
      linearGrey->SetUseLogScale(false);
      greyFunction = linearGrey;
    }
    linearOpacity->DeepCopy(opacity);
    linearOpacity->SetUseLogScale(false);
    opacity = linearOpacity;
  }

  const int n = vtkAMRMapperTransferFunctionTable::Size;
  std::vector<float> rgb(static_cast<std::size_t>(3 * n)), alpha(static_cast<std::size_t>(n));
  std::vector<float> rgba(static_cast<std::size_t>(4 * n));
  Tabulate(colour, greyFunction, opacity, range, this->Logarithmic, rgb, alpha);
  for (int i = 0; i < n; ++i)
  {
    rgba[4 * i + 0] = rgb[3 * i + 0];
    rgba[4 * i + 1] = rgb[3 * i + 1];
    rgba[4 * i + 2] = rgb[3 * i + 2];
    rgba[4 * i + 3] = alpha[i];
  }
  if (!this->Texture || this->Texture->GetContext() != renWin)
  {
    this->Texture = vtkSmartPointer<vtkTextureObject>::New();
    this->Texture->SetContext(renWin);
    this->Texture->SetInternalFormat(GL_RGBA32F);
    this->Texture->SetFormat(GL_RGBA);
    this->Texture->SetDataType(GL_FLOAT);
    this->Texture->SetMinificationFilter(vtkTextureObject::Linear);
    this->Texture->SetMagnificationFilter(vtkTextureObject::Linear);
    this->Texture->SetWrapS(vtkTextureObject::ClampToEdge);
    this->Texture->SetWrapT(vtkTextureObject::ClampToEdge);
  }
  if (!this->Texture->Create2DFromRaw(static_cast<unsigned int>(n), 1, 4, VTK_FLOAT, rgba.data()))
  {
    return false;
  }
  this->Range[0] = range[0];
  this->Range[1] = range[1];
  this->Opacity = std::move(alpha);
  this->Property = property;
  this->PropertyMTime = property->GetMTime();
  this->Time.Modified();
  return true;
}

void vtkAMRMapperTransferFunctionTable::GetShaderRange(float range[2]) const
{
  const double lo = this->Logarithmic ? std::log10(this->Range[0]) : this->Range[0];
  const double hi = this->Logarithmic ? std::log10(this->Range[1]) : this->Range[1];
  range[0] = static_cast<float>(lo);
  range[1] = static_cast<float>(1.0 / (hi - lo));
}

float vtkAMRMapperTransferFunctionTable::TableScalar(float scalar) const
{
  if (!this->Logarithmic)
  {
    return scalar;
  }
  // as the shader's amrspTableScalar: at or below 0 before every entry
  return scalar > 0.0f ? std::log10(scalar) : -FLT_MAX;
}

void vtkAMRMapperTransferFunctionTable::ReleaseGraphicsResources(vtkWindow* window)
{
  if (this->Texture)
  {
    this->Texture->ReleaseGraphicsResources(window);
    this->Texture = nullptr;
  }
  this->Property = nullptr;
}
