// The render parameters' table (OPAL_RENDER_PARAMETERS) reaches every layer,
// row by row, with a value other than the default:
//  - its CLI flag sets that row's member and no other (an enumeration by name);
//  - the VTK filter's members hold it (SetRenderParameters and back) and
//    PrintSelf prints it under the row's name;
//  - validate refuses a value beyond the row's range with a message naming it.
// TestOpalParameterTable.py holds the ParaView XML to the same table.
#include "OpalRenderOptions.h"
#include "OpalRenderParameters.h"
#include "OpalTestHarness.h"
#include "vtkOpalSpectralRender.h"

#include "vtkNew.h"

#include <sstream>
#include <string>
#include <vector>

namespace
{
using Row = opal::ParameterRow<opal::RenderParameters>;

// A value in the row's range that differs from its default in every component.
std::vector<double> otherValue(const Row& row)
{
  std::vector<double> values = row.Get(opal::RenderParameters());
  for (double& v : values)
  {
    const double lower = row.Min == -opal::Unbounded ? -2 : row.Min;
    const double upper = row.Max == opal::Unbounded ? lower + 2 : row.Max;
    v = v == upper ? lower : upper;
  }
  return values;
}

// The flag's words: a name for an enumeration, the flag alone for a switch.
std::vector<std::string> flagArguments(const Row& row, const std::vector<double>& values)
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

void checkFlag(const Row& row, const std::vector<double>& values)
{
  CLI::App app;
  OpalRenderOptions options;
  options.addTo(app);
  const std::vector<std::string> words = flagArguments(row, values);
  app.parse(std::vector<std::string>(words.rbegin(), words.rend())); // CLI11 pops from the back
  const opal::RenderParameters parsed = options.parameters("custom", opal::RenderParameters().RefractiveIndex);
  OPAL_CHECK(row.Get(parsed) == values, std::string(row.Flag) + " sets " + row.Name);
  for (const Row& other : opal::renderParameterRows())
  {
    OPAL_CHECK(&other == &row || other.Get(parsed) == other.Get(opal::RenderParameters()),
      std::string(row.Flag) + " leaves " + other.Name + " as it was");
  }
}

void checkFilter(const Row& row, const std::vector<double>& values)
{
  opal::RenderParameters p;
  row.Set(p, values);
  vtkNew<vtkOpalSpectralRender> render;
  render->SetRenderParameters(p);
  OPAL_CHECK(row.Get(render->GetRenderParameters()) == values, std::string("the filter holds ") + row.Name);
  std::ostringstream printed;
  render->Print(printed);
  std::ostringstream line;
  line << "  " << row.Name << ":";
  for (const double v : values)
  {
    line << " " << v;
  }
  line << "\n";
  OPAL_CHECK(printed.str().find(line.str()) != std::string::npos, "PrintSelf prints " + line.str());
}

void checkRange(const Row& row)
{
  if (row.Type == opal::ParameterType::Bool)
  {
    return;
  }
  for (const double beyond : { row.Min == -opal::Unbounded ? -HUGE_VAL : row.Min - 1,
         row.Max == opal::Unbounded ? HUGE_VAL : row.Max + 1 })
  {
    opal::RenderParameters p;
    std::vector<double> values = row.Get(p);
    values.back() = beyond;
    row.Set(p, values);
    if (row.Get(p).back() != beyond)
    {
      continue; // an int member cannot hold infinity
    }
    const std::string error = opal::validate(p);
    OPAL_CHECK(error.find(row.Name) != std::string::npos,
      std::string(row.Name) + " beyond its range is refused naming it (got: " + error + ")");
  }
}
} // namespace

int TestOpalParameterTable(int, char*[])
{
  OPAL_CHECK(opal::renderParameterRows().size() >= 29, "the table has every render parameter");
  for (const Row& row : opal::renderParameterRows())
  {
    const std::vector<double> values = otherValue(row);
    OPAL_CHECK(values != row.Get(opal::RenderParameters()), std::string("a value other than the default for ") + row.Name);
    if (*row.Flag != '\0')
    {
      checkFlag(row, values);
    }
    checkFilter(row, values);
    checkRange(row);
  }
  return opaltest::finish("TestOpalParameterTable");
}
