#include "vtkOpalRankAgreement.h"

#include "vtkCommunicator.h"
#include "vtkMultiProcessController.h"

#include <algorithm>
#include <cstdlib>
#include <sstream>

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

std::vector<RankView> Gather(vtkMultiProcessController* given, const RankView& mine)
{
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    return { mine };
  }
  const std::string bytes = encode(mine);
  const int ranks = controller->GetNumberOfProcesses();
  std::vector<vtkIdType> lengths(ranks), offsets(ranks);
  const vtkIdType length = static_cast<vtkIdType>(bytes.size());
  controller->AllGather(&length, lengths.data(), 1);
  vtkIdType total = 0;
  for (int r = 0; r < ranks; ++r)
  {
    offsets[r] = total;
    total += lengths[r];
  }
  std::vector<char> received(static_cast<std::size_t>(total));
  controller->AllGatherV(bytes.data(), received.data(), length, lengths.data(), offsets.data());
  std::vector<RankView> views;
  for (int r = 0; r < ranks; ++r)
  {
    views.push_back(decode(received.data() + offsets[r]));
  }
  return views;
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

bool AnyRank(vtkMultiProcessController* given, bool mine)
{
  vtkMultiProcessController* controller = ranksController(given);
  if (!controller)
  {
    return mine;
  }
  const int local = mine ? 1 : 0;
  int any = 0;
  controller->AllReduce(&local, &any, 1, vtkCommunicator::MAX_OP);
  return any != 0;
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
