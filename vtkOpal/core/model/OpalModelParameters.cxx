#include "OpalModelParameters.h"

#include "OpalMessages.h"
#include "OpalModelFields.h"
#include "OpalPresets.h"

#include <cmath>
#include <sstream>
#include <utility>
#include <vector>

namespace opal
{

bool ModelParameters::applyPreset(int presetIndex)
{
  const PresetSettings* preset = presetByIndex(presetIndex);
  if (!preset)
  {
    return presetIndex == CustomPreset;
  }
  // Every field a preset may set: its value, else the model's default, so a
  // preset gives the same volume whichever preset came before (docs/design.md §2.8).
  const ModelParameters defaults;
  for (const ModelField& field : presetModelFields())
  {
    const std::vector<double>* values = preset->valuesOf(field.Name);
    field.Set(*this, values ? *values : field.Get(defaults));
  }
  return true;
}

namespace
{

template <typename T>
std::string rangeError(const char* name, const std::array<T, 2>& range)
{
  std::ostringstream message = messageStream();
  if (range[0] > range[1])
  {
    message << name << " has min " << range[0] << " > max " << range[1] << ".";
  }
  return message.str();
}

template <typename T>
std::string positiveRangeError(const char* name, const std::array<T, 2>& range)
{
  std::string error = rangeError(name, range);
  if (error.empty() && !(range[0] > 0))
  {
    std::ostringstream message = messageStream();
    message << name << " must be positive, got min " << range[0] << ".";
    error = message.str();
  }
  return error;
}

std::string withinRangeError(const char* name, const std::array<double, 2>& range, double lo, double hi)
{
  std::string error = rangeError(name, range);
  if (error.empty() && !(range[0] >= lo && range[1] <= hi))
  {
    std::ostringstream message = messageStream();
    message << name << " must lie within [" << lo << ", " << hi << "], got [" << range[0] << ", "
            << range[1] << "].";
    error = message.str();
  }
  return error;
}

} // namespace

namespace
{
// Every real-valued parameter must be a finite number before anything else.
std::string finiteError(const ModelParameters& p)
{
  const std::pair<const char*, std::vector<double>> reals[] = {
    { "PhysicalSize", { p.PhysicalSize.begin(), p.PhysicalSize.end() } },
    { "SemiAxes", { p.SemiAxes.begin(), p.SemiAxes.end() } },
    { "ScatteringDiameterRange", { p.ScatteringDiameterRange.begin(), p.ScatteringDiameterRange.end() } },
    { "ScatteringVolumeFraction", { p.ScatteringVolumeFraction } },
    { "DomainRadiusRange", { p.DomainRadiusRange.begin(), p.DomainRadiusRange.end() } },
    { "DomainVertexJitter", { p.DomainVertexJitter.begin(), p.DomainVertexJitter.end() } },
    { "DomainAngleRange", { p.DomainAngleRange.begin(), p.DomainAngleRange.end() } },
    { "DomainRotationRange", { p.DomainRotationRange.begin(), p.DomainRotationRange.end() } },
    { "DomainDiameterRange", { p.DomainDiameterRange.begin(), p.DomainDiameterRange.end() } },
    { "RefractiveIndex", { p.RefractiveIndex } },
    { "VoronoiWeightSpread", { p.VoronoiWeightSpread } },
    { "OrderedFraction", { p.OrderedFraction } },
    { "DiameterCorrelationLength", { p.DiameterCorrelationLength } },
    { "BodyAbsorption", { p.BodyAbsorption } },
    { "BodyAbsorptionExponent", { p.BodyAbsorptionExponent } },
    { "BackingThickness", { p.BackingThickness } },
    { "BackingAbsorption", { p.BackingAbsorption } },
    { "DomainScatteringCoefficient", { p.DomainScatteringCoefficient } },
    { "SphereRefractiveIndex", { p.SphereRefractiveIndex } },
    { "MatrixRefractiveIndex", { p.MatrixRefractiveIndex } },
  };
  for (const auto& [name, values] : reals)
  {
    for (double value : values)
    {
      if (!std::isfinite(value))
      {
        std::ostringstream message = messageStream();
        message << name << " must be a finite number, got " << value << ".";
        return message.str();
      }
    }
  }
  return {};
}

// Plausible magnitudes: beyond them lengths squared overflow or underflow.
std::string magnitudeError(const ModelParameters& p)
{
  const struct
  {
    const char* Name;
    std::vector<double> Values;
    double Lo, Hi;
    const char* Unit;
  } magnitudes[] = {
    { "PhysicalSize", { p.PhysicalSize.begin(), p.PhysicalSize.end() }, 1e-6, 1e4, "mm" },
    { "SemiAxes", { p.SemiAxes.begin(), p.SemiAxes.end() }, 1e-6, 1e4, "mm" },
    { "ScatteringDiameterRange", { p.ScatteringDiameterRange.begin(), p.ScatteringDiameterRange.end() }, 1e-3, 1e5, "nm" },
    { "DomainDiameterRange", { p.DomainDiameterRange.begin(), p.DomainDiameterRange.end() }, 1e-3, 1e5, "nm" },
    { "DomainRadiusRange", { p.DomainRadiusRange.begin(), p.DomainRadiusRange.end() }, 1e-6, 1e4, "mm" },
  };
  for (const auto& magnitude : magnitudes)
  {
    for (double value : magnitude.Values)
    {
      if (std::fabs(value) > magnitude.Hi || (value > 0 && value < magnitude.Lo))
      {
        std::ostringstream message = messageStream();
        message << magnitude.Name << " must lie within [" << magnitude.Lo << ", " << magnitude.Hi << "] "
                << magnitude.Unit << ", got " << value << ".";
        return message.str();
      }
    }
  }
  return {};
}

// The grid and the half-ellipsoid, which sits on the base y = 0, centred in x and z.
std::string shapeError(const ModelParameters& p)
{
  static const char* axis = "xyz";
  std::ostringstream message = messageStream();
  for (int a = 0; a < 3; ++a)
  {
    if (p.Dimensions[a] < 1)
    {
      message << "Dimensions must be positive, got " << p.Dimensions[a] << " along " << axis[a] << ".";
    }
    else if (!(p.PhysicalSize[a] > 0))
    {
      message << "PhysicalSize must be positive, got " << p.PhysicalSize[a] << " mm along " << axis[a] << ".";
    }
    else if (!(p.SemiAxes[a] > 0))
    {
      message << "SemiAxes must be positive, got " << p.SemiAxes[a] << " mm along " << axis[a] << ".";
    }
    if (!message.str().empty())
    {
      return message.str();
    }
  }
  const std::array<double, 3> room{ p.PhysicalSize[0] / 2, p.PhysicalSize[1], p.PhysicalSize[2] / 2 };
  for (int a = 0; a < 3; ++a)
  {
    if (p.SemiAxes[a] > room[a] * (1 + 1e-9))
    {
      message << "SemiAxes: the shape does not fit the box: semi-axis " << axis[a] << " = " << p.SemiAxes[a]
              << " mm exceeds " << room[a] << " mm (PhysicalSize).";
      return message.str();
    }
  }
  return {};
}

std::string rangesError(const ModelParameters& p)
{
  for (const std::string& error : {
         positiveRangeError("ScatteringDiameterRange", p.ScatteringDiameterRange),
         positiveRangeError("DomainRadiusRange", p.DomainRadiusRange),
         positiveRangeError("DomainDiameterRange", p.DomainDiameterRange),
         withinRangeError("DomainVertexJitter", p.DomainVertexJitter, 0.0, 1.0),
         withinRangeError("DomainAngleRange", p.DomainAngleRange, 0.0, 180.0),
         withinRangeError("DomainRotationRange", p.DomainRotationRange, 0.0, 90.0),
         rangeError("DomainVertexRange", p.DomainVertexRange),
       })
  {
    if (!error.empty())
    {
      return error;
    }
  }
  if (!(p.DomainVertexJitter[0] > 0))
  {
    return "DomainVertexJitter must be above 0: a vertex at the centre degenerates the polygon.";
  }
  return {};
}

std::string scalarsError(const ModelParameters& p)
{
  std::ostringstream message = messageStream();
  if (!(p.ScatteringVolumeFraction > 0 && p.ScatteringVolumeFraction <= MaxVolumeFraction))
  {
    message << "ScatteringVolumeFraction must lie in (0, " << MaxVolumeFraction << "], got "
            << p.ScatteringVolumeFraction << ".";
  }
  else if (const std::string index = refractiveIndexError(p.RefractiveIndex); !index.empty())
  {
    message << index;
  }
  return message.str();
}

// The Voronoi layout's settings and the diameter field (docs/design.md §2.3, §2.9).
std::string grainsError(const ModelParameters& p)
{
  std::ostringstream message = messageStream();
  if (!(p.DiameterCorrelationLength == 0 ||
             (p.DiameterCorrelationLength >= 1e-6 && p.DiameterCorrelationLength <= 1e4)))
  {
    message << "DiameterCorrelationLength must be 0 (independent voxels) or lie in [1e-06, 10000] mm, got "
            << p.DiameterCorrelationLength << ".";
  }
  return message.str();
}

// Absorption, the backing and domain scattering (docs/design.md §2.10).
std::string opticsError(const ModelParameters& p)
{
  std::ostringstream message = messageStream();
  if (!(p.BackingThickness >= 0 && p.BackingThickness <= p.PhysicalSize[1]))
  {
    message << "BackingThickness must lie in [0, " << p.PhysicalSize[1] << "] mm (the box's height, PhysicalSize), got "
            << p.BackingThickness << ".";
  }
  else if (!(p.SphereRefractiveIndex >= 1 && p.SphereRefractiveIndex < 4))
  {
    message << "SphereRefractiveIndex must lie in [1, 4), got " << p.SphereRefractiveIndex << ".";
  }
  else if (!(p.MatrixRefractiveIndex >= 1 && p.MatrixRefractiveIndex < 4))
  {
    message << "MatrixRefractiveIndex must lie in [1, 4), got " << p.MatrixRefractiveIndex << ".";
  }
  return message.str();
}
} // namespace

bool ModelParameters::absorbs() const
{
  return this->BodyAbsorption > 0 || (this->BackingThickness > 0 && this->BackingAbsorption > 0);
}

namespace
{
// Every row's range (OPAL_MODEL_PARAMETERS).
std::string tableError(const ModelParameters& p)
{
  return tableRangeError(modelParameterRows(), p);
}
} // namespace

const std::vector<ParameterRow<ModelParameters>>& modelParameterRows()
{
  using OpalTableStruct = ModelParameters;
  static const std::vector<ParameterRow<OpalTableStruct>> rows = { OPAL_MODEL_PARAMETERS(OPAL_TABLE_ROW) };
  return rows;
}

std::string validate(const ModelParameters& p)
{
  return firstError(
    p, { finiteError, magnitudeError, shapeError, rangesError, scalarsError, grainsError, opticsError, tableError });
}

std::string smallShapeWarning(const ModelParameters& p)
{
  static const char* axes[3] = { "x", "y", "z" };
  for (std::size_t a = 0; a < 3; ++a)
  {
    const double spacing = p.PhysicalSize[a] / p.Dimensions[a];
    if (p.SemiAxes[a] < 2 * spacing)
    {
      std::ostringstream message = messageStream();
      message << "SemiAxes " << p.SemiAxes[a] << " mm spans fewer than two voxels (" << spacing << " mm) along "
              << axes[a] << ": the opal is (nearly) empty; use larger SemiAxes or more voxels.";
      return message.str();
    }
  }
  return {};
}

} // namespace opal
