// The humble_fastdds_twin command: its command line, signals and exit codes.
#include <atomic>
#include <cctype>
#include <cmath>
#include <csignal>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <string>

#include "twin.hpp"

namespace
{

const char * const kUsage =
  "usage: humble_fastdds_twin [-h] [--module {servo,imu}] [--namespace NAME] [--rate HZ] [--reply-wait S]\n"
  "                           [--no-reply-identity] [--call SERVICE]\n";

const char * const kHelp =
  "\nOne Olive module as a ROS 2 Humble module (rmw_fastrtps, Fast DDS) is on the wire: its graph\n"
  "message in Humble's layout, its node's parameter services, led (Bool) in, and\n"
  "  servo: /olive/servo/NAME/goal/position (Float32) in, /olive/servo/NAME/joint (JointState) out,\n"
  "         setTorqueEnable and setTorqueDisable (std_srvs/srv/Trigger); parameters kp, ki, kd;\n"
  "         torque is off at start, goals move the servo once it is on;\n"
  "  imu:   /olive/imu/NAME/imu (Imu, a fixed 0.3 rad pitch) out, setBias, setZeroQuaternion and\n"
  "         setZeroPose (std_srvs/srv/Trigger, answered only).\n"
  "Ctrl-C stops it.\n\n"
  "options:\n"
  "  -h, --help            show this help and exit\n"
  "  --module {servo,imu}  the module type (default servo)\n"
  "  --namespace NAME      the module's namespace (default humble)\n"
  "  --rate HZ             joint states or IMU readings per second (default 50)\n"
  "  --reply-wait S        how long a reply waits for a new client's reader to be matched\n"
  "                        (default 0.1 s, Fast DDS's max_blocking_time on a Humble module)\n"
  "  --no-reply-identity   send replies without the request's sample identity (a broken server:\n"
  "                        Fast DDS clients then never take the reply)\n"
  "  --call SERVICE        once ready, call this std_srvs/srv/Trigger service (e.g. a servo's\n"
  "                        /olive/servo/pan/setTorqueEnable) as a Humble client does, print the\n"
  "                        answer and its round trip, and go on as the servo\n";

std::atomic<bool> g_stop{false};

void on_signal(int)
{
  g_stop = true;
}

[[noreturn]] void fail(const std::string & message)
{
  std::fprintf(stderr, "%shumble_fastdds_twin: error: %s\n", kUsage, message.c_str());
  std::exit(2);
}

bool is_ros_name(const std::string & name)
{
  if (name.empty() || !std::isalpha(static_cast<unsigned char>(name[0]))) {
    return false;
  }
  for (char c : name) {
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '_') {
      return false;
    }
  }
  return true;
}

double number(const std::string & option, const std::string & text, double low, double high,
  const std::string & what)
{
  char * end = nullptr;
  const double value = std::strtod(text.c_str(), &end);
  if (text.empty() || *end != '\0' || !std::isfinite(value) || value <= low || value > high) {
    fail(option + " '" + text + "' is not " + what);
  }
  return value;
}

owl::TwinOptions parse(int argc, char ** argv)
{
  owl::TwinOptions options;
  for (int i = 1; i < argc; ++i) {
    std::string arg = argv[i];
    std::string value;
    const bool takes_value = arg == "--namespace" || arg == "--rate" || arg == "--reply-wait" || arg == "--module" ||
    arg == "--call";
    const auto equals = arg.find('=');
    if (arg.rfind("--", 0) == 0 && equals != std::string::npos) {
      value = arg.substr(equals + 1);
      arg = arg.substr(0, equals);
    } else if (takes_value) {
      if (i + 1 >= argc) {
        fail("argument " + arg + ": expected one value");
      }
      value = argv[++i];
    }
    if (arg == "-h" || arg == "--help") {
      std::printf("%s%s", kUsage, kHelp);
      std::exit(0);
    } else if (arg == "--module") {
      if (value != "servo" && value != "imu") {
        fail("argument --module: invalid choice: '" + value + "' (choose from 'servo', 'imu')");
      }
      options.module = value;
    } else if (arg == "--namespace") {
      if (!is_ros_name(value)) {
        fail("--namespace '" + value + "' is not a ROS name (letters, digits, _; a letter first)");
      }
      options.name_space = value;
    } else if (arg == "--rate") {
      options.rate = number(arg, value, 0, 1000, "between 0 and 1000 messages per second");
    } else if (arg == "--reply-wait") {
      options.reply_wait = number(arg, value, 0, 60, "a time between 0 and 60 s");
    } else if (arg == "--call") {
      if (value.size() < 2 || value[0] != '/' || value.back() == '/' ||
        value.find("//") != std::string::npos || !is_ros_name(value.substr(value.rfind('/') + 1)))
      {
        fail("--call '" + value + "' is not an absolute service name (e.g. /olive/servo/pan/setTorqueEnable)");
      }
      options.call = value;
    } else if (arg == "--no-reply-identity" && equals == std::string::npos) {
      options.reply_identity = false;
    } else {
      fail("unrecognized argument '" + std::string(argv[i]) + "'");
    }
  }
  return options;
}

}  // namespace

int main(int argc, char ** argv)
{
  const owl::TwinOptions options = parse(argc, argv);
  std::signal(SIGINT, on_signal);
  std::signal(SIGTERM, on_signal);
  try {
    return owl::run_twin(options, g_stop);
  } catch (const std::exception & error) {
    std::fprintf(stderr, "humble_fastdds_twin: error: %s\n", error.what());
    return 1;
  }
}
