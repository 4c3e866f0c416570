// The parameter tables (OPAL_RENDER_PARAMETERS, OPAL_MODEL_PARAMETERS) reach
// every layer, row by row, with a value other than the default:
//  - its CLI flag sets that row's member and no other (an enumeration by name);
//  - the VTK class's members hold it (vtkOpalSpectralRender, vtkOpalSource:
//    the struct in and back) and PrintSelf prints it under the row's name;
//  - the volume's field data records a model row and reads it back;
//  - validate refuses a value beyond the row's range with a message naming it.
// TestOpalParameterTable.py holds the ParaView XML to the same tables.
#include "OpalModelOptions.h"
#include "OpalModelParameters.h"
#include "OpalPresets.h"
#include "OpalRenderOptions.h"
#include "OpalRenderParameters.h"
#include "OpalTestHarness.h"
#include "vtkOpalFieldData.h"
#include "vtkOpalSource.h"
#include "vtkOpalSpectralRender.h"

#include "vtkImageData.h"
#include "vtkNew.h"

#include <climits>
#include <cmath>
#include <sstream>
#include <string>
#include <vector>

namespace
{
// A value in the row's range (and an int's) that differs from its default in every component.
template <typename Parameters>
std::vector<double> otherValue(const opal::ParameterRow<Parameters>& row)
{
  std::vector<double> values = row.Get(Parameters());
  for (double& v : values)
  {
    const double lower = row.Min == -opal::Unbounded ? -2 : row.Min;
    double upper = row.Max == opal::Unbounded ? lower + 2 : row.Max;
    upper = row.Type == opal::ParameterType::Double ? upper : std::min(upper, double(INT_MAX));
    v = v == upper ? lower : upper;
  }
  return values;
}

// The flag's words: a name for an enumeration, the flag alone for a switch.
template <typename Parameters>
std::vector<std::string> flagArguments(const opal::ParameterRow<Parameters>& row, const std::vector<double>& values)
{
  std::vector<std::string> words{ row.Flag };
  const std::vector<std::string> names = opal::choicesOf(row.Choices);
  for (const double v : values)
  {
    if (row.Type == opal::ParameterType::Bool)
    {
      break;
    }
    std::ostringstream word;
    word.precision(17);
    word << v;
    words.push_back(names.empty() ? word.str() : names.at(static_cast<std::size_t>(v)));
  }
  return words;
}

// The parameters opal-render's flags give (the custom preset: no preset's values).
opal::RenderParameters parsed(OpalRenderOptions& options, const opal::RenderParameters*)
{
  return options.parameters("custom", opal::RenderParameters().RefractiveIndex);
}

opal::ModelParameters parsed(OpalModelOptions& options, const opal::ModelParameters*)
{
  return options.parameters();
}

// The parameters opal-render or opal-volume takes from these words.
template <typename Options, typename Parameters>
Parameters parsedWords(std::vector<std::string> words)
{
  CLI::App app;
  Options options;
  options.addTo(app);
  app.allow_extras(); // the other program's flags (--preset for the render's rows)
  words.insert(words.end(), { "--preset", "custom" });
  app.parse(std::vector<std::string>(words.rbegin(), words.rend())); // CLI11 pops from the back
  return parsed(options, static_cast<const Parameters*>(nullptr));
}

// A row's flag sets it and leaves every other row as no flag leaves it (the
// custom volume's: ScatteringOrders all, the struct's single).
template <typename Options, typename Parameters>
void checkFlag(const opal::ParameterRow<Parameters>& row, const std::vector<double>& values,
  const std::vector<opal::ParameterRow<Parameters>>& rows)
{
  const Parameters result = parsedWords<Options, Parameters>(flagArguments(row, values));
  const Parameters unflagged = parsedWords<Options, Parameters>({});
  OPAL_CHECK(row.Get(result) == values, std::string(row.Flag) + " sets " + row.Name);
  for (const opal::ParameterRow<Parameters>& other : rows)
  {
    OPAL_CHECK(&other == &row || other.Get(result) == other.Get(unflagged),
      std::string(row.Flag) + " leaves " + other.Name + " as it was");
  }
}

// The VTK class holds the row's value and prints it under the row's name.
template <typename Filter, typename Parameters>
void checkVtkClass(const opal::ParameterRow<Parameters>& row, const std::vector<double>& values,
  Parameters (Filter::*get)() const, void (Filter::*set)(const Parameters&))
{
  Parameters p;
  row.Set(p, values);
  vtkNew<Filter> filter;
  (filter.Get()->*set)(p);
  OPAL_CHECK(row.Get((filter.Get()->*get)()) == values, std::string("the VTK class holds ") + row.Name);
  std::ostringstream printed, line;
  filter->Print(printed);
  line << "  " << row.Name << ":";
  for (const double v : values)
  {
    line << " ";
    if (row.Type == opal::ParameterType::Double)
    {
      line << v;
    }
    else
    {
      line << static_cast<long long>(v);
    }
  }
  line << "\n";
  OPAL_CHECK(printed.str().find(line.str()) != std::string::npos, "PrintSelf prints " + line.str());
}

void checkFieldData(const opal::ParameterRow<opal::ModelParameters>& row, const std::vector<double>& values)
{
  opal::ModelParameters p;
  row.Set(p, values);
  vtkNew<vtkImageData> volume;
  vtkOpalFieldData::AddModelParameters(volume, p, opal::CustomPreset, 0);
  const opal::ModelParameters read = vtkOpalFieldData::ReadModelParameters(volume->GetFieldData());
  OPAL_CHECK(row.Get(read) == values, std::string("the field data records and gives back ") + row.Name);
}

template <typename Parameters>
void checkRange(const opal::ParameterRow<Parameters>& row)
{
  if (row.Type == opal::ParameterType::Bool)
  {
    return;
  }
  // Just past a bound: the next double (1e30 + 1 is 1e30), the next whole number for an int.
  const auto past = [&row](double bound, double direction) {
    return row.Type == opal::ParameterType::Double ? std::nextafter(bound, direction * HUGE_VAL) : bound + direction;
  };
  for (const double beyond : { row.Min == -opal::Unbounded ? -HUGE_VAL : past(row.Min, -1),
         row.Max == opal::Unbounded ? HUGE_VAL : past(row.Max, 1) })
  {
    Parameters p;
    std::vector<double> values = row.Get(p);
    values.back() = beyond;
    row.Set(p, values);
    if (row.Get(p).back() != beyond)
    {
      continue; // an int member cannot hold infinity, an unsigned one -1
    }
    const std::string error = opal::validate(p);
    OPAL_CHECK(error.find(row.Name) != std::string::npos,
      std::string(row.Name) + " beyond its range is refused naming it (got: " + error + ")");
  }
}
} // namespace

int TestOpalParameterTable(int, char*[])
{
  const auto& renderRows = opal::renderParameterRows();
  const auto& modelRows = opal::modelParameterRows();
  OPAL_CHECK(renderRows.size() >= 29 && modelRows.size() >= 27, "the tables have every parameter");
  for (const auto& row : renderRows)
  {
    const std::vector<double> values = otherValue(row);
    if (*row.Flag != '\0')
    {
      checkFlag<OpalRenderOptions>(row, values, renderRows);
    }
    checkVtkClass(row, values, &vtkOpalSpectralRender::GetRenderParameters, &vtkOpalSpectralRender::SetRenderParameters);
    checkRange(row);
  }
  for (const auto& row : modelRows)
  {
    const std::vector<double> values = otherValue(row);
    if (*row.Flag != '\0')
    {
      checkFlag<OpalModelOptions>(row, values, modelRows);
    }
    checkVtkClass(row, values, &vtkOpalSource::GetModelParameters, &vtkOpalSource::SetModelParameters);
    checkFieldData(row, values);
    checkRange(row);
  }
  return opaltest::finish("TestOpalParameterTable");
}
