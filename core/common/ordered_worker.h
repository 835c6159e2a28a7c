#pragma once
/// One consumer thread that does `work` for each item pushed, in the order
/// pushed, a bounded number of items behind the producer (docs/architecture.md
/// "Threads"). Nothing flows back from the work to the producer but its
/// errors, so the results are those of doing the work inline, whatever the
/// timing. With capacity 0 the work is done inline, in push().
///
/// An exception from `work` ends the thread; the next push() or finish()
/// rethrows it (items pushed after it are dropped). The destructor stops the
/// thread after the item in progress (a producer may give up early).
#include <condition_variable>
#include <cstddef>
#include <deque>
#include <exception>
#include <functional>
#include <mutex>
#include <thread>
#include <utility>

namespace storey {

template <typename Item>
class OrderedWorker {
 public:
  OrderedWorker(std::size_t capacity, std::function<void(Item&)> work)
      : capacity_(capacity), work_(std::move(work)) {
    if (capacity_ > 0) thread_ = std::thread([this] { run(); });
  }
  OrderedWorker(const OrderedWorker&) = delete;
  OrderedWorker& operator=(const OrderedWorker&) = delete;
  ~OrderedWorker() { stop(/*drain=*/false); }

  /// Queues `item` (waits while `capacity` items are queued).
  void push(Item item) {
    if (capacity_ == 0) {
      work_(item);
      return;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait(lock, [&] { return queue_.size() < capacity_ || error_ || done_; });
    rethrowLocked(lock);
    queue_.push_back(std::move(item));
    lock.unlock();
    changed_.notify_all();
  }

  /// Waits until every item pushed is done; rethrows the work's error.
  void finish() {
    stop(/*drain=*/true);
    std::unique_lock<std::mutex> lock(mutex_);
    rethrowLocked(lock);
  }

 private:
  void run() {
    for (;;) {
      std::unique_lock<std::mutex> lock(mutex_);
      changed_.wait(lock, [&] { return !queue_.empty() || stopping_ || draining_; });
      if (stopping_ || queue_.empty()) break;  // stopped, or drained
      Item item = std::move(queue_.front());
      queue_.pop_front();
      lock.unlock();
      changed_.notify_all();
      try {
        work_(item);
      } catch (...) {
        const std::lock_guard<std::mutex> error_lock(mutex_);
        error_ = std::current_exception();
        queue_.clear();
        break;
      }
    }
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      done_ = true;
    }
    changed_.notify_all();
  }

  void stop(bool drain) {
    {
      const std::lock_guard<std::mutex> lock(mutex_);
      (drain ? draining_ : stopping_) = true;
    }
    changed_.notify_all();
    if (thread_.joinable()) thread_.join();
  }

  void rethrowLocked(std::unique_lock<std::mutex>& lock) {
    if (!error_) return;
    const std::exception_ptr error = error_;
    error_ = nullptr;
    done_ = true;
    lock.unlock();
    std::rethrow_exception(error);
  }

  std::size_t capacity_;
  std::function<void(Item&)> work_;
  std::mutex mutex_;
  std::condition_variable changed_;
  std::deque<Item> queue_;
  bool draining_ = false;  ///< finish(): end when the queue is empty
  bool stopping_ = false;  ///< destructor: end after the item in progress
  bool done_ = false;      ///< the thread has ended
  std::exception_ptr error_;
  std::thread thread_;
};

}  // namespace storey
