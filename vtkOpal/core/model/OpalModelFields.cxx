#include "OpalModelFields.h"

namespace opal
{

const std::vector<ModelField>& presetModelFields()
{
  static const std::vector<ModelField> rows = [] {
    std::vector<ModelField> fields;
    for (const char* name : { "ScatteringVolumeFraction", "DomainCount", "DomainRadiusRange", "DomainDiameterRange",
           "DomainLayout", "VoronoiCellCount", "VoronoiWeightSpread", "OrderedFraction", "BodyAbsorption",
           "BodyAbsorptionExponent", "BackingThickness", "BackingAbsorption", "DomainScatteringCoefficient" })
    {
      fields.push_back(*findRow(modelParameterRows(), name));
    }
    return fields;
  }();
  return rows;
}

const ModelField* presetModelField(const std::string& property)
{
  return findRow(presetModelFields(), property);
}

} // namespace opal
