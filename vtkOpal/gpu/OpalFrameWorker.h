// One frame rendered on a thread of its own (docs/design.md §5.2): the
// render session's background frame. The worker runs the render it is given
// with a progress callback that records the fraction done and stops the frame
// at its next check (between light-pass slabs or march tiles) once cancel()
// is asked. Plain C++: no VTK, no Vulkan here.
#pragma once

#include <atomic>
#include <exception>
#include <functional>
#include <thread>

namespace opal
{


template <typename Frame>
class FrameWorker
{
public:
  using Progress = std::function<bool(double)>;

  // Starts `render` on the worker thread.
  explicit FrameWorker(std::function<Frame(const Progress&)> render)
    : Worker([this, render = std::move(render)]() { this->run(render); })
  {
  }
  ~FrameWorker() { this->cancel(); }
  FrameWorker(const FrameWorker&) = delete;
  FrameWorker& operator=(const FrameWorker&) = delete;

  bool finished() const { return this->Finished.load(); }
  double progress() const { return this->Fraction.load(); }

  // Asks the frame to stop and waits for the worker to end.
  void cancel()
  {
    this->Cancel.store(true);
    this->join();
  }

  // Waits for the worker to end; the frame it rendered, or its exception rethrown.
  Frame take()
  {
    this->join();
    if (this->Error)
    {
      std::rethrow_exception(this->Error);
    }
    return std::move(this->Result);
  }

  // After the worker ended: whether it ended by an exception.
  bool failed() const { return static_cast<bool>(this->Error); }
  const Frame& frame() const { return this->Result; }

private:
  void run(const std::function<Frame(const Progress&)>& render)
  {
    try
    {
      this->Result = render([this](double fraction) {
        this->Fraction.store(fraction);
        return !this->Cancel.load();
      });
    }
    catch (...)
    {
      this->Error = std::current_exception();
    }
    this->Finished.store(true);
  }

  void join()
  {
    if (this->Worker.joinable())
    {
      this->Worker.join();
    }
  }

  // Written by the worker before Finished; read by the caller after join().
  Frame Result{};
  std::exception_ptr Error;
  std::atomic<bool> Cancel{ false };
  std::atomic<bool> Finished{ false };
  std::atomic<double> Fraction{ 0.0 };
  std::thread Worker; // last: started once the state above exists
};

} // namespace opal
