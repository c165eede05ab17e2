// The few ROS messages the twin sends and reads, as serialized DDS payloads (CDR, encapsulation
// header included), written by hand with Fast CDR: the layouts are the same on Humble and Jazzy,
// except the graph message's gids (24 bytes on Humble, 16 from Iron on).
#pragma once

#include <array>
#include <cstdint>
#include <stdexcept>
#include <string>
#include <vector>

namespace owl
{

using Bytes = std::vector<uint8_t>;
using HumbleGid = std::array<uint8_t, 24>;  // rmw_dds_common/msg/Gid on Humble: char[24]

// One node's entry of a graph message.
struct NodeEntities
{
  std::string name_space;
  std::string name;
  std::vector<HumbleGid> reader_gids;
  std::vector<HumbleGid> writer_gids;
};

// rmw_dds_common/msg/ParticipantEntitiesInfo in Humble's layout.
struct ParticipantEntities
{
  HumbleGid gid{};
  std::vector<NodeEntities> nodes;
};

// Bytes that are not a sample of the type asked for, with the reason.
struct Malformed : std::runtime_error
{
  using std::runtime_error::runtime_error;
};

Bytes encode_participant_entities(const ParticipantEntities & info);
// Strict: every length fits the sample, strings are NUL-terminated, nothing but padding is left over.
ParticipantEntities decode_participant_entities(const Bytes & data);

Bytes encode_float32(float value);
float decode_float32(const Bytes & data);

// sensor_msgs/msg/JointState with one joint (position only, as the twin knows no more).
Bytes encode_joint_state(
  int32_t sec, uint32_t nanosec, const std::string & frame_id,
  const std::string & joint, double position);

// sensor_msgs/msg/Imu: orientation (x, y, z, w) and linear acceleration; no angular velocity, all
// covariances 0 ("unknown").
Bytes encode_imu(
  int32_t sec, uint32_t nanosec, const std::string & frame_id, const double (&orientation)[4],
  const double (&linear_acceleration)[3]);
bool decode_bool(const Bytes & data);

// std_srvs/srv/Trigger: the request has one placeholder octet; the response a bool and a string.
void check_trigger_request(const Bytes & data);
Bytes encode_trigger_response(bool success, const std::string & message);
Bytes encode_trigger_request();
bool decode_trigger_response(const Bytes & data, std::string & message);

// rcl_interfaces: the parameter services of a node.
enum ParameterType : uint8_t
{
  kNotSet = 0, kBool = 1, kInteger = 2, kDouble = 3, kString = 4, kByteArray = 5, kBoolArray = 6,
  kIntegerArray = 7, kDoubleArray = 8, kStringArray = 9,
};

// rcl_interfaces/msg/ParameterValue: the scalar members kept, the arrays read and left out (the
// twin's parameters are scalars; a request with an array is answered as a type mismatch).
struct ParameterValue
{
  uint8_t type = kNotSet;
  bool bool_value = false;
  int64_t integer_value = 0;
  double double_value = 0.0;
  std::string string_value;
};

struct Parameter
{
  std::string name;
  ParameterValue value;
};

struct ParameterDescriptor
{
  std::string name;
  uint8_t type = kNotSet;
  std::string description;
  bool read_only = false;
};

struct SetResult
{
  bool successful = false;
  std::string reason;
};

// GetParameters, GetParameterTypes, DescribeParameters: the request is `string[] names`.
std::vector<std::string> decode_names_request(const Bytes & data);
// ListParameters: `string[] prefixes`, `uint64 depth`.
std::vector<std::string> decode_list_request(const Bytes & data, uint64_t & depth);
// SetParameters, SetParametersAtomically: `Parameter[] parameters`.
std::vector<Parameter> decode_parameters_request(const Bytes & data);

Bytes encode_list_parameters_response(
  const std::vector<std::string> & names, const std::vector<std::string> & prefixes);
Bytes encode_get_parameters_response(const std::vector<ParameterValue> & values);
Bytes encode_get_parameter_types_response(const std::vector<uint8_t> & types);
Bytes encode_describe_parameters_response(const std::vector<ParameterDescriptor> & descriptors);
Bytes encode_set_parameters_response(const std::vector<SetResult> & results);
Bytes encode_set_parameters_atomically_response(const SetResult & result);

}  // namespace owl
