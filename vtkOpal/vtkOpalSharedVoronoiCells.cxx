#include "vtkOpalSharedVoronoiCells.h"

#include "OpalModelParameters.h"
#include "OpalParallel.h"
#include "vtkOpalRankAgreement.h"

#include <algorithm>
#include <cstdint>
#include <exception>
#include <string>
#include <vector>

namespace vtkOpalSharedVoronoiCells
{
namespace
{
// Share `share` of `shares` assigns its layers z = floor(s nz / N) to
// floor((s + 1) nz / N) and sends their runs; the grid's runs are every
// share's stacked in order (empty where a share stopped). `exchanged` is set
// before the exchange, so that a throw after it does not exchange again.
opal::VoronoiCellRuns assignShare(const opal::DomainLayout::LayerCells& layers, int nz, int share, int shares,
  const vtkOpalRankShares::Exchanger& exchange, bool& exchanged)
{
  const std::pair<int, int> shareLayers = opal::evenShare(nz, share, shares);
  const opal::VoronoiCellRuns mine = layers(shareLayers.first, shareLayers.second);
  std::optional<std::vector<char>> bytes;
  if (!mine.empty())
  {
    bytes = mine.bytes();
  }
  std::vector<std::vector<char>> received(static_cast<std::size_t>(shares));
  std::exception_ptr failure; // a throw inside the sink would leave the ranks' exchange midway
  exchanged = true;
  const vtkOpalRankShares::Outcome outcome =
    exchange(bytes, [&](int from, std::uint64_t first, std::uint64_t count, const char* data) {
      try
      {
        std::vector<char>& part = received[static_cast<std::size_t>(from)];
        part.resize(std::max<std::size_t>(part.size(), first + count));
        std::copy_n(data, count, part.data() + first);
      }
      catch (...)
      {
        failure = failure ? failure : std::current_exception();
      }
    });
  if (failure)
  {
    std::rethrow_exception(failure);
  }
  if (!outcome.Complete)
  {
    return {};
  }
  std::vector<opal::VoronoiCellRuns> parts;
  for (std::vector<char>& part : received)
  {
    parts.push_back(opal::VoronoiCellRuns::fromBytes(part));
    std::vector<char>().swap(part); // each share's bytes gone once read: the runs are held twice at most
  }
  return opal::VoronoiCellRuns::stacked(parts);
}
} // namespace

std::string SettingsOf(const opal::ModelParameters& parameters)
{
  std::string text;
  for (const auto& row : opal::modelParameterRows())
  {
    text += vtkOpalRankAgreement::SettingsLine(row.Name, row.Get(parameters));
  }
  return text;
}

vtkOpalRankShares::Result Build(vtkMultiProcessController* controller, bool failed,
  const opal::ModelParameters& parameters, const std::function<bool(double)>& progress,
  const std::function<bool()>& aborted, std::optional<opal::DomainLayout>& layout)
{
  return vtkOpalRankShares::Share(
    controller, failed, [] { return true; },
    [&] { return SettingsOf(parameters); }, aborted,
    "the Voronoi cells' shares", [&](int share, int shares, const vtkOpalRankShares::Exchanger& exchange) {
      bool exchanged = false;
      const auto stop = [&] { // the others wait for this share's last exchange
        if (!exchanged)
        {
          exchange(std::nullopt, [](int, std::uint64_t, std::uint64_t, const char*) {});
        }
      };
      try
      {
        opal::DomainLayout built =
          opal::DomainLayout::build(parameters, progress, [&](const opal::DomainLayout::LayerCells& layers) {
            return assignShare(layers, parameters.Dimensions[2], share, shares, exchange, exchanged);
          });
        stop();
        if (built.aborted())
        {
          return false;
        }
        layout = std::move(built);
        return true;
      }
      catch (...)
      {
        stop();
        throw;
      }
    });
}
} // namespace vtkOpalSharedVoronoiCells
