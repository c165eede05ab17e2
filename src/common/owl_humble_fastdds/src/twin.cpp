// humble_fastdds_twin: one Olive servo or IMU as a ROS 2 Humble module (rmw_fastrtps_cpp) is on the wire.
//
// What it has of Humble: its graph message on ros_discovery_info has 24-byte gids; its endpoints
// carry no type hash (no USER_DATA) and no XTypes type information; its services are the
// request/reply topic pairs of rmw_fastrtps (rq/<service>Request, rr/<service>Reply), and a reply
// carries the request's sample identity as its related sample identity, the client's reply reader
// in place of the request writer when the request names it. That is how a Fast DDS client (Humble's
// or Jazzy's) pairs a reply with its request; without it the client drops the reply.
#include "twin.hpp"

#include <chrono>
#include <cctype>
#include <cinttypes>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <functional>
#include <iomanip>
#include <map>
#include <memory>
#include <mutex>
#include <set>
#include <sstream>
#include <thread>
#include <vector>

#include <fastdds/dds/domain/DomainParticipant.hpp>
#include <fastdds/dds/domain/DomainParticipantFactory.hpp>
#include <fastdds/dds/domain/qos/DomainParticipantQos.hpp>
#include <fastdds/dds/publisher/DataWriter.hpp>
#include <fastdds/dds/publisher/DataWriterListener.hpp>
#include <fastdds/dds/publisher/Publisher.hpp>
#include <fastdds/dds/publisher/qos/DataWriterQos.hpp>
#include <fastdds/dds/subscriber/DataReader.hpp>
#include <fastdds/dds/subscriber/DataReaderListener.hpp>
#include <fastdds/dds/subscriber/SampleInfo.hpp>
#include <fastdds/dds/subscriber/Subscriber.hpp>
#include <fastdds/dds/subscriber/qos/DataReaderQos.hpp>
#include <fastdds/dds/topic/Topic.hpp>
#include <fastdds/dds/topic/TopicDataType.hpp>
#include <fastdds/dds/topic/TypeSupport.hpp>
#include <fastdds/rtps/common/WriteParams.h>
#include <fastdds/rtps/transport/UDPv4TransportDescriptor.h>
#include <fastrtps/config.h>
#include <fastrtps/utils/IPLocator.h>

#include "cdr.hpp"

namespace owl
{
namespace
{

namespace dds = eprosima::fastdds::dds;
namespace rtps = eprosima::fastrtps::rtps;
using Clock = std::chrono::steady_clock;

const char * const kPrefix = "humble_fastdds_twin";
const char * const kDiscoveryTopic = "ros_discovery_info";
const char * const kDiscoveryType = "rmw_dds_common::msg::dds_::ParticipantEntitiesInfo_";
constexpr double kServoSpeed = 3.0;  // rad/s towards the goal, as humble_twin's servo
constexpr double kPitch = 0.3;       // rad, the IMU's fixed tilt, as humble_twin's
constexpr int kMaxDomainId = 232;    // as owl_common.ros_env: the largest id whose ports fit

void say(const std::string & text)
{
  std::printf("%s: %s\n", kPrefix, text.c_str());
  std::fflush(stdout);
}

// A sample handled as its serialized bytes: the payload, encapsulation header included.
struct RawSample
{
  Bytes bytes;
};

// One DDS type name, samples as bytes (cdr.hpp writes and reads them). No type object and no type
// information is announced: rmw_fastrtps on Humble sends none.
class RawType : public dds::TopicDataType
{
public:
  explicit RawType(const std::string & name)
  {
    setName(name.c_str());
    m_typeSize = 512;  // the first guess of a payload's size; larger ones are grown
    m_isGetKeyDefined = false;
    auto_fill_type_object(false);
    auto_fill_type_information(false);
  }

  using dds::TopicDataType::serialize;
  using dds::TopicDataType::getSerializedSizeProvider;

  bool serialize(void * data, rtps::SerializedPayload_t * payload) override
  {
    const Bytes & bytes = static_cast<RawSample *>(data)->bytes;
    if (payload->max_size < bytes.size()) {
      payload->reserve(static_cast<uint32_t>(bytes.size()));
    }
    std::memcpy(payload->data, bytes.data(), bytes.size());
    payload->length = static_cast<uint32_t>(bytes.size());
    payload->encapsulation = bytes.size() > 1 && bytes[1] == 1 ? CDR_LE : CDR_BE;
    return true;
  }

  bool deserialize(rtps::SerializedPayload_t * payload, void * data) override
  {
    static_cast<RawSample *>(data)->bytes.assign(payload->data, payload->data + payload->length);
    return true;
  }

  std::function<uint32_t()> getSerializedSizeProvider(void * data) override
  {
    const auto size = static_cast<uint32_t>(static_cast<RawSample *>(data)->bytes.size());
    return [size]() {return size;};
  }

  void * createData() override {return new RawSample();}
  void deleteData(void * data) override {delete static_cast<RawSample *>(data);}
  bool getKey(void *, rtps::InstanceHandle_t *, bool) override {return false;}
};

std::string ros_type(const std::string & package, const std::string & kind, const std::string & name)
{
  return package + "::" + kind + "::dds_::" + name + "_";
}

std::string hex(const uint8_t * data, size_t size)
{
  std::ostringstream out;
  for (size_t i = 0; i < size; ++i) {
    out << std::hex << std::setw(2) << std::setfill('0') << int(data[i]);
  }
  return out.str();
}

HumbleGid humble_gid(const rtps::GUID_t & guid)
{
  HumbleGid gid{};  // a GUID is 16 bytes; Humble pads the gid with zeros
  std::memcpy(gid.data(), guid.guidPrefix.value, 12);
  std::memcpy(gid.data() + 12, guid.entityId.value, 4);
  return gid;
}

std::string guid_text(const rtps::GUID_t & guid)
{
  HumbleGid gid = humble_gid(guid);
  return hex(gid.data(), 16);
}

// Wakes the main loop when a reader has data.
class Wakeup : public dds::DataReaderListener
{
public:
  void on_data_available(dds::DataReader *) override
  {
    {
      std::lock_guard<std::mutex> lock(mutex_);
      pending_ = true;
    }
    changed_.notify_all();
  }

  void wait_until(Clock::time_point deadline)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    changed_.wait_until(lock, deadline, [this] {return pending_;});
    pending_ = false;
  }

private:
  std::mutex mutex_;
  std::condition_variable changed_;
  bool pending_ = false;
};

// The readers a reply writer has matched, so a reply can wait for a brand-new client's reader as
// rmw_fastrtps on Humble does (rmw_send_response: up to the writer's max_blocking_time).
class MatchedReaders : public dds::DataWriterListener
{
public:
  void on_publication_matched(dds::DataWriter *, const dds::PublicationMatchedStatus & status) override
  {
    const rtps::GUID_t guid = rtps::iHandle2GUID(status.last_subscription_handle);
    {
      std::lock_guard<std::mutex> lock(mutex_);
      if (status.current_count_change > 0) {
        readers_.insert(guid);
      } else if (status.current_count_change < 0) {
        readers_.erase(guid);
      }
    }
    changed_.notify_all();
  }

  bool wait_for(const rtps::GUID_t & reader, std::chrono::duration<double> timeout)
  {
    std::unique_lock<std::mutex> lock(mutex_);
    return changed_.wait_for(lock, timeout, [&] {return readers_.count(reader) > 0;});
  }

private:
  std::mutex mutex_;
  std::condition_variable changed_;
  std::set<rtps::GUID_t> readers_;
};

// A request's bytes -> the reply's bytes, and what the twin's line about the call says.
using Handler = std::function<Bytes(const Bytes & request, std::string & note)>;

struct Service
{
  std::string name;  // as the twin's lines name it: setTorqueEnable, get_parameters, ...
  Handler handle;
  dds::DataReader * requests = nullptr;
  dds::DataWriter * replies = nullptr;
  std::unique_ptr<MatchedReaders> matched;
};

struct DiscoverySettings
{
  int domain_id = 0;
  std::string range = "SUBNET";
  std::vector<std::string> peers;
};

// ROS_DOMAIN_ID, ROS_AUTOMATIC_DISCOVERY_RANGE and ROS_STATIC_PEERS as rcl (Jazzy) reads them: the
// twin joins our Jazzy processes in the discovery range they use.
bool read_discovery_settings(DiscoverySettings & settings, std::string & error)
{
  const char * domain = std::getenv("ROS_DOMAIN_ID");
  if (domain != nullptr && *domain != '\0') {
    char * end = nullptr;
    long value = std::strtol(domain, &end, 10);
    if (*end != '\0' || value < 0 || value > kMaxDomainId) {
      error = std::string("ROS_DOMAIN_ID '") + domain + "' is not a ROS domain (0 to " +
        std::to_string(kMaxDomainId) + ")";
      return false;
    }
    settings.domain_id = static_cast<int>(value);
  }
  const char * range = std::getenv("ROS_AUTOMATIC_DISCOVERY_RANGE");
  if (range != nullptr && *range != '\0') {
    settings.range = range;
  }
  if (settings.range == "SYSTEM_DEFAULT") {
    settings.range = "SUBNET";
  }
  if (settings.range != "LOCALHOST" && settings.range != "SUBNET") {
    error = "ROS_AUTOMATIC_DISCOVERY_RANGE '" + settings.range +
      "' is not one the twin joins (LOCALHOST or SUBNET)";
    return false;
  }
  if (const char * peers = std::getenv("ROS_STATIC_PEERS")) {
    std::stringstream list(peers);
    for (std::string peer; std::getline(list, peer, ';'); ) {
      if (!peer.empty()) {
        settings.peers.push_back(peer);
      }
    }
  }
  return true;
}

bool configure_discovery(
  dds::DomainParticipantQos & qos, const DiscoverySettings & settings, std::string & error)
{
  auto & builtin = qos.wire_protocol().builtin;
  // UDP only, as between a module and the student's machine (no shared memory between two hosts).
  qos.transport().use_builtin_transports = false;
  auto udp = std::make_shared<eprosima::fastdds::rtps::UDPv4TransportDescriptor>();
  if (settings.range == "LOCALHOST") {
    // As rmw_fastrtps (Jazzy) in LOCALHOST: no multicast, unicast announcements to this host's
    // well-known ports of the first 32 participants.
    builtin.metatrafficMulticastLocatorList.clear();
    builtin.metatrafficUnicastLocatorList.push_back(rtps::Locator_t());
    udp->maxInitialPeersRange = 32;
  }
  qos.transport().user_transports.push_back(udp);
  for (const std::string & peer : settings.peers) {
    auto addresses = rtps::IPLocator::resolveNameDNS(peer);
    if (addresses.first.empty()) {
      error = "ROS_STATIC_PEERS: cannot resolve '" + peer + "' to an IPv4 address";
      return false;
    }
    rtps::Locator_t locator;
    rtps::IPLocator::setIPv4(locator, *addresses.first.begin());
    builtin.initialPeersList.push_back(locator);
  }
  if (settings.range == "LOCALHOST") {
    rtps::Locator_t localhost;
    rtps::IPLocator::setIPv4(localhost, "127.0.0.1");
    builtin.initialPeersList.push_back(localhost);
  } else if (!builtin.initialPeersList.empty()) {
    rtps::Locator_t multicast;  // static peers replace the default; keep announcing on multicast
    rtps::IPLocator::setIPv4(multicast, 239, 255, 0, 1);
    builtin.initialPeersList.push_back(multicast);
  }
  return true;
}

class Twin
{
public:
  explicit Twin(const TwinOptions & options)
  : options_(options),
    prefix_("/olive/" + options.module + "/" + options.name_space + "/"),
    node_name_("olive_" + options.module + "_" + options.name_space + "_dcm_srv"),
    period_(1.0 / options.rate)
  {}

  ~Twin()
  {
    if (participant_ != nullptr) {
      // Deleting the participant says goodbye on DDS: our tools drop the node at once.
      participant_->delete_contained_entities();
      dds::DomainParticipantFactory::get_instance()->delete_participant(participant_);
    }
  }

  bool start(std::string & error)
  {
    if (options_.module == "servo") {
      parameters_["kd"] = {double_value(0.3), "PID gain kd of the position controller"};
      parameters_["ki"] = {double_value(10.0), "PID gain ki of the position controller"};
      parameters_["kp"] = {double_value(5.0), "PID gain kp of the position controller"};
    }
    DiscoverySettings settings;
    if (!read_discovery_settings(settings, error)) {
      return false;
    }
    domain_id_ = settings.domain_id;
    auto * factory = dds::DomainParticipantFactory::get_instance();
    dds::DomainParticipantQos qos = factory->get_default_participant_qos();
    if (!configure_discovery(qos, settings, error)) {
      return false;
    }
    const std::string enclave = "enclave=/;";  // rmw_fastrtps's participant USER_DATA
    qos.user_data().data_vec(std::vector<rtps::octet>(enclave.begin(), enclave.end()));
    participant_ = factory->create_participant(settings.domain_id, qos);
    if (participant_ == nullptr) {
      error = "Fast DDS could not create a participant in domain " + std::to_string(settings.domain_id);
      return false;
    }
    publisher_ = participant_->create_publisher(dds::PUBLISHER_QOS_DEFAULT);
    subscriber_ = participant_->create_subscriber(dds::SUBSCRIBER_QOS_DEFAULT);

    discovery_reader_ = reader(kDiscoveryTopic, kDiscoveryType, discovery_reader_qos());
    discovery_writer_ = writer(kDiscoveryTopic, kDiscoveryType, discovery_writer_qos());
    led_reader_ = reader("rt" + prefix_ + "led", ros_type("std_msgs", "msg", "Bool"), topic_reader_qos());
    NodeEntities node{"/", node_name_, {humble_gid(led_reader_->guid())}, {}};
    if (options_.module == "imu") {
      imu_writer_ = writer("rt" + prefix_ + "imu", ros_type("sensor_msgs", "msg", "Imu"), topic_writer_qos());
      node.writer_gids.push_back(humble_gid(imu_writer_->guid()));
      // The IMU's services (specs: olive_hardware.md 2.3); what they do is not known, so they only answer.
      for (const auto & [name, done] : {std::pair{"setBias", "bias set"},
          {"setZeroQuaternion", "orientation zeroed"}, {"setZeroPose", "pose zeroed"}})
      {
        const std::string answer = done;
        add_service(node, prefix_, name, "std_srvs", "Trigger",
          [answer](const Bytes & request, std::string & note) {
            check_trigger_request(request);
            note = answer;
            return encode_trigger_response(true, answer);
          });
      }
    } else {
      goal_reader_ = reader("rt" + prefix_ + "goal/position", ros_type("std_msgs", "msg", "Float32"),
          topic_reader_qos());
      joint_writer_ = writer("rt" + prefix_ + "joint", ros_type("sensor_msgs", "msg", "JointState"),
          topic_writer_qos());
      node.reader_gids.push_back(humble_gid(goal_reader_->guid()));
      node.writer_gids.push_back(humble_gid(joint_writer_->guid()));
      for (bool torque : {true, false}) {
        add_service(node, prefix_, torque ? "setTorqueEnable" : "setTorqueDisable", "std_srvs", "Trigger",
          [this, torque](const Bytes & request, std::string & note) {
            return switch_torque(request, torque, note);
          });
      }
    }
    // The parameter services every Humble node has (Jazzy's nodes add get_type_description).
    const std::string node_prefix = "/" + node_name_ + "/";
    const std::pair<const char *, Handler> parameter_services[] = {
      {"describe_parameters", [this](const Bytes & r, std::string & n) {return describe_parameters(r, n);}},
      {"get_parameter_types", [this](const Bytes & r, std::string & n) {return get_parameter_types(r, n);}},
      {"get_parameters", [this](const Bytes & r, std::string & n) {return get_parameters(r, n);}},
      {"list_parameters", [this](const Bytes & r, std::string & n) {return list_parameters(r, n);}},
      {"set_parameters", [this](const Bytes & r, std::string & n) {return set_parameters(r, false, n);}},
      {"set_parameters_atomically",
        [this](const Bytes & r, std::string & n) {return set_parameters(r, true, n);}},
    };
    for (const auto & [name, handler] : parameter_services) {
      std::string type;  // describe_parameters -> DescribeParameters
      bool upper = true;
      for (const char * c = name; *c != '\0'; ++c) {
        if (*c == '_') {
          upper = true;
        } else {
          type += upper ? static_cast<char>(std::toupper(*c)) : *c;
          upper = false;
        }
      }
      add_service(node, node_prefix, name, "rcl_interfaces", type, handler);
    }
    if (!options_.call.empty()) {
      // A client of a Trigger service, as rclcpp's on Humble: its request writer and reply reader.
      call_requests_ = writer("rq" + options_.call + "Request", ros_type("std_srvs", "srv", "Trigger_Request"),
          topic_writer_qos());
      call_replies_ = reader("rr" + options_.call + "Reply", ros_type("std_srvs", "srv", "Trigger_Response"),
          topic_reader_qos());
      if (call_requests_ != nullptr && call_replies_ != nullptr) {
        node.writer_gids.push_back(humble_gid(call_requests_->guid()));
        node.reader_gids.push_back(humble_gid(call_replies_->guid()));
      }
    }
    for (dds::DataReader * each : readers_) {
      if (each == nullptr) {
        error = "Fast DDS could not create a reader";
        return false;
      }
    }
    for (dds::DataWriter * each : writers_) {
      if (each == nullptr) {
        error = "Fast DDS could not create a writer";
        return false;
      }
    }
    ParticipantEntities info{humble_gid(participant_->guid()), {node}};
    own_gid_ = info.gid;
    RawSample graph{encode_participant_entities(info)};
    discovery_writer_->write(&graph);
    return true;
  }

  std::string ready_line() const
  {
    return "ready: node /" + node_name_ + " (" + options_.module + ", ROS 2 Humble on Fast DDS " + FASTRTPS_VERSION_STR +
           ", replies " + (options_.reply_identity ? "with" : "WITHOUT") +
           " the request's identity), participant " + guid_text(participant_->guid()) +
           " in domain " + std::to_string(domain_id_);
  }

  // The --call: wait for the service (its request reader and reply writer matched, as a client's
  // wait_for_service), send one request naming this client's reply reader in its related sample
  // identity, and take the reply whose related sample identity is the request's.
  void call_once(const std::atomic<bool> & stop)
  {
    const std::string & service = options_.call;
    const auto found_by = Clock::now() + std::chrono::seconds(20);
    dds::PublicationMatchedStatus requests;
    dds::SubscriptionMatchedStatus replies;
    while (!stop) {
      call_requests_->get_publication_matched_status(requests);
      call_replies_->get_subscription_matched_status(replies);
      if (requests.current_count > 0 && replies.current_count > 0) {
        break;
      }
      if (Clock::now() > found_by) {
        say("call " + service + ": no server of it within 20 s");
        return;
      }
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
    if (stop) {
      return;
    }
    RawSample request{encode_trigger_request()};
    rtps::WriteParams params;
    params.related_sample_identity().writer_guid() = call_replies_->guid();
    const auto sent = Clock::now();
    if (!call_requests_->write(&request, params)) {
      say("call " + service + ": the request could not be written");
      return;
    }
    const rtps::SequenceNumber_t sequence = params.sample_identity().sequence_number();
    const auto answered_by = sent + std::chrono::seconds(10);
    while (!stop && Clock::now() < answered_by) {
      RawSample reply;
      dds::SampleInfo info;
      while (call_replies_->take_next_sample(&reply, &info) == ReturnCode_t::RETCODE_OK) {
        if (!info.valid_data) {
          continue;
        }
        const rtps::SampleIdentity & related = info.related_sample_identity;
        const bool ours = related.writer_guid() == call_replies_->guid() ||
          related.writer_guid() == call_requests_->guid();
        if (!ours || related.sequence_number() != sequence) {
          say("call " + service + ": a reply for another request (" + guid_text(related.writer_guid()) +
            " #" + std::to_string(related.sequence_number().to64long()) + "), left alone");
          continue;
        }
        const double took_ms = std::chrono::duration<double, std::milli>(Clock::now() - sent).count();
        std::string message;
        bool success = false;
        try {
          success = decode_trigger_response(reply.bytes, message);
        } catch (const Malformed & error) {
          say("call " + service + ": the reply does not parse (" + error.what() + ")");
          return;
        }
        std::ostringstream line;
        line << "call " << service << ": success=" << (success ? "true" : "false") << " message='" << message
             << "' (request #" << sequence.to64long() << ", round trip " << std::fixed << std::setprecision(1)
             << took_ms << " ms)";
        say(line.str());
        return;
      }
      wakeup_.wait_until(std::min(answered_by, Clock::now() + std::chrono::milliseconds(100)));
    }
    if (!stop) {
      say("call " + service + ": no reply within 10 s");
    }
  }

  void run(const std::atomic<bool> & stop)
  {
    auto next_tick = Clock::now();
    while (!stop) {
      take_graph_messages();
      answer_requests();
      take_led();
      if (goal_reader_ != nullptr) {
        take_goals();
      }
      if (Clock::now() >= next_tick) {
        if (imu_writer_ != nullptr) {
          publish_imu();
        } else {
          publish_joint();
        }
        next_tick += std::chrono::duration_cast<Clock::duration>(period_);
      }
      // A request is answered as it comes; at most 100 ms between looks at the stop flag.
      wakeup_.wait_until(std::min(next_tick, Clock::now() + std::chrono::milliseconds(100)));
    }
  }

  std::string summary() const
  {
    return "discovery samples received: " + std::to_string(received_) +
           ", malformed in Humble's layout: " + std::to_string(malformed_) +
           "; replies sent: " + std::to_string(replies_);
  }

private:
  // rclpy's QoSProfile(depth=10) and rmw's services default: reliable, volatile, keep last 10.
  template<typename Qos>
  static Qos topic_qos(Qos qos)
  {
    qos.reliability().kind = dds::RELIABLE_RELIABILITY_QOS;
    qos.durability().kind = dds::VOLATILE_DURABILITY_QOS;
    qos.history().kind = dds::KEEP_LAST_HISTORY_QOS;
    qos.history().depth = 10;
    qos.endpoint().history_memory_policy = rtps::PREALLOCATED_WITH_REALLOC_MEMORY_MODE;
    qos.data_sharing().off();
    return qos;
  }

  static dds::DataWriterQos topic_writer_qos() {return topic_qos(dds::DATAWRITER_QOS_DEFAULT);}

  static dds::DataReaderQos topic_reader_qos() {return topic_qos(dds::DATAREADER_QOS_DEFAULT);}

  static dds::DataWriterQos discovery_writer_qos()
  {
    dds::DataWriterQos qos = topic_writer_qos();  // reliable, transient local, the last sample only
    qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
    qos.history().depth = 1;
    return qos;
  }

  static dds::DataReaderQos discovery_reader_qos()
  {
    dds::DataReaderQos qos = topic_reader_qos();  // reliable, transient local, every sample kept
    qos.durability().kind = dds::TRANSIENT_LOCAL_DURABILITY_QOS;
    qos.history().kind = dds::KEEP_ALL_HISTORY_QOS;
    return qos;
  }

  dds::Topic * topic(const std::string & name, const std::string & type_name)
  {
    if (participant_->find_type(type_name).empty()) {
      dds::TypeSupport type(new RawType(type_name));
      type.register_type(participant_);
    }
    if (dds::TopicDescription * existing = participant_->lookup_topicdescription(name)) {
      return static_cast<dds::Topic *>(existing);
    }
    return participant_->create_topic(name, type_name, dds::TOPIC_QOS_DEFAULT);
  }

  dds::DataReader * reader(const std::string & name, const std::string & type_name,
    const dds::DataReaderQos & qos)
  {
    dds::DataReader * created = subscriber_->create_datareader(topic(name, type_name), qos, &wakeup_);
    readers_.push_back(created);
    return created;
  }

  dds::DataWriter * writer(const std::string & name, const std::string & type_name,
    const dds::DataWriterQos & qos, dds::DataWriterListener * listener = nullptr)
  {
    dds::DataWriter * created = publisher_->create_datawriter(topic(name, type_name), qos, listener);
    writers_.push_back(created);
    return created;
  }

  void add_service(NodeEntities & node, const std::string & prefix, const std::string & name,
    const std::string & package, const std::string & type, Handler handler)
  {
    Service service;
    service.name = name;
    service.handle = std::move(handler);
    service.requests = reader("rq" + prefix + name + "Request", ros_type(package, "srv", type + "_Request"),
        topic_reader_qos());
    service.matched = std::make_unique<MatchedReaders>();
    service.replies = writer("rr" + prefix + name + "Reply", ros_type(package, "srv", type + "_Response"),
        topic_writer_qos(), service.matched.get());
    if (service.requests != nullptr && service.replies != nullptr) {
      node.reader_gids.push_back(humble_gid(service.requests->guid()));
      node.writer_gids.push_back(humble_gid(service.replies->guid()));
    }
    services_.push_back(std::move(service));
  }

  Bytes switch_torque(const Bytes & request, bool torque, std::string & note)
  {
    check_trigger_request(request);
    const bool already = torque_ == torque;
    torque_ = torque;
    const std::string state = torque ? "enabled" : "disabled";
    note = already ? "torque already " + state : "torque " + state;
    say(std::string("torque ") + (torque_ ? "on" : "off"));
    return encode_trigger_response(true, note);
  }

  static std::string value_text(const ParameterValue & value)
  {
    std::ostringstream out;
    switch (value.type) {
      case kBool: out << (value.bool_value ? "true" : "false"); break;
      case kInteger: out << value.integer_value; break;
      case kDouble: out << value.double_value; break;
      case kString: out << "'" << value.string_value << "'"; break;
      default: out << "(" << type_name(value.type) << ")";
    }
    return out.str();
  }

  static std::string type_name(uint8_t type)
  {
    // rclcpp's names of the types, as its messages use them
    static const char * const names[] = {"not set", "bool", "integer", "double", "string", "byte_array",
      "bool_array", "integer_array", "double_array", "string_array"};
    return type < 10 ? names[type] : "unknown type " + std::to_string(type);
  }

  Bytes list_parameters(const Bytes & request, std::string & note)
  {
    uint64_t depth = 0;
    const std::vector<std::string> prefixes = decode_list_request(request, depth);
    std::vector<std::string> names;
    for (const auto & [name, value] : parameters_) {
      bool wanted = prefixes.empty();
      for (const auto & prefix : prefixes) {
        wanted = wanted || name == prefix || name.rfind(prefix + ".", 0) == 0;
      }
      if (wanted) {
        names.push_back(name);
      }
    }
    note = std::to_string(names.size()) + " names";
    return encode_list_parameters_response(names, {});
  }

  Bytes get_parameters(const Bytes & request, std::string & note)
  {
    std::vector<ParameterValue> values;
    for (const auto & name : decode_names_request(request)) {
      auto found = parameters_.find(name);
      values.push_back(found == parameters_.end() ? ParameterValue() : found->second.value);
      note += (note.empty() ? "" : ", ") + name + " = " + value_text(values.back());
    }
    return encode_get_parameters_response(values);
  }

  Bytes get_parameter_types(const Bytes & request, std::string & note)
  {
    std::vector<uint8_t> types;
    for (const auto & name : decode_names_request(request)) {
      auto found = parameters_.find(name);
      types.push_back(found == parameters_.end() ? uint8_t{kNotSet} : found->second.value.type);
      note += (note.empty() ? "" : ", ") + name + ": " + type_name(types.back());
    }
    return encode_get_parameter_types_response(types);
  }

  Bytes describe_parameters(const Bytes & request, std::string & note)
  {
    std::vector<ParameterDescriptor> descriptors;
    for (const auto & name : decode_names_request(request)) {
      auto found = parameters_.find(name);
      if (found == parameters_.end()) {
        // rclcpp's parameter service answers with no descriptors when one is not declared.
        note = name + " is not declared: no descriptors";
        return encode_describe_parameters_response({});
      }
      descriptors.push_back({name, found->second.value.type, found->second.description, false});
      note += (note.empty() ? "" : ", ") + name;
    }
    return encode_describe_parameters_response(descriptors);
  }

  // What setting the parameter would do: rclcpp's checks for declared, statically typed parameters.
  SetResult check(const Parameter & parameter) const
  {
    auto found = parameters_.find(parameter.name);
    if (found == parameters_.end()) {
      return {false, "One or more parameters were not declared before setting"};
    }
    const uint8_t type = found->second.value.type;
    if (parameter.value.type == kNotSet) {
      return {false, "Static parameter cannot be undeclared"};
    }
    if (parameter.value.type != type) {
      return {false, "Wrong parameter type, parameter {" + parameter.name + "} is of type {" + type_name(type) +
              "}, setting it to {" + type_name(parameter.value.type) + "} is not allowed."};
    }
    return {true, ""};
  }

  Bytes set_parameters(const Bytes & request, bool atomically, std::string & note)
  {
    const std::vector<Parameter> parameters = decode_parameters_request(request);
    std::vector<SetResult> results;
    SetResult all{true, ""};
    for (const auto & parameter : parameters) {
      results.push_back(check(parameter));
      if (!results.back().successful && all.successful) {
        all = results.back();
      }
    }
    for (size_t i = 0; i < parameters.size(); ++i) {
      const bool applied = atomically ? all.successful : results[i].successful;
      if (applied) {
        parameters_[parameters[i].name].value = parameters[i].value;
        say("parameter " + parameters[i].name + " = " + value_text(parameters[i].value));
      }
      note += (note.empty() ? "" : ", ") + parameters[i].name + " = " + value_text(parameters[i].value) +
        (applied ? "" : " refused (" + (atomically ? all : results[i]).reason + ")");
    }
    return atomically ? encode_set_parameters_atomically_response(all) : encode_set_parameters_response(results);
  }

  void take_graph_messages()
  {
    RawSample sample;
    dds::SampleInfo info;
    while (discovery_reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;
      }
      try {
        if (decode_participant_entities(sample.bytes).gid != own_gid_) {
          ++received_;
        }
      } catch (const Malformed & error) {
        ++received_;
        ++malformed_;
        const std::string sender = sample.bytes.size() >= 20 ? hex(sample.bytes.data() + 4, 16) : "?";
        say("malformed discovery sample #" + std::to_string(malformed_) + " (from participant " +
          sender + "): " + error.what());
      }
    }
  }

  void answer_requests()
  {
    for (Service & service : services_) {
      RawSample sample;
      dds::SampleInfo info;
      while (service.requests->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
        if (info.valid_data) {
          answer(service, sample, info);
        }
      }
    }
  }

  void answer(Service & service, const RawSample & request, const dds::SampleInfo & info)
  {
    const auto received = Clock::now();
    const int64_t sequence = info.sample_identity.sequence_number().to64long();
    const std::string from = guid_text(info.sample_identity.writer_guid());
    std::string message;
    RawSample reply;
    try {
      reply.bytes = service.handle(request.bytes, message);
    } catch (const Malformed & error) {
      say(service.name + ": request #" + std::to_string(sequence) + " from " + from +
        " does not parse (" + error.what() + "): not answered");
      return;
    }
    // The identity the reply carries, as rmw_fastrtps on Humble makes it: the request's sequence
    // number, with the client's reply reader when the request names it (its related sample
    // identity), else the request's writer.
    rtps::SampleIdentity related = info.sample_identity;
    const rtps::GUID_t & reply_reader = info.related_sample_identity.writer_guid();
    if (reply_reader != rtps::GUID_t::unknown()) {
      related.writer_guid() = reply_reader;
    }
    // A brand-new client's reply reader may not be matched yet: wait for it as Humble does (an
    // entity id whose kind has the reader bit 0x04 names a reader).
    if ((related.writer_guid().entityId.value[3] & 0x04) != 0 &&
      !service.matched->wait_for(related.writer_guid(), std::chrono::duration<double>(options_.reply_wait)))
    {
      say(service.name + ": " + message + "; the client's reply reader " + guid_text(related.writer_guid()) +
        " was not matched within " + std::to_string(options_.reply_wait) +
        " s: no reply (rmw_fastrtps on Humble gives up the same way)");
      return;
    }
    bool written = false;
    if (options_.reply_identity) {
      rtps::WriteParams params;
      params.related_sample_identity(related);
      written = service.replies->write(&reply, params);
    } else {
      written = service.replies->write(&reply);
    }
    const double waited_ms = std::chrono::duration<double, std::milli>(Clock::now() - received).count();
    if (!written) {
      say(service.name + ": " + message + "; the reply could not be written");
      return;
    }
    ++replies_;
    std::ostringstream line;
    // On one machine both clocks are one: how long the request took to arrive after it was written.
    const double in_transit_ms = (info.reception_timestamp.to_ns() - info.source_timestamp.to_ns()) / 1e6;
    line << service.name << ": " << message << " (request #" << sequence << " from " << from
         << ", arrived " << std::fixed << std::setprecision(1) << in_transit_ms << " ms after it was sent"
         << "; reply " << (options_.reply_identity ? "with" : "WITHOUT") << " the request's identity, "
         << waited_ms << " ms after the request)";
    say(line.str());
  }

  void take_goals()
  {
    RawSample sample;
    dds::SampleInfo info;
    while (goal_reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;
      }
      float goal = 0;
      try {
        goal = decode_float32(sample.bytes);
      } catch (const Malformed & error) {
        say(std::string("a goal that is no Float32: ") + error.what());
        continue;
      }
      char text[128];
      std::snprintf(text, sizeof(text), "goal %+.3f rad on %sgoal/position%s", goal, prefix_.c_str(),
        torque_ ? "" : " (torque off: held until setTorqueEnable)");
      say(text);
      if (std::isfinite(goal)) {
        goal_ = goal;
        has_goal_ = true;
      }
    }
  }

  void take_led()
  {
    RawSample sample;
    dds::SampleInfo info;
    while (led_reader_->take_next_sample(&sample, &info) == ReturnCode_t::RETCODE_OK) {
      if (!info.valid_data) {
        continue;
      }
      try {
        const bool on = decode_bool(sample.bytes);
        if (on != led_on_) {
          led_on_ = on;
          say(std::string("LED ") + (on ? "on" : "off"));
        }
      } catch (const Malformed & error) {
        say(std::string("an led message that is no Bool: ") + error.what());
      }
    }
  }

  void publish_imu()
  {
    // A fixed tilt, as humble_twin's IMU: pitched by kPitch about y, gravity measured accordingly.
    const double orientation[4] = {0.0, std::sin(kPitch / 2), 0.0, std::cos(kPitch / 2)};
    const double acceleration[3] = {-9.81 * std::sin(kPitch), 0.0, 9.81 * std::cos(kPitch)};
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    const auto nanoseconds = std::chrono::duration_cast<std::chrono::nanoseconds>(now).count();
    RawSample imu{encode_imu(
        static_cast<int32_t>(nanoseconds / 1000000000), static_cast<uint32_t>(nanoseconds % 1000000000),
        options_.name_space + "_base_link", orientation, acceleration)};
    imu_writer_->write(&imu);
  }

  void publish_joint()
  {
    if (torque_ && has_goal_) {
      const double step = kServoSpeed * period_.count();
      position_ += std::max(-step, std::min(step, goal_ - position_));
    }
    const auto now = std::chrono::system_clock::now().time_since_epoch();
    const auto nanoseconds = std::chrono::duration_cast<std::chrono::nanoseconds>(now).count();
    RawSample joint{encode_joint_state(
        static_cast<int32_t>(nanoseconds / 1000000000), static_cast<uint32_t>(nanoseconds % 1000000000),
        options_.name_space + "_base_link", node_name_, position_)};
    joint_writer_->write(&joint);
  }

  TwinOptions options_;
  std::string prefix_;
  std::string node_name_;
  std::chrono::duration<double> period_;
  int domain_id_ = 0;
  dds::DomainParticipant * participant_ = nullptr;
  dds::Publisher * publisher_ = nullptr;
  dds::Subscriber * subscriber_ = nullptr;
  std::vector<dds::DataReader *> readers_;
  std::vector<dds::DataWriter *> writers_;
  dds::DataReader * discovery_reader_ = nullptr;
  dds::DataWriter * discovery_writer_ = nullptr;
  dds::DataReader * goal_reader_ = nullptr;
  dds::DataReader * led_reader_ = nullptr;
  dds::DataWriter * imu_writer_ = nullptr;
  bool led_on_ = false;
  dds::DataWriter * call_requests_ = nullptr;
  dds::DataReader * call_replies_ = nullptr;
  dds::DataWriter * joint_writer_ = nullptr;
  std::vector<Service> services_;
  Wakeup wakeup_;
  HumbleGid own_gid_{};
  uint64_t received_ = 0;
  uint64_t malformed_ = 0;
  uint64_t replies_ = 0;
  struct Declared
  {
    ParameterValue value;
    std::string description;
  };
  static ParameterValue double_value(double value)
  {
    ParameterValue parameter;
    parameter.type = kDouble;
    parameter.double_value = value;
    return parameter;
  }
  // The servo node's parameters: the position controller's gains (the course's kp, ki, kd; the
  // simulated servo's defaults) and the use_sim_time every node has.
  std::map<std::string, Declared> parameters_{
    {"use_sim_time", {ParameterValue{kBool, false, 0, 0.0, ""}, ""}},
  };
  bool torque_ = false;  // off at boot, as the simulated servo: goals wait for setTorqueEnable
  bool has_goal_ = false;
  double goal_ = 0.0;
  double position_ = 0.0;
};

}  // namespace

int run_twin(const TwinOptions & options, const std::atomic<bool> & stop)
{
  // A Humble module does not read our Fast DDS profile (config/fastdds.xml, set by env.sh): its
  // graph endpoints would land in our partition and its timing would be ours.
  unsetenv("FASTRTPS_DEFAULT_PROFILES_FILE");
  unsetenv("FASTDDS_DEFAULT_PROFILES_FILE");
  setenv("SKIP_DEFAULT_XML", "1", 1);
  std::string error;
  {
    Twin twin(options);
    if (!twin.start(error)) {
      std::fprintf(stderr, "%s: error: %s\n", kPrefix, error.c_str());
      return 1;
    }
    say(twin.ready_line());
    if (!options.call.empty()) {
      twin.call_once(stop);
    }
    twin.run(stop);
    say(twin.summary());
  }
  return 0;
}

}  // namespace owl
