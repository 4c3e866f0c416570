// The processes' exchange played by sessions on threads of one test
// (docs/design.md §8.1): what vtkOpalRankShares does over MPI.
#pragma once

#include "OpalRenderSession.h"

#include <algorithm>
#include <condition_variable>
#include <cstdint>
#include <cstdio>
#include <cstring>
#include <exception>
#include <mutex>
#include <optional>
#include <thread>
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
      // A round hands on the rounds' bytes; a stopping share's last bytes
      // reach only the last exchanges, as over MPI (vtkOpalRankShares).
      for (std::size_t first = 0; post.Bytes && (goesOn || (post.Last && last)) && first < post.Bytes->size();
           first += 1000)
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

  // An every-order solve's scores (RenderSession::ScoresExchange) through
  // its last exchange: every share's in share order, nullopt where one stopped.
  std::optional<std::vector<std::vector<double>>> meetScores(int share, const std::optional<std::vector<double>>& mine)
  {
    std::optional<std::vector<char>> bytes;
    if (mine)
    {
      bytes.emplace(mine->size() * sizeof(double));
      std::memcpy(bytes->data(), mine->data(), bytes->size());
    }
    std::vector<std::vector<char>> arrived(this->Posts.size());
    const bool whole = this->meet(share, true, bytes, [&arrived](int from, std::uint64_t first, std::uint64_t count, const char* b) {
      std::vector<char>& into = arrived[static_cast<std::size_t>(from)];
      into.resize(std::max<std::size_t>(into.size(), first + count));
      std::memcpy(into.data() + first, b, count);
    });
    if (!whole)
    {
      return std::nullopt;
    }
    std::vector<std::vector<double>> scores;
    for (const std::vector<char>& from : arrived)
    {
      scores.emplace_back(from.size() / sizeof(double));
      std::memcpy(scores.back().data(), from.data(), from.size());
    }
    return scores;
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
// The sessions solve every order's scattered light for `frame` together, one
// share each on threads of their own (RenderSession::solveScatteredLightShared:
// each reads back its slab of the medium, and the slabs go to every share);
// the first reports to `progress`. Whether each holds the field (false where
// its share threw, said on stderr).
inline std::vector<bool> solveTogether(
  const std::vector<opal::RenderSession*>& sessions, const opal::ResolvedFrame& frame, const opal::RenderProgress& progress)
{
  const int shares = static_cast<int>(sessions.size());
  Meeting meeting(shares);
  std::vector<char> solved(sessions.size(), 0);
  std::vector<std::thread> threads;
  for (int share = 0; share < shares; ++share)
  {
    threads.emplace_back([&, share] {
      try
      {
        solved[static_cast<std::size_t>(share)] = sessions[static_cast<std::size_t>(share)]->solveScatteredLightShared(
          frame, share, shares,
          [&meeting, share](const std::optional<std::vector<double>>& mine) { return meeting.meetScores(share, mine); },
          [&meeting, share](const std::vector<char>& mine, const opal::RenderSession::ShareSink& sink) {
            return meeting.meet(share, false, mine, sink);
          },
          share == 0 ? progress : nullptr);
      }
      catch (const std::exception& e)
      {
        std::fprintf(stderr, "share %d of the solve failed: %s\n", share, e.what());
      }
      catch (...)
      {
        std::fprintf(stderr, "share %d of the solve failed\n", share);
      }
    });
  }
  for (std::thread& thread : threads)
  {
    thread.join();
  }
  return { solved.begin(), solved.end() };
}
} // namespace opaltest
