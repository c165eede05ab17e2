#include "cdr.hpp"

#include <cstring>
#include <functional>

#include <fastcdr/Cdr.h>
#include <fastcdr/FastBuffer.h>
#include <fastcdr/exceptions/Exception.h>

namespace owl
{
namespace
{

using eprosima::fastcdr::Cdr;
using eprosima::fastcdr::CdrVersion;
using eprosima::fastcdr::FastBuffer;

constexpr uint32_t kMaxNameLength = 256;  // NodeEntitiesInfo's strings are string<=256

// Plain CDR (XCDR1, as rmw_fastrtps writes ROS messages), little endian, with its 4-byte header.
Bytes encode(const std::function<void(Cdr &)> & body)
{
  FastBuffer buffer;
  Cdr cdr(buffer, Cdr::LITTLE_ENDIANNESS, CdrVersion::XCDRv1);
  cdr.serialize_encapsulation();
  body(cdr);
  const auto * begin = reinterpret_cast<const uint8_t *>(buffer.getBuffer());
  return Bytes(begin, begin + cdr.get_serialized_data_length());
}

template<typename Result>
Result decode(const Bytes & data, const std::function<Result(Cdr &)> & body)
{
  Bytes copy(data);  // Fast CDR reads from a mutable buffer
  FastBuffer buffer(reinterpret_cast<char *>(copy.data()), copy.size());
  Cdr cdr(buffer, Cdr::DEFAULT_ENDIAN, CdrVersion::XCDRv1);
  try {
    cdr.read_encapsulation();
    return body(cdr);
  } catch (const eprosima::fastcdr::exception::Exception & error) {
    throw Malformed(error.what());
  }
}

// A bounds-checked reader for samples that may be in the other layout: it checks a sequence's
// length against the bytes left before it reads (Humble's generated code sizes the sequence first).
class StrictReader
{
public:
  explicit StrictReader(const Bytes & data)
  : data_(data)
  {
    if (data.size() < 4 || data[0] != 0 || data[1] > 1) {
      throw Malformed("not plain CDR (encapsulation header)");
    }
    little_ = data[1] == 1;
  }

  size_t left() const {return data_.size() - at_;}

  const uint8_t * take(size_t size, const std::string & what)
  {
    if (size > left()) {
      throw Malformed(what + " needs " + std::to_string(size) + " bytes at offset " +
              std::to_string(at_ - 4) + ", " + std::to_string(left()) + " are left");
    }
    const uint8_t * start = data_.data() + at_;
    at_ += size;
    return start;
  }

  uint32_t u32(const std::string & what)
  {
    at_ += (4 - (at_ - 4) % 4) % 4;  // aligned from the end of the header
    if (at_ > data_.size()) {
      at_ = data_.size();
    }
    const uint8_t * b = take(4, what);
    return little_ ? (b[0] | b[1] << 8 | b[2] << 16 | uint32_t(b[3]) << 24) :
           (b[3] | b[2] << 8 | b[1] << 16 | uint32_t(b[0]) << 24);
  }

  uint32_t count(size_t item_size, const std::string & what)
  {
    uint32_t n = u32(what);
    if (uint64_t(n) * item_size > left()) {
      throw Malformed(what + ": a sequence of " + std::to_string(n) + " in " +
              std::to_string(left()) + " bytes");
    }
    return n;
  }

  std::string string(const std::string & what)
  {
    uint32_t length = u32(what);
    if (length < 1 || length > kMaxNameLength + 1) {
      throw Malformed(what + ": a string of " + std::to_string(length) + " bytes");
    }
    const uint8_t * text = take(length, what);
    if (text[length - 1] != 0 || std::memchr(text, 0, length - 1) != nullptr) {
      throw Malformed(what + ": not a NUL-terminated string");
    }
    return std::string(reinterpret_cast<const char *>(text), length - 1);
  }

  void gids(std::vector<HumbleGid> & out, const std::string & what)
  {
    uint32_t n = count(24, what);
    for (uint32_t i = 0; i < n; ++i) {
      HumbleGid gid;
      std::memcpy(gid.data(), take(24, what), 24);
      out.push_back(gid);
    }
  }

  void finish()
  {
    size_t rest = left();
    const uint8_t * tail = data_.data() + at_;
    bool padding = rest <= 3;
    for (size_t i = 0; padding && i < rest; ++i) {
      padding = tail[i] == 0;
    }
    if (!padding) {
      throw Malformed(std::to_string(rest) + " bytes left over after the last node");
    }
  }

private:
  const Bytes & data_;
  size_t at_ = 4;
  bool little_ = true;
};

}  // namespace

Bytes encode_participant_entities(const ParticipantEntities & info)
{
  return encode([&info](Cdr & cdr) {
             cdr.serialize_array(info.gid.data(), info.gid.size());
             cdr << static_cast<uint32_t>(info.nodes.size());
             for (const auto & node : info.nodes) {
               cdr << node.name_space << node.name;
               for (const auto * gids : {&node.reader_gids, &node.writer_gids}) {
                 cdr << static_cast<uint32_t>(gids->size());
                 for (const auto & gid : *gids) {
                   cdr.serialize_array(gid.data(), gid.size());
                 }
               }
             }
           });
}

ParticipantEntities decode_participant_entities(const Bytes & data)
{
  StrictReader in(data);
  ParticipantEntities info;
  std::memcpy(info.gid.data(), in.take(24, "gid"), 24);
  // The smallest node: two empty strings and two empty sequences (20 bytes).
  uint32_t nodes = in.count(20, "node_entities_info_seq");
  for (uint32_t i = 0; i < nodes; ++i) {
    NodeEntities node;
    std::string which = "node " + std::to_string(i);
    node.name_space = in.string(which + " namespace");
    node.name = in.string(which + " name");
    in.gids(node.reader_gids, which + " reader_gid_seq");
    in.gids(node.writer_gids, which + " writer_gid_seq");
    info.nodes.push_back(node);
  }
  in.finish();
  return info;
}

Bytes encode_float32(float value)
{
  return encode([value](Cdr & cdr) {cdr << value;});
}

float decode_float32(const Bytes & data)
{
  return decode<float>(data, [](Cdr & cdr) {
             float value = 0;
             cdr >> value;
             return value;
           });
}

Bytes encode_joint_state(
  int32_t sec, uint32_t nanosec, const std::string & frame_id,
  const std::string & joint, double position)
{
  return encode([&](Cdr & cdr) {
             cdr << sec << nanosec << frame_id;
             cdr << uint32_t{1} << joint;     // name
             cdr << uint32_t{1} << position;  // position
             cdr << uint32_t{0} << uint32_t{0};  // velocity, effort: empty
           });
}

Bytes encode_imu(
  int32_t sec, uint32_t nanosec, const std::string & frame_id, const double (&orientation)[4],
  const double (&linear_acceleration)[3])
{
  return encode([&](Cdr & cdr) {
             cdr << sec << nanosec << frame_id;
             const double none[9] = {};
             for (double q : orientation) {
               cdr << q;
             }
             cdr.serialize_array(none, 9);  // orientation_covariance
             cdr.serialize_array(none, 3);  // angular_velocity
             cdr.serialize_array(none, 9);
             for (double a : linear_acceleration) {
               cdr << a;
             }
             cdr.serialize_array(none, 9);
           });
}

bool decode_bool(const Bytes & data)
{
  return decode<bool>(data, [](Cdr & cdr) {
             bool value = false;
             cdr >> value;
             return value;
           });
}

void check_trigger_request(const Bytes & data)
{
  decode<int>(data, [](Cdr & cdr) {
      uint8_t placeholder = 0;  // structure_needs_at_least_one_member
      cdr >> placeholder;
      return 0;
    });
}

Bytes encode_trigger_response(bool success, const std::string & message)
{
  return encode([&](Cdr & cdr) {cdr << success << message;});
}

Bytes encode_trigger_request()
{
  return encode([](Cdr & cdr) {cdr << uint8_t{0};});
}

bool decode_trigger_response(const Bytes & data, std::string & message)
{
  return decode<bool>(data, [&message](Cdr & cdr) {
             bool success = false;
             cdr >> success >> message;
             return success;
           });
}

namespace
{

void put(Cdr & cdr, const ParameterValue & value)
{
  cdr << value.type << value.bool_value << value.integer_value << value.double_value << value.string_value;
  for (int array = 0; array < 5; ++array) {
    cdr << uint32_t{0};  // byte, bool, integer, double and string arrays: empty
  }
}

ParameterValue take_value(Cdr & cdr)
{
  ParameterValue value;
  cdr >> value.type >> value.bool_value >> value.integer_value >> value.double_value >> value.string_value;
  std::vector<uint8_t> bytes;
  std::vector<bool> bools;
  std::vector<int64_t> integers;
  std::vector<double> doubles;
  std::vector<std::string> strings;
  cdr >> bytes >> bools >> integers >> doubles >> strings;
  return value;
}

void put_strings(Cdr & cdr, const std::vector<std::string> & strings)
{
  cdr << static_cast<uint32_t>(strings.size());
  for (const auto & text : strings) {
    cdr << text;
  }
}

void put_result(Cdr & cdr, const SetResult & result)
{
  cdr << result.successful << result.reason;
}

}  // namespace

std::vector<std::string> decode_names_request(const Bytes & data)
{
  return decode<std::vector<std::string>>(data, [](Cdr & cdr) {
             std::vector<std::string> names;
             cdr >> names;
             return names;
           });
}

std::vector<std::string> decode_list_request(const Bytes & data, uint64_t & depth)
{
  return decode<std::vector<std::string>>(data, [&depth](Cdr & cdr) {
             std::vector<std::string> prefixes;
             cdr >> prefixes >> depth;
             return prefixes;
           });
}

std::vector<Parameter> decode_parameters_request(const Bytes & data)
{
  return decode<std::vector<Parameter>>(data, [&data](Cdr & cdr) {
             uint32_t count = 0;
             cdr >> count;
             if (count > data.size()) {
               throw Malformed("a sequence of " + std::to_string(count) + " parameters in " +
               std::to_string(data.size()) + " bytes");
             }
             std::vector<Parameter> parameters(count);
             for (auto & parameter : parameters) {
               cdr >> parameter.name;
               parameter.value = take_value(cdr);
             }
             return parameters;
           });
}

Bytes encode_list_parameters_response(
  const std::vector<std::string> & names, const std::vector<std::string> & prefixes)
{
  return encode([&](Cdr & cdr) {
             put_strings(cdr, names);
             put_strings(cdr, prefixes);
           });
}

Bytes encode_get_parameters_response(const std::vector<ParameterValue> & values)
{
  return encode([&](Cdr & cdr) {
             cdr << static_cast<uint32_t>(values.size());
             for (const auto & value : values) {
               put(cdr, value);
             }
           });
}

Bytes encode_get_parameter_types_response(const std::vector<uint8_t> & types)
{
  return encode([&](Cdr & cdr) {
             cdr << static_cast<uint32_t>(types.size());
             for (uint8_t type : types) {
               cdr << type;
             }
           });
}

Bytes encode_describe_parameters_response(const std::vector<ParameterDescriptor> & descriptors)
{
  return encode([&](Cdr & cdr) {
             cdr << static_cast<uint32_t>(descriptors.size());
             for (const auto & d : descriptors) {
               cdr << d.name << d.type << d.description << std::string() << d.read_only;
               cdr << false;  // dynamic_typing
               cdr << uint32_t{0} << uint32_t{0};  // floating_point_range, integer_range: none
             }
           });
}

Bytes encode_set_parameters_response(const std::vector<SetResult> & results)
{
  return encode([&](Cdr & cdr) {
             cdr << static_cast<uint32_t>(results.size());
             for (const auto & result : results) {
               put_result(cdr, result);
             }
           });
}

Bytes encode_set_parameters_atomically_response(const SetResult & result)
{
  return encode([&](Cdr & cdr) {put_result(cdr, result);});
}

}  // namespace owl
