#include "vtkOpalRankAgreement.h"

#include "vtkOpalRankWait.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <charconv>
#include <cstdlib>
#include <numeric>
#include <sstream>
#include <stdexcept>

namespace vtkOpalRankAgreement
{
namespace
{
vtkMultiProcessController* ranksController(vtkMultiProcessController* controller)
{
  return controller && controller->GetNumberOfProcesses() > 1 ? controller : nullptr;
}

// A view as bytes: the code, then the message and the settings, each ended by a NUL.
std::string encode(const RankView& view)
{
  return std::to_string(view.Code) + '\0' + view.Message + '\0' + view.Settings + '\0';
}

RankView decode(const char* bytes)
{
  RankView view;
  view.Code = std::atoi(bytes);
  bytes += std::char_traits<char>::length(bytes) + 1;
  view.Message = bytes;
  bytes += view.Message.size() + 1;
  view.Settings = bytes;
  return view;
}

std::vector<std::string> lines(const std::string& text)
{
  std::vector<std::string> result;
  std::istringstream in(text);
  for (std::string line; std::getline(in, line);)
  {
    result.push_back(line);
  }
  return result;
}
} // namespace

int Rank(vtkMultiProcessController* controller)
{
  return ranksController(controller) ? controller->GetLocalProcessId() : 0;
}

int Ranks(vtkMultiProcessController* controller)
{
  return ranksController(controller) ? controller->GetNumberOfProcesses() : 1;
}

std::vector<vtkIdType> GatherLengths(vtkMultiProcessController* controller, vtkIdType mine)
{
  std::vector<vtkIdType> lengths(static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  const vtkOpalRankWait::Bounded bounded(controller);
  if (!controller->AllGather(&mine, lengths.data(), 1))
  {
    throw std::runtime_error("The ranks could not exchange their lengths.");
  }
  return lengths;
}

bool GatherBytes(vtkMultiProcessController* controller, const char* mine, const std::vector<vtkIdType>& lengths,
  std::vector<char>& bytes, vtkIdType roundBytes)
{
  const std::vector<vtkIdType> offsets = RankOffsets(lengths);
  bytes.resize(static_cast<std::size_t>(offsets.back() + lengths.back()));
  return GatherBytesTo(
    controller, mine, lengths,
    [&](int rank, vtkIdType first, vtkIdType count, const char* data) {
      std::copy_n(data, count, bytes.data() + offsets[rank] + first);
    },
    roundBytes);
}

bool GatherBytesTo(vtkMultiProcessController* controller, const char* mine, const std::vector<vtkIdType>& lengths,
  const ByteSink& sink, vtkIdType roundBytes, int destination)
{
  const bool receives = destination < 0 || destination == controller->GetLocalProcessId();
  const int ranks = controller->GetNumberOfProcesses();
  const vtkIdType longest = *std::max_element(lengths.begin(), lengths.end());
  // The window holds a round of every rank: no larger than the longest bytes need.
  const vtkIdType round =
    std::max<vtkIdType>(1, std::min<vtkIdType>({ roundBytes, (VTK_INT_MAX - 1) / ranks, longest }));
  std::vector<char> window(receives ? static_cast<std::size_t>(round * ranks) : 0);
  const vtkIdType mineLength = lengths[controller->GetLocalProcessId()];
  for (vtkIdType start = 0; start < longest; start += round)
  {
    std::vector<vtkIdType> counts(ranks), places(ranks);
    for (int r = 0; r < ranks; ++r)
    {
      counts[r] = std::clamp<vtkIdType>(lengths[r] - start, 0, round);
      places[r] = r * round;
    }
    const vtkIdType count = std::clamp<vtkIdType>(mineLength - start, 0, round);
    const char* sent = count > 0 ? mine + start : mine;
    const vtkOpalRankWait::Bounded bounded(controller);
    if (!(destination < 0 ? controller->AllGatherV(sent, window.data(), count, counts.data(), places.data())
                          : controller->GatherV(sent, window.data(), count, counts.data(), places.data(), destination)))
    {
      return false;
    }
    for (int r = 0; r < ranks && receives; ++r)
    {
      if (counts[r] > 0)
      {
        sink(r, start, counts[r], window.data() + places[r]);
      }
    }
  }
  return true;
}

std::vector<vtkIdType> RankOffsets(const std::vector<vtkIdType>& lengths)
{
  std::vector<vtkIdType> offsets(lengths.size(), 0);
  if (!lengths.empty())
  {
    std::partial_sum(lengths.begin(), lengths.end() - 1, offsets.begin() + 1);
  }
  return offsets;
}

std::vector<RankView> Gather(vtkMultiProcessController* given, const RankView& mine)
{
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    return { mine };
  }
  const std::string bytes = encode(mine);
  const std::vector<vtkIdType> lengths = GatherLengths(controller, static_cast<vtkIdType>(bytes.size()));
  std::vector<char> received;
  if (!GatherBytes(controller, bytes.data(), lengths, received))
  {
    throw std::runtime_error("The ranks could not exchange their views of the render.");
  }
  std::vector<RankView> views;
  for (const vtkIdType offset : RankOffsets(lengths))
  {
    views.push_back(decode(received.data() + offset));
  }
  return views;
}

std::string SettingsLine(const char* name, const std::vector<double>& values)
{
  std::string line = name;
  for (const double value : values)
  {
    char number[32];
    line += " " + std::string(number, std::to_chars(number, number + sizeof(number), value).ptr);
  }
  return line + "\n";
}

std::string SettingsDisagreement(const std::vector<RankView>& views)
{
  const std::vector<std::string> first = lines(views.front().Settings);
  for (std::size_t r = 1; r < views.size(); ++r)
  {
    const std::vector<std::string> other = lines(views[r].Settings);
    for (std::size_t i = 0; i < std::max(first.size(), other.size()); ++i)
    {
      const std::string a = i < first.size() ? first[i] : "(none)";
      const std::string b = i < other.size() ? other[i] : "(none)";
      if (a != b)
      {
        return "Rank " + std::to_string(r) + " of " + std::to_string(views.size()) + " renders with " + b +
          ", rank 0 with " + a.substr(a.find(' ') + 1) +
          ": every rank of one render must have the same settings; no rank renders.";
      }
    }
  }
  return {};
}

bool AnyRank(vtkMultiProcessController* controller, bool mine)
{
  return MostOverRanks(controller, mine ? 1 : 0) != 0;
}

int MostOverRanks(vtkMultiProcessController* given, int mine)
{
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    return mine;
  }
  int most = mine;
  const vtkOpalRankWait::Bounded bounded(controller);
  controller->AllReduce(&mine, &most, 1, vtkCommunicator::MAX_OP);
  return most;
}

std::vector<int> GatherInts(vtkMultiProcessController* controller, const int* mine, int count, const char* what)
{
  std::vector<int> all(static_cast<std::size_t>(count) * static_cast<std::size_t>(controller->GetNumberOfProcesses()));
  const vtkOpalRankWait::Bounded bounded(controller);
  if (!controller->AllGather(mine, all.data(), count))
  {
    throw std::runtime_error(std::string("The ranks could not exchange ") + what + ".");
  }
  return all;
}

int FirstWith(const std::vector<RankView>& views, int code)
{
  for (std::size_t r = 0; r < views.size(); ++r)
  {
    if (views[r].Code == code)
    {
      return static_cast<int>(r);
    }
  }
  return -1;
}
} // namespace vtkOpalRankAgreement
