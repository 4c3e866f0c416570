// Numbers as every flag takes them: the whole word in decimal (std::from_chars:
// no leading space or '+', no "0x"), and a whole number as digits only, within
// its range. CLI11 alone reads "010" as 8 and "0x10" as 16, lets " 5" and "+5"
// through, and refuses a whole number too large for an int naming the int's
// range, not the parameter's.
#pragma once

#include <CLI/CLI.hpp>

#include <string>

namespace opalcli
{
// A flag's value (each of its values) as a number named `name`: refused
// unless it is a decimal number and, if `whole`, digits only (an optional
// '-') in [min, max] (as validate says it: opal::rowRangeError), else finite
// (its range is validate's). A whole number goes on to CLI11 in canonical
// form ("010" as 10). Give it to CLI::Option::transform.
CLI::Validator numberCheck(const std::string& name, double min, double max, bool whole);
}
