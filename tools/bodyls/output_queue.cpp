#include "output_queue.h"

#include <unistd.h>

#include <cerrno>
#include <chrono>
#include <condition_variable>
#include <deque>
#include <mutex>
#include <thread>

namespace bodyfmt::lsp {

struct OutputQueue::State {
  int fd = -1;
  std::mutex mutex;
  std::condition_variable changed;
  std::deque<std::string> queue;
  std::size_t pending = 0;
  int error = 0;
  bool stopping = false;

  void write_loop() {
    std::unique_lock<std::mutex> lock(mutex);
    for (;;) {
      changed.wait(lock, [&] { return stopping || !queue.empty(); });
      if (queue.empty()) return;  // stopping, with nothing left to write
      // The front stays queued (and counted) while it is written: pending is what the client
      // has not been given yet.
      const std::string& bytes = queue.front();
      lock.unlock();
      int failed = 0;
      for (std::size_t done = 0; done < bytes.size();) {
        const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
        if (n < 0 && errno == EINTR) continue;
        if (n <= 0) {
          failed = n < 0 ? errno : EIO;
          break;
        }
        done += static_cast<std::size_t>(n);
      }
      lock.lock();
      pending -= bytes.size();
      queue.pop_front();
      if (failed) {
        error = failed;
        queue.clear();
        pending = 0;
      }
      changed.notify_all();
      if (failed) return;
    }
  }
};

OutputQueue::OutputQueue(int fd) : state_(std::make_shared<State>()) {
  state_->fd = fd;
  std::thread([state = state_] { state->write_loop(); }).detach();
}

OutputQueue::~OutputQueue() {
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    state_->stopping = true;
  }
  state_->changed.notify_all();
}

void OutputQueue::push(std::string bytes) {
  if (bytes.empty()) return;
  {
    std::lock_guard<std::mutex> lock(state_->mutex);
    if (state_->error || state_->stopping) return;
    state_->pending += bytes.size();
    state_->queue.push_back(std::move(bytes));
  }
  state_->changed.notify_all();
}

std::size_t OutputQueue::pending_bytes() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->pending;
}

bool OutputQueue::wait_below(std::size_t bytes, int milliseconds) {
  std::unique_lock<std::mutex> lock(state_->mutex);
  state_->changed.wait_for(lock, std::chrono::milliseconds(milliseconds),
                           [&] { return state_->error || state_->pending < bytes; });
  return !state_->error && state_->pending < bytes;
}

int OutputQueue::error() const {
  std::lock_guard<std::mutex> lock(state_->mutex);
  return state_->error;
}

}  // namespace bodyfmt::lsp
