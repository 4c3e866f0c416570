// The processes' exchange played by sessions on threads of one test
// (docs/design.md §8.1): what vtkOpalRankShares does over MPI.
#pragma once

#include "OpalRenderSession.h"

#include <algorithm>
#include <condition_variable>
#include <mutex>
#include <optional>
#include <vector>

namespace opaltest
{
// The processes' exchange: in each round every share posts its bytes (a
// layer's edge rows, or its last: nullopt where it stopped) and, once all
// have, is handed the others' in pieces of 1000 bytes, a size that is no
// multiple of any record's. A round goes on where every share posted a
// layer's; the last is whole where every share posted its bytes.
class Meeting
{
public:
  explicit Meeting(int shares) : Posts(static_cast<std::size_t>(shares)) {}

  bool meet(int share, bool last, const std::optional<std::vector<char>>& bytes, const opal::RenderSession::ShareSink& sink)
  {
    std::unique_lock<std::mutex> lock(this->Mutex);
    this->Changed.wait(lock, [&] { return !this->Reading; }); // the round before fully read
    this->Posts[static_cast<std::size_t>(share)] = { last, bytes };
    if (++this->Arrived == static_cast<int>(this->Posts.size()))
    {
      this->Reading = true;
      this->Changed.notify_all();
    }
    this->Changed.wait(lock, [&] { return this->Reading; });
    const bool goesOn = std::none_of(this->Posts.begin(), this->Posts.end(), [](const Post& p) { return p.Last; });
    const bool whole =
      std::all_of(this->Posts.begin(), this->Posts.end(), [](const Post& p) { return p.Last && p.Bytes; });
    for (std::size_t from = 0; from < this->Posts.size(); ++from)
    {
      const Post& post = this->Posts[from];
      for (std::size_t first = 0; post.Bytes && (goesOn || post.Last) && first < post.Bytes->size(); first += 1000)
      {
        sink(static_cast<int>(from), first, std::min<std::size_t>(1000, post.Bytes->size() - first),
          post.Bytes->data() + first);
      }
    }
    if (++this->Left == static_cast<int>(this->Posts.size()))
    {
      this->Arrived = this->Left = 0;
      this->Reading = false;
      this->Changed.notify_all();
    }
    return last ? whole : goesOn;
  }

private:
  struct Post
  {
    bool Last = false;
    std::optional<std::vector<char>> Bytes;
  };
  std::mutex Mutex;
  std::condition_variable Changed;
  std::vector<Post> Posts;
  int Arrived = 0, Left = 0;
  bool Reading = false;
};
} // namespace opaltest
