// One client drives the camera at a time, the others watch: the seat goes to the first client
// that sends input and stays with it while it keeps sending (held keys are sent again every
// quarter second); after SEAT_SECONDS of silence another client may take it.
#pragma once

#include <chrono>
#include <mutex>
#include <string>

namespace gvdp::detail {

constexpr double SEAT_SECONDS = 3.0;

class DriverSeat {
 public:
  using Clock = std::chrono::steady_clock;
  // True when `client` drives now (taking the seat if it is free).
  bool claim(const std::string& client, Clock::time_point now) {
    std::lock_guard lock(mutex_);
    if (client != driver_ && !driver_.empty() && seconds(now - last_) < SEAT_SECONDS) return false;
    driver_ = client;
    last_ = now;
    return true;
  }
  // True when `client` holds the seat now.
  bool drives(const std::string& client, Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    return !client.empty() && client == driver_ && seconds(now - last_) < SEAT_SECONDS;
  }
  bool free(Clock::time_point now) const {
    std::lock_guard lock(mutex_);
    return driver_.empty() || seconds(now - last_) >= SEAT_SECONDS;
  }

 private:
  static double seconds(Clock::duration d) { return std::chrono::duration<double>(d).count(); }
  mutable std::mutex mutex_;
  std::string driver_;
  Clock::time_point last_;
};

}  // namespace gvdp::detail
