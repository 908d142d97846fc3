#include "drvslam/io/realtime_feeder.h"

#include <spdlog/spdlog.h>

#include <algorithm>
#include <chrono>

#include "drvslam/core/error.h"
#include "drvslam/core/thread_name.h"

namespace drvslam {

RealtimeFeeder::RealtimeFeeder(const TumDataset& dataset, std::size_t count, double rate,
                               FrameRejections* rejections, std::size_t preload_bytes)
    : dataset_(dataset), rejections_(rejections) {
  if (!(rate > 0.0)) throw Error("RealtimeFeeder: the playback rate must be positive");
  thread_ = std::thread([this, count, rate, preload_bytes] {
    NameCurrentThread("drv-camera");
    Play(count, rate, preload_bytes);
    RecordEndedThread();
  });
}

namespace {

std::size_t FrameBytes(const RgbdFrame& frame) {
  return frame.bgr.total() * frame.bgr.elemSize() + frame.depth.total() * frame.depth.elemSize();
}

}  // namespace

bool RealtimeFeeder::Preload(std::size_t count, std::size_t budget) {
  if (count == 0) return false;
  const auto started = std::chrono::steady_clock::now();
  preloaded_.assign(count, std::nullopt);
  preload_errors_.assign(count, nullptr);
  // The first frame that loads tells the size of a frame.
  std::size_t first = 0;
  std::size_t frame_bytes = 0;
  for (; first < count && frame_bytes == 0; ++first) {
    try {
      preloaded_[first] = dataset_.Read(first);
      frame_bytes = FrameBytes(*preloaded_[first]);
    } catch (...) {
      preload_errors_[first] = std::current_exception();
    }
  }
  if (frame_bytes * count > budget) {
    preloaded_.clear();
    preload_errors_.clear();
    return false;
  }
  // Decoding is independent per frame: every core takes a share (nothing else runs yet). A frame
  // that fails keeps its error, raised when its turn comes, after the frames before it.
  const std::size_t workers = std::max(1u, std::thread::hardware_concurrency());
  std::vector<std::thread> threads;
  for (std::size_t w = 0; w < workers; ++w) {
    threads.emplace_back([&, w] {
      NameCurrentThread("drv-decode");
      for (std::size_t i = first + w; i < count; i += workers) {
        try {
          preloaded_[i] = dataset_.Read(i);
        } catch (...) {
          preload_errors_[i] = std::current_exception();
        }
      }
      RecordEndedThread();
    });
  }
  for (std::thread& t : threads) t.join();
  preload_seconds_ =
      std::chrono::duration<double>(std::chrono::steady_clock::now() - started).count();
  return true;
}

RgbdFrame RealtimeFeeder::Load(std::size_t i) {
  if (i < preloaded_.size()) {
    if (preload_errors_[i]) std::rethrow_exception(preload_errors_[i]);
    if (preloaded_[i]) return std::move(*preloaded_[i]);
  }
  return dataset_.Read(i);
}

RealtimeFeeder::~RealtimeFeeder() { Stop(); }

void RealtimeFeeder::Stop() {
  {
    std::lock_guard<std::mutex> lock(mutex_);
    stopping_ = true;
  }
  stop_requested_.notify_all();
  slot_.Close();
  if (thread_.joinable()) thread_.join();
}

void RealtimeFeeder::Play(std::size_t count, double rate, std::size_t preload_bytes) {
  try {
    preloaded_flag_ = Preload(count, preload_bytes);
    if (preloaded_flag_) {
      spdlog::info("realtime: {} frames decoded before playback in {:.2f} s", count,
                   preload_seconds_.load());
    } else if (count > 0) {
      spdlog::info(
          "realtime: the sequence does not fit the {} MB preload budget; frames are "
          "decoded during playback",
          preload_bytes >> 20);
    }
  } catch (...) {
    std::lock_guard<std::mutex> lock(mutex_);
    error_ = std::current_exception();
    slot_.Close();
    return;
  }
  const auto started = std::chrono::steady_clock::now();
  const double first = count > 0 ? dataset_.Timestamp(0) : 0.0;
  const auto due = [&](std::size_t i) {
    return started + std::chrono::duration_cast<std::chrono::steady_clock::duration>(
                         std::chrono::duration<double>((dataset_.Timestamp(i) - first) / rate));
  };
  std::size_t i = 0;
  while (i < count) {
    // Frames whose successor has arrived already would only be replaced: not loaded at all.
    const auto now = std::chrono::steady_clock::now();
    std::size_t newest = i;
    while (newest + 1 < count && due(newest + 1) <= now) ++newest;
    if (newest > i) {
      std::lock_guard<std::mutex> lock(mutex_);
      skipped_loading_ += newest - i;
      i = newest;
    }
    std::optional<RgbdFrame> frame;
    try {
      // Loaded before its arrival time, as a sensor has the image ready when it delivers it.
      frame = Load(i);
      if (rejections_) rejections_->Accept();
    } catch (const FrameError& error) {
      if (!rejections_) {
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        break;
      }
      try {
        rejections_->Reject(i, error);
      } catch (...) {
        // Too many bad frames in a row: the delivery ends with that Error.
        std::lock_guard<std::mutex> lock(mutex_);
        error_ = std::current_exception();
        break;
      }
      ++i;
      continue;
    } catch (...) {
      std::lock_guard<std::mutex> lock(mutex_);
      error_ = std::current_exception();
      break;
    }
    std::unique_lock<std::mutex> lock(mutex_);
    if (stop_requested_.wait_until(lock, due(i), [&] { return stopping_; })) break;
    const double lag_ms =
        std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - due(i))
            .count();
    max_lag_ms_ = std::max(max_lag_ms_, lag_ms);
    lock.unlock();
    slot_.Put(std::move(*frame));
    ++i;
  }
  slot_.Close();
}

void RealtimeFeeder::RecordEndedThread() {
  ThreadUsage usage = ReadCallingThreadUsage();
  std::lock_guard<std::mutex> lock(mutex_);
  ended_threads_.push_back(std::move(usage));
}

std::vector<ThreadUsage> RealtimeFeeder::EndedThreads() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return ended_threads_;
}

bool RealtimeFeeder::Preloaded() const { return preloaded_flag_; }

double RealtimeFeeder::PreloadSeconds() const { return preload_seconds_; }

std::size_t RealtimeFeeder::SkippedWhileLoading() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return skipped_loading_;
}

double RealtimeFeeder::MaxArrivalLagMs() const {
  std::lock_guard<std::mutex> lock(mutex_);
  return max_lag_ms_;
}

std::optional<RgbdFrame> RealtimeFeeder::Next() {
  std::optional<RgbdFrame> frame = slot_.Take();
  if (frame) return frame;
  std::lock_guard<std::mutex> lock(mutex_);
  if (error_) std::rethrow_exception(error_);
  return std::nullopt;
}

}  // namespace drvslam
