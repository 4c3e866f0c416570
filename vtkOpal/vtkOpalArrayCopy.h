// Copies between the VTK classes' C-array members and the plain parameter
// structs' std::arrays (the thin VTK layer over the Opal* science).
#pragma once

#include <algorithm>
#include <array>
#include <cstddef>

namespace vtkOpalArrayCopy
{
template <typename T, std::size_t N>
void copy(const std::array<T, N>& from, T* to)
{
  std::copy(from.begin(), from.end(), to);
}

template <typename T, std::size_t N>
void copy(const T* from, std::array<T, N>& to)
{
  std::copy(from, from + N, to.begin());
}
} // namespace vtkOpalArrayCopy
