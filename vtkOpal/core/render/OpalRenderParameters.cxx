#include "OpalRenderParameters.h"

#include "OpalMessages.h"
#include "OpalSpectralSampling.h"

#include <algorithm>
#include <cmath>
#include <sstream>

namespace opal
{

int wavelengthCount(const RenderParameters& p)
{
  return wavelengthBinCount(p.WavelengthRange[0], p.WavelengthRange[1], p.WavelengthStep);
}

bool conservesEnergy(const RenderParameters& p)
{
  return p.EnergyConservation || p.BraggModel == BraggModelKind::CoupledWave;
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
  auto half = [](int n) { return n > 0 ? (n + 1) / 2 : n; };
  q.ImageSize = { half(p.ImageSize[0]), half(p.ImageSize[1]) };
  q.ImageRegion = { p.ImageRegion[0] / 2, p.ImageRegion[1] / 2, half(p.ImageRegion[2]), half(p.ImageRegion[3]) };
  q.WavelengthStep = std::max(p.WavelengthStep, 20.0);
  q.SpectralNodes = p.SpectralNodes == 0 ? 0 : 8;
  q.SpecularSamples = std::min(p.SpecularSamples, 2);
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
  else if (!(p.LightRadius >= 1e-6 && p.LightRadius <= 1000))
  {
    m << "LightRadius must lie in [1e-6, 1000] mm, got " << p.LightRadius << " mm.";
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
  else if (p.Illuminant != LightSpectrum::D65 && p.Illuminant != LightSpectrum::None)
  {
    m << "Illuminant must be 0 (D65) or 1 (none), got " << static_cast<int>(p.Illuminant) << ".";
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
  else if (!(p.DiffractionGain >= 0 && p.DiffractionGain <= 1000))
  {
    // The paper's is 4; beyond 1000 the radiance leaves float's range.
    m << "DiffractionGain must lie in [0, 1000], got " << p.DiffractionGain << ".";
  }
  else if (p.BraggOrders < 1 || p.BraggOrders > 8)
  {
    m << "BraggOrders must be 1-8, got " << p.BraggOrders << ".";
  }
  else if (!(p.MosaicSpread >= 0 && p.MosaicSpread <= 90))
  {
    m << "MosaicSpread must lie in [0, 90] degrees, got " << p.MosaicSpread << ".";
  }
  return m.str();
}

// The settings beyond the paper (docs/design.md §7.2).
std::string braggModelError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (p.BraggModel != BraggModelKind::Paper && p.BraggModel != BraggModelKind::CoupledWave)
  {
    m << "BraggModel must be 0 (paper) or 1 (coupled-wave), got " << static_cast<int>(p.BraggModel) << ".";
  }
  else if (p.LatticePlanes != LatticePlaneSet::Stacking111 && p.LatticePlanes != LatticePlaneSet::Fcc)
  {
    m << "LatticePlanes must be 0 (111) or 1 (fcc), got " << static_cast<int>(p.LatticePlanes) << ".";
  }
  else if (p.LatticePlanes == LatticePlaneSet::Fcc && p.BraggModel != BraggModelKind::CoupledWave)
  {
    // The paper's box band has no strength per family to give the others.
    m << "LatticePlanes fcc needs BraggModel coupled-wave.";
  }
  else if (p.CoherentLayers < 1 || p.CoherentLayers > MaxCoherentLayers)
  {
    m << "CoherentLayers must be 1-" << MaxCoherentLayers << ", got " << p.CoherentLayers << ".";
  }
  return m.str();
}

std::string samplingError(const RenderParameters& p)
{
  std::ostringstream m = messageStream();
  if (!(p.Exposure >= 0 && std::isfinite(p.Exposure)))
  {
    m << "Exposure must be 0 (automatic) or positive, got " << p.Exposure << ".";
  }
  else if (!(p.StepSize >= 0 && std::isfinite(p.StepSize)))
  {
    m << "StepSize must be 0 (one voxel) or positive, got " << p.StepSize << " mm.";
  }
  else if (p.SpecularSamples < 1 || p.SpecularSamples > 16)
  {
    m << "SpecularSamples must be 1-16, got " << p.SpecularSamples << ".";
  }
  else if (p.Quality != RenderQuality::Final && p.Quality != RenderQuality::Preview)
  {
    m << "Quality must be 0 (final) or 1 (preview), got " << static_cast<int>(p.Quality) << ".";
  }
  else if (!std::all_of(p.Background.begin(), p.Background.end(), [](double b) { return b >= 0 && b <= 1; }))
  {
    m << "Background components must lie in [0, 1].";
  }
  return m.str();
}
} // namespace

std::string validate(const RenderParameters& p)
{
  return firstError(p, { imageError, cameraError, spectrumError, opticsError, braggModelError, samplingError });
}

} // namespace opal
