// The one rule for every array Opal's filters read from their input (the
// render, the Bragg map and the live representation through the render;
// docs/design.md §6): an array is used only once it is known to be numeric,
// to have the components and the tuples its reader indexes, and to hold
// finite values (integers within int32 for ids). A crafted file can then
// neither overrun a reader's buffer nor smuggle a NaN or a wrapped id into
// an image; what fails is refused naming the array and the element.
#pragma once

#include "vtkType.h"

#include <string>

class vtkDataArray;
class vtkFieldData;

namespace vtkOpalInputArrays
{
// What a reader needs of one array.
struct Expected
{
  enum class Values
  {
    Real, // finite numbers
    Id    // whole numbers in [-2^31, 2^31): converted to int32 without loss
  };
  const char* Name;
  int Components;
  // The tuples the reader indexes: one per point, cell or domain; or
  // FieldValue (at least one tuple, the first read) or AnyCount (a table).
  vtkIdType Tuples;
  static constexpr vtkIdType FieldValue = -1;
  static constexpr vtkIdType AnyCount = -2;
  Values Kind = Values::Real;
};

// The named array of `data` checked against `expected`, or nullptr: absent
// (no error unless `required`), or malformed (`error` names the array as a
// `role`, e.g. "point array"; the first finding only: `error` already set is
// kept).
vtkDataArray* Find(
  vtkFieldData* data, const Expected& expected, const char* role, bool required, std::string& error);
} // namespace vtkOpalInputArrays
