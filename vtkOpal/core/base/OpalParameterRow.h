// One row of a parameter table (docs/design.md §1.1): a parameter's name
// (its member, VTK's Set/Get and ParaView's property), its type as VTK and
// ParaView hold it, its components, allowed range, enumeration names, CLI flag
// and one-line description, with access to the member of the parameters'
// struct, whose initialiser is the default. The layers loop over the rows
// instead of spelling each parameter out.
#pragma once

#include "OpalMessages.h"

#include <array>
#include <cmath>
#include <limits>
#include <sstream>
#include <string>
#include <type_traits>
#include <utility>
#include <vector>

namespace opal
{

// How VTK and ParaView hold a parameter (an enumeration is an Int with names).
enum class ParameterType : int
{
  Int = 0,
  Double = 1,
  Bool = 2,
};

// No bound (Min -Unbounded, Max Unbounded): an unbounded row still refuses infinity and NaN.
constexpr double Unbounded = std::numeric_limits<double>::max();

template <typename Parameters>
struct ParameterRow
{
  const char* Name;        // "StepSize": member, Set/Get and property name
  ParameterType Type;      // int, double or bool
  int Components;          // 1-4
  double Min;              // each component's allowed range, inclusive
  double Max;              //   (-Unbounded, Unbounded: none, only finite)
  const char* Choices;     // an enumeration's names for 0, 1, ..., space-separated; "" otherwise
  const char* Flag;        // the CLI flag, "--step-size"; "" where the CLI sets it otherwise
  bool FromVolume;         // VTK's and ParaView's default is 0: the volume's value
  const char* Description; // one line: CLI help, docs
  std::vector<double> (*Get)(const Parameters&);
  void (*Set)(Parameters&, const std::vector<double>&);
};

namespace parameter_access
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

// Whole numbers, booleans and enumerations arrive as doubles (ParaView's helpers, the CLI).
template <typename T>
void assign(T& target, const std::vector<double>& values)
{
  target = static_cast<T>(static_cast<long long>(values.at(0)));
}

inline void assign(double& target, const std::vector<double>& values)
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

template <typename T>
struct Shape
{
  using Element = T;
  static constexpr int Components = 1;
};

template <typename T, std::size_t N>
struct Shape<std::array<T, N>>
{
  using Element = T;
  static constexpr int Components = static_cast<int>(N);
};

// A member of this element type can be held as VtkType without loss.
template <typename Element, typename VtkType>
constexpr bool holds()
{
  if constexpr (std::is_same_v<VtkType, int>)
  {
    return std::is_integral_v<Element> || std::is_enum_v<Element>; // enumerations as their int; ranges bound the rest
  }
  return std::is_same_v<Element, VtkType>;
}

template <typename T>
constexpr ParameterType typeOf()
{
  return std::is_same_v<T, double> ? ParameterType::Double
                                   : (std::is_same_v<T, bool> ? ParameterType::Bool : ParameterType::Int);
}
} // namespace parameter_access

// The row of `Member` (a table's X-macro expands to these); the member's
// shape must be the row's, or the table does not compile.
template <typename Parameters, auto Member, typename VtkType, int Components>
ParameterRow<Parameters> parameterRow(
  const char* name, double min, double max, const char* choices, const char* flag, bool fromVolume,
  const char* description)
{
  using namespace parameter_access;
  using Member_t = std::remove_cv_t<std::remove_reference_t<decltype(std::declval<Parameters>().*Member)>>;
  static_assert(Shape<Member_t>::Components == Components, "the row's Count is not the member's");
  static_assert(holds<typename Shape<Member_t>::Element, VtkType>(), "the row's Type cannot hold the member");
  return { name, typeOf<VtkType>(), Components, min, max, choices, flag, fromVolume, description,
    [](const Parameters& p) { return valuesOf(p.*Member); },
    [](Parameters& p, const std::vector<double>& values) { assign(p.*Member, values); } };
}

// A table's X-macro row as a ParameterRow of the struct named OpalTableStruct
// where it expands: { OPAL_RENDER_PARAMETERS(OPAL_TABLE_ROW) } lists a table's rows.
#define OPAL_TABLE_ROW(Name, Type, Count, Min, Max, Choices, Flag, FromVolume, Description)                  \
  ::opal::parameterRow<OpalTableStruct, &OpalTableStruct::Name, Type, Count>(                             \
    #Name, Min, Max, Choices, Flag, FromVolume, Description),

// An enumeration's names: "paper coupled-wave" -> { "paper", "coupled-wave" }.
std::vector<std::string> choicesOf(const char* choices);

// Empty if every component of the row's value lies in its range (an
// enumeration: is one of its values), else one sentence naming the parameter.
std::string rowRangeError(
  const char* name, const std::vector<double>& values, double min, double max, const char* choices);

// The first row of the table whose value in `p` is out of its range; empty if none.
template <typename Parameters>
std::string tableRangeError(const std::vector<ParameterRow<Parameters>>& rows, const Parameters& p)
{
  for (const ParameterRow<Parameters>& row : rows)
  {
    std::string error = rowRangeError(row.Name, row.Get(p), row.Min, row.Max, row.Choices);
    if (!error.empty())
    {
      return error;
    }
  }
  return {};
}

// The row of that name, or nullptr.
template <typename Parameters>
const ParameterRow<Parameters>* findRow(const std::vector<ParameterRow<Parameters>>& rows, const std::string& name)
{
  for (const ParameterRow<Parameters>& row : rows)
  {
    if (name == row.Name)
    {
      return &row;
    }
  }
  return nullptr;
}

} // namespace opal
