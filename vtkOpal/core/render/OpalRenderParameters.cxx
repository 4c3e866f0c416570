#include "OpalRenderParameters.h"

#include "OpalMessages.h"
#include "OpalSpectralSampling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace opal
{

const std::vector<ParameterRow<RenderParameters>>& renderParameterRows()
{
  using OpalTableStruct = RenderParameters;
  static const std::vector<ParameterRow<OpalTableStruct>> rows = { OPAL_RENDER_PARAMETERS(OPAL_TABLE_ROW) };
  return rows;
}

int wavelengthCount(const RenderParameters& p)
{
  return wavelengthBinCount(p.WavelengthRange[0], p.WavelengthRange[1], p.WavelengthStep);
}

bool conservesEnergy(const RenderParameters& p)
{
  return p.EnergyConservation || p.BraggModel == BraggModelKind::CoupledWave;
}

bool scattersEveryOrder(const RenderParameters& p)
{
  return p.ScatteringOrders == ScatteringOrdersKind::All;
}

double effectiveMosaicSpread(const RenderParameters& p)
{
  return p.BraggModel == BraggModelKind::CoupledWave && p.MosaicSpread == 0.0 ? CoupledWaveDefaultSpread
                                                                                : p.MosaicSpread;
}

RenderParameters withQuality(const RenderParameters& p)
{
  RenderParameters q = p;
  q.Quality = RenderQuality::Final;
  if (p.Quality != RenderQuality::Preview)
  {
    return q;
  }
  const int scale = p.PreviewScale;
  auto shrink = [scale](int n) { return n > 0 ? (n + scale - 1) / scale : n; };
  q.ImageSize = { shrink(p.ImageSize[0]), shrink(p.ImageSize[1]) };
  q.ImageRegion = { p.ImageRegion[0] / scale, p.ImageRegion[1] / scale, shrink(p.ImageRegion[2]),
    shrink(p.ImageRegion[3]) };
  q.WavelengthStep = std::max(p.WavelengthStep, 20.0);
  q.SpectralNodes = p.SpectralNodes == 0 ? 0 : 8;
  q.SpecularSamples = std::min(p.SpecularSamples, 2);
  q.PixelSamples = 1;
  return q;
}

namespace
{
bool finite3(const std::array<double, 3>& v)
{
  return std::isfinite(v[0]) && std::isfinite(v[1]) && std::isfinite(v[2]);
}

// Positions within a kilometre: the scene is millimetres, and the device
// squares distances in float.
constexpr double MaxSceneDistance = 1e6;

bool withinReach(const std::array<double, 3>& v)
{
  return std::fabs(v[0]) <= MaxSceneDistance && std::fabs(v[1]) <= MaxSceneDistance &&
    std::fabs(v[2]) <= MaxSceneDistance;
}

std::string imageError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (p.ImageSize[0] < 1 || p.ImageSize[1] < 1 || p.ImageSize[0] > 16384 || p.ImageSize[1] > 16384)
  {
    m << "ImageSize must be 1-16384 pixels each way, got " << p.ImageSize[0] << " x " << p.ImageSize[1] << ".";
  }
  else if (p.ImageRegion[0] < 0 || p.ImageRegion[1] < 0 || p.ImageRegion[0] >= p.ImageSize[0] ||
    p.ImageRegion[1] >= p.ImageSize[1] || p.ImageRegion[0] + p.ImageRegion[2] > p.ImageSize[0] ||
    p.ImageRegion[1] + p.ImageRegion[3] > p.ImageSize[1])
  {
    m << "ImageRegion (" << p.ImageRegion[0] << ", " << p.ImageRegion[1] << ", " << p.ImageRegion[2] << ", "
      << p.ImageRegion[3] << ") must lie within the " << p.ImageSize[0] << " x " << p.ImageSize[1] << " image.";
  }
  return m.str();
}

std::string cameraError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (!finite3(p.EyePosition) || !finite3(p.FocalPoint) || !finite3(p.LightPosition) || !finite3(p.ViewUp))
  {
    m << "EyePosition, FocalPoint, LightPosition and ViewUp must be finite.";
  }
  else if (!withinReach(p.EyePosition) || !withinReach(p.FocalPoint) || !withinReach(p.LightPosition))
  {
    // Squared distances beyond this leave float's range on the device.
    m << "EyePosition, FocalPoint and LightPosition must lie within " << MaxSceneDistance << " mm of the origin.";
  }
  else if (p.EyePosition == p.FocalPoint)
  {
    m << "FocalPoint must differ from EyePosition.";
  }
  else if (!(p.ViewUp[0] * p.ViewUp[0] + p.ViewUp[1] * p.ViewUp[1] + p.ViewUp[2] * p.ViewUp[2] > 0))
  {
    m << "ViewUp must not be the zero vector.";
  }
  else if (!(p.ViewAngle > 0 && p.ViewAngle < 179))
  {
    m << "ViewAngle must lie in (0, 179) degrees, got " << p.ViewAngle << ".";
  }
  else if (!finite3(p.ModelRotation) || !finite3(p.PresetRotation))
  {
    m << (finite3(p.ModelRotation) ? "PresetRotation" : "ModelRotation") << " must be finite.";
  }
  return m.str();
}

std::string spectrumError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (!(p.WavelengthRange[0] >= 200 && p.WavelengthRange[1] <= 1000 && p.WavelengthRange[0] <= p.WavelengthRange[1]))
  {
    m << "WavelengthRange must be min <= max within [200, 1000] nm, got [" << p.WavelengthRange[0] << ", "
      << p.WavelengthRange[1] << "].";
  }
  else if (!(p.WavelengthStep > 0))
  {
    m << "WavelengthStep must be positive, got " << p.WavelengthStep << " nm.";
  }
  else if (!(p.WavelengthStep >= 0.01 && p.WavelengthStep <= 800))
  {
    // Bounded before the count, which could not be held beyond these.
    m << "WavelengthStep must lie in [0.01, 800] nm, got " << p.WavelengthStep << " nm.";
  }
  else if (wavelengthCount(p) > MaxWavelengths)
  {
    m << "WavelengthStep " << p.WavelengthStep << " nm gives " << wavelengthCount(p) << " wavelengths; at most "
      << MaxWavelengths << " are supported.";
  }
  else if (p.SpectralNodes != 0 && (p.SpectralNodes < 4 || p.SpectralNodes > 64))
  {
    m << "SpectralNodes must be 0 (every wavelength) or 4-64, got " << p.SpectralNodes << ".";
  }
  return m.str();
}

std::string opticsError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (const std::string index = refractiveIndexError(p.RefractiveIndex); !index.empty())
  {
    m << index;
  }
  else if (!(p.BraggBandwidth > 0 && p.BraggBandwidth < 1))
  {
    m << "BraggBandwidth must lie in (0, 1), got " << p.BraggBandwidth << ".";
  }
  return m.str();
}

// The settings beyond the paper (docs/design.md §7.2).
std::string braggModelError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (p.LatticePlanes == LatticePlaneSet::Fcc && p.BraggModel == BraggModelKind::Paper)
  {
    // The paper's box band has no strength per family to give the others.
    m << "LatticePlanes fcc needs BraggModel coupled-wave.";
  }
  return m.str();
}

// Every row's range (OPAL_RENDER_PARAMETERS).
std::string rangeError(const RenderParameters& p)
{
  return tableRangeError(renderParameterRows(), p);
}
} // namespace

std::string validate(const RenderParameters& p)
{
  return firstError(p, { imageError, cameraError, spectrumError, opticsError, braggModelError, rangeError });
}

} // namespace opal
