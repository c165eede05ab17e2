// One Olive servo or IMU as a ROS 2 Humble module is on the wire, on Fast DDS.
#pragma once

#include <atomic>
#include <string>

namespace owl
{

struct TwinOptions
{
  std::string module = "servo";     // servo or imu
  std::string name_space = "humble";
  double rate = 50.0;              // joint states per second
  bool reply_identity = true;      // false: replies leave out the request's sample identity
  double reply_wait = 0.1;         // s a reply waits for the client's reader (Humble: max_blocking_time)
  std::string call;                // a Trigger service to call once at start, as a Humble client
};

// Runs the twin until stop is set; returns the process's exit code.
int run_twin(const TwinOptions & options, const std::atomic<bool> & stop);

}  // namespace owl
