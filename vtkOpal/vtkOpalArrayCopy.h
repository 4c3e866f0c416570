// Copies between the VTK classes' members (C arrays, int for enumerations)
// and the plain parameter structs' (std::arrays, enumerations), and prints a
// member as PrintSelf does: the thin VTK layer over the Opal* science, looped
// over the parameter tables (vtkOpalTableMacros.h).
#pragma once

#include "vtkIndent.h"

#include <algorithm>
#include <array>
#include <cstddef>
#include <ostream>
#include <type_traits>

namespace vtkOpalArrayCopy
{
// One value: an enumeration to or from its int, a number or a boolean as is.
template <typename To, typename From>
std::enable_if_t<std::is_arithmetic_v<From> || std::is_enum_v<From>> assign(To& to, const From& from)
{
  to = static_cast<To>(from);
}

template <typename T, std::size_t N>
void assign(std::array<T, N>& to, const T (&from)[N])
{
  std::copy(from, from + N, to.begin());
}

template <typename T, std::size_t N>
void assign(T (&to)[N], const std::array<T, N>& from)
{
  std::copy(from.begin(), from.end(), to);
}

// "  Name: v0 v1 ...", the line TestOpalXmlDefaults reads.
template <typename T>
void print(std::ostream& os, vtkIndent indent, const char* name, const T& value)
{
  os << indent << name << ": " << value << "\n";
}

template <typename T, std::size_t N>
void print(std::ostream& os, vtkIndent indent, const char* name, const T (&values)[N])
{
  os << indent << name << ":";
  for (const T& value : values)
  {
    os << " " << value;
  }
  os << "\n";
}
} // namespace vtkOpalArrayCopy
