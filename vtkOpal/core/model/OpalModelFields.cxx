#include "OpalModelFields.h"

#include <cctype>

namespace opal
{

namespace
{
template <typename T>
std::vector<double> valuesOf(const T& value)
{
  return { static_cast<double>(value) };
}

template <typename T, std::size_t N>
std::vector<double> valuesOf(const std::array<T, N>& values)
{
  return std::vector<double>(values.begin(), values.end());
}

// Whole numbers and enumerations arrive as doubles (ParaView's helper, the table).
template <typename T>
void assign(T& target, const std::vector<double>& values)
{
  target = static_cast<T>(static_cast<long long>(values.at(0)));
}

void assign(double& target, const std::vector<double>& values)
{
  target = values.at(0);
}

template <typename T, std::size_t N>
void assign(std::array<T, N>& target, const std::vector<double>& values)
{
  for (std::size_t i = 0; i < N; ++i)
  {
    target[i] = static_cast<T>(values.at(i));
  }
}

template <auto Member>
ModelField field(const char* property)
{
  return { property, [](const ModelParameters& p) { return valuesOf(p.*Member); },
    [](ModelParameters& p, const std::vector<double>& values) { assign(p.*Member, values); } };
}
} // namespace

const std::vector<ModelField>& presetModelFields()
{
  using P = ModelParameters;
  static const std::vector<ModelField> table = {
    field<&P::ScatteringVolumeFraction>("ScatteringVolumeFraction"),
    field<&P::DomainCount>("DomainCount"),
    field<&P::DomainRadiusRange>("DomainRadiusRange"),
    field<&P::DomainDiameterRange>("DomainDiameterRange"),
    field<&P::DomainLayout>("DomainLayout"),
    field<&P::VoronoiCellCount>("VoronoiCellCount"),
    field<&P::VoronoiWeightSpread>("VoronoiWeightSpread"),
    field<&P::OrderedFraction>("OrderedFraction"),
    field<&P::BodyAbsorption>("BodyAbsorption"),
    field<&P::BodyAbsorptionExponent>("BodyAbsorptionExponent"),
    field<&P::BackingThickness>("BackingThickness"),
    field<&P::BackingAbsorption>("BackingAbsorption"),
    field<&P::DomainScatteringCoefficient>("DomainScatteringCoefficient"),
  };
  return table;
}

const ModelField* presetModelField(const std::string& property)
{
  for (const ModelField& f : presetModelFields())
  {
    if (property == f.Property)
    {
      return &f;
    }
  }
  return nullptr;
}

std::string flagOf(const std::string& property)
{
  std::string flag = "-";
  for (const char c : property)
  {
    if (std::isupper(static_cast<unsigned char>(c)))
    {
      flag += '-';
    }
    flag += static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
  }
  return flag;
}

} // namespace opal
