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

// std_srvs/srv/Trigger: the request has one placeholder octet; the response a bool and a string.
void check_trigger_request(const Bytes & data);
Bytes encode_trigger_response(bool success, const std::string & message);

}  // namespace owl
