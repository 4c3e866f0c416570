#include "vtkOpalInputArrays.h"

#include "vtkArrayDispatch.h"
#include "vtkDataArray.h"
#include "vtkDataArrayRange.h"
#include "vtkFieldData.h"

#include <cmath>
#include <cstdint>
#include <limits>
#include <sstream>

namespace
{
using Expected = vtkOpalInputArrays::Expected;

// Whether a value is one a reader of this kind may use.
bool acceptable(double value, Expected::Values kind)
{
  if (kind == Expected::Values::Real)
  {
    return std::isfinite(value);
  }
  constexpr double low = std::numeric_limits<std::int32_t>::min();
  constexpr double high = std::numeric_limits<std::int32_t>::max();
  return std::isfinite(value) && value == std::floor(value) && value >= low && value <= high;
}

// The flat index of the first value `acceptable` refuses, or -1. Floating
// arrays are scanned whole; integer arrays need the range test only for ids
// (a 64-bit id can wrap int32) and never hold a non-finite value.
vtkIdType firstUnacceptable(vtkDataArray* array, Expected::Values kind)
{
  vtkIdType found = -1;
  auto scan = [&found, kind](auto* typed) {
    const auto values = vtk::DataArrayValueRange(typed);
    for (auto it = values.begin(); it != values.end(); ++it)
    {
      if (!acceptable(static_cast<double>(*it), kind))
      {
        found = static_cast<vtkIdType>(it - values.begin());
        return;
      }
    }
  };
  if (!vtkArrayDispatch::Dispatch::Execute(array, scan))
  {
    scan(array);
  }
  return found;
}

// The sentence for a value refused at flat index `index`.
std::string valueError(vtkDataArray* array, const Expected& expected, const char* role, vtkIdType index)
{
  const int components = array->GetNumberOfComponents();
  std::ostringstream message;
  message.precision(17);
  message << "The " << role << " " << expected.Name << " holds " << array->GetComponent(index / components, index % components)
          << " at tuple " << index / components;
  if (components > 1)
  {
    message << " (component " << index % components << ")";
  }
  message << (expected.Kind == Expected::Values::Id ? "; it needs whole numbers in [-2147483648, 2147483647]."
                                                    : "; it needs finite numbers.");
  return message.str();
}

// Empty if the array's shape is what the reader indexes, else the sentence.
std::string shapeError(vtkDataArray* array, const Expected& expected, const char* role)
{
  std::ostringstream message;
  message << "The " << role << " " << expected.Name;
  if (array->GetNumberOfComponents() != expected.Components)
  {
    message << " needs " << expected.Components << (expected.Components == 1 ? " component" : " components")
            << ", it has " << array->GetNumberOfComponents() << ".";
    return message.str();
  }
  const vtkIdType tuples = array->GetNumberOfTuples();
  const bool fits = expected.Tuples == Expected::AnyCount ||
    (expected.Tuples == Expected::FieldValue ? tuples >= 1 : tuples == expected.Tuples);
  if (!fits)
  {
    message << " needs "
            << (expected.Tuples == Expected::FieldValue ? std::string("a value") : std::to_string(expected.Tuples) + " tuples")
            << ", it has " << tuples << (tuples == 1 ? " tuple." : " tuples.");
    return message.str();
  }
  return {};
}
} // namespace

namespace vtkOpalInputArrays
{
vtkDataArray* Find(vtkFieldData* data, const Expected& expected, const char* role, bool required, std::string& error)
{
  if (!error.empty())
  {
    return nullptr;
  }
  vtkAbstractArray* abstract = data ? data->GetAbstractArray(expected.Name) : nullptr;
  vtkDataArray* array = vtkDataArray::SafeDownCast(abstract);
  if (!array)
  {
    if (abstract || required)
    {
      error = "The input " + std::string(abstract ? "has a non-numeric " : "lacks the ") + role + " " + expected.Name +
        (abstract ? "; it needs numbers." : ".");
    }
    return nullptr;
  }
  error = shapeError(array, expected, role);
  if (error.empty())
  {
    const vtkIdType bad = firstUnacceptable(array, expected.Kind);
    error = bad < 0 ? std::string() : valueError(array, expected, role, bad);
  }
  return error.empty() ? array : nullptr;
}
} // namespace vtkOpalInputArrays
