// What parameter checks and their messages share: checks run in order to the
// first error, numbers printed with enough digits to tell a value from the
// bound it passed (0.7400001 is refused as 0.7400001, not as "0.74"), and the
// one rule for the refractive index of the volume and the render.
#pragma once

#include <initializer_list>
#include <sstream>
#include <string>

namespace opal
{

// The first error the checks find in the parameters, in order; empty if none.
template <typename Parameters>
std::string firstError(const Parameters& p, std::initializer_list<std::string (*)(const Parameters&)> checks)
{
  for (auto check : checks)
  {
    std::string error = check(p);
    if (!error.empty())
    {
      return error;
    }
  }
  return {};
}

// A stream for an error message: 10 significant digits.
inline std::ostringstream messageStream()
{
  std::ostringstream stream;
  stream.precision(10);
  return stream;
}

// The refractive index the model and the render accept: [1, 4) (1: an
// index-matched boundary; opals are about 1.45, the densest glasses below 2).
// Empty if accepted, else the sentence saying so.
inline std::string refractiveIndexError(double mu)
{
  if (mu >= 1 && mu < 4)
  {
    return {};
  }
  std::ostringstream message = messageStream();
  message << "RefractiveIndex must lie in [1, 4) (1: an index-matched boundary), got " << mu << ".";
  return message.str();
}

} // namespace opal
