#include "drvslam/core/side_worker.h"

#include <stdexcept>
#include <string>

#include "drvslam/core/thread_name.h"

namespace drvslam {

SideWorker::SideWorker(const char* name)
    : thread_([this, name = std::string(name)] {
        NameCurrentThread(name.c_str());
        Loop();
      }) {}

SideWorker::~SideWorker() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  changed_.notify_all();
  thread_.join();
}

std::exception_ptr SideWorker::TakeItems(int thread) {
  for (int i = next_.fetch_add(1); i < count_; i = next_.fetch_add(1)) {
    try {
      (*item_)(i, thread);
    } catch (...) {
      next_.store(count_);  // the other thread stops after its current item
      return std::current_exception();
    }
  }
  return nullptr;
}

void SideWorker::Offer(const std::function<void(int, int)>* item, int count) {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    item_ = item;
    count_ = count;
    next_.store(0);
    offered_ = true;
    helper_error_ = nullptr;
  }
  changed_.notify_all();
}

void SideWorker::ForEach(int count, const std::function<void(int, int)>& item) {
  if (count <= 0) return;
  if (started_) throw std::logic_error("SideWorker::ForEach called between Start and Finish");
  Offer(&item, count);
  started_ = true;
  Finish();
}

void SideWorker::Start(int count, std::function<void(int, int)> item) {
  if (started_) throw std::logic_error("SideWorker::Start called twice without Finish");
  if (count <= 0) return;
  started_item_ = std::move(item);
  Offer(&started_item_, count);
  started_ = true;
}

void SideWorker::Finish() {
  if (!started_) return;
  started_ = false;
  const std::exception_ptr error = TakeItems(0);
  std::exception_ptr helper_error;
  {
    std::unique_lock<std::mutex> lock(mutex_);
    // A helper that has not joined yet is not waited for: no item is left for it.
    offered_ = false;
    changed_.wait(lock, [this] { return !helping_; });
    helper_error = helper_error_;
    item_ = nullptr;
  }
  started_item_ = nullptr;
  if (error) std::rethrow_exception(error);
  if (helper_error) std::rethrow_exception(helper_error);
}

void SideWorker::Loop() {
  std::unique_lock<std::mutex> lock(mutex_);
  for (;;) {
    changed_.wait(lock, [this] { return stopping_ || offered_; });
    if (stopping_) return;
    offered_ = false;
    helping_ = true;
    lock.unlock();
    const std::exception_ptr error = TakeItems(1);
    lock.lock();
    helper_error_ = error;
    helping_ = false;
    changed_.notify_all();
  }
}

}  // namespace drvslam
