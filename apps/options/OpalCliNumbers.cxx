#include "OpalCliNumbers.h"

#include "OpalParameterRow.h"

#include <charconv>
#include <system_error>

namespace opalcli
{
namespace
{
bool digitsOnly(const std::string& word)
{
  const std::size_t first = word.rfind('-', 0) == 0 ? 1 : 0;
  return word.size() > first && word.find_first_not_of("0123456789", first) == std::string::npos;
}

// Empty if `word` is a number as the flag takes it; the sentence refusing it otherwise.
std::string refusal(const std::string& name, std::string& word, double min, double max, bool whole)
{
  double value = 0;
  const char* last = word.data() + word.size();
  const auto [stop, error] = std::from_chars(word.data(), last, value);
  if (word.empty() || stop != last || (whole && !digitsOnly(word)) ||
    (error != std::errc() && error != std::errc::result_out_of_range))
  {
    return name + " must be " + (whole ? "a whole number" : "a number") + " in decimal, got \"" + word + "\".";
  }
  if (error == std::errc::result_out_of_range)
  {
    return name + " is beyond what a double holds, got " + word + ".";
  }
  std::string outside = whole ? opal::rowRangeError(name.c_str(), { value }, min, max, "")
                              : opal::rowRangeError(name.c_str(), { value }, -opal::Unbounded, opal::Unbounded, "");
  if (outside.empty() && whole)
  {
    word = std::to_string(static_cast<long long>(value)); // CLI11 reads "010" as octal
  }
  return outside;
}
} // namespace

CLI::Validator numberCheck(const std::string& name, double min, double max, bool whole)
{
  return CLI::Validator(
    [name, min, max, whole](std::string& word) { return refusal(name, word, min, max, whole); }, "");
}
} // namespace opalcli
