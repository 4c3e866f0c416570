#include "OpalParameterRow.h"

namespace opal
{

std::vector<std::string> choicesOf(const char* choices)
{
  std::istringstream words(choices);
  std::vector<std::string> names;
  for (std::string name; words >> name;)
  {
    names.push_back(name);
  }
  return names;
}

namespace
{
std::string enumerationError(const char* name, double value, const std::vector<std::string>& names)
{
  if (value >= 0 && value < static_cast<double>(names.size()) && value == std::floor(value))
  {
    return {};
  }
  std::ostringstream m = messageStream();
  m << name << " must be";
  for (std::size_t i = 0; i < names.size(); ++i)
  {
    m << (i == 0 ? " " : (i + 1 == names.size() ? " or " : ", ")) << i << " (" << names[i] << ")";
  }
  m << ", got " << value << ".";
  return m.str();
}
} // namespace

std::string rowRangeError(
  const char* name, const std::vector<double>& values, double min, double max, const char* choices)
{
  const std::vector<std::string> names = choicesOf(choices);
  bool inRange = true;
  for (const double v : values)
  {
    if (!names.empty())
    {
      return enumerationError(name, v, names);
    }
    inRange = inRange && v >= min && v <= max; // false for NaN
  }
  if (inRange)
  {
    return {};
  }
  std::ostringstream m = messageStream();
  m << name << (values.size() > 1 ? " components" : "");
  if (min == -Unbounded && max == Unbounded)
  {
    m << " must be finite";
  }
  else if (max == Unbounded)
  {
    m << " must lie in [" << min << ", inf)";
  }
  else
  {
    m << " must lie in [" << min << ", " << max << "]";
  }
  m << ", got";
  for (const double v : values)
  {
    m << " " << v;
  }
  m << ".";
  return m.str();
}

} // namespace opal
