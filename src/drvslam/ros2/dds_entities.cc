#include "drvslam/ros2/dds_entities.h"

#include <cstdlib>
#include <memory>
#include <stdexcept>

namespace drvslam::ros2 {
namespace {

struct QosDeleter {
  void operator()(dds_qos_t* qos) const { dds_delete_qos(qos); }
};
using QosPointer = std::unique_ptr<dds_qos_t, QosDeleter>;

QosPointer MakeQos(TopicQos kind, std::int32_t depth) {
  QosPointer qos(dds_create_qos());
  switch (kind) {
    case TopicQos::kSensorData:
      dds_qset_reliability(qos.get(), DDS_RELIABILITY_BEST_EFFORT, 0);
      dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, depth);
      dds_qset_durability(qos.get(), DDS_DURABILITY_VOLATILE);
      break;
    case TopicQos::kReliable:
      dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, depth);
      dds_qset_durability(qos.get(), DDS_DURABILITY_VOLATILE);
      break;
    case TopicQos::kLatched:
      dds_qset_reliability(qos.get(), DDS_RELIABILITY_RELIABLE, DDS_SECS(1));
      dds_qset_history(qos.get(), DDS_HISTORY_KEEP_LAST, 1);
      dds_qset_durability(qos.get(), DDS_DURABILITY_TRANSIENT_LOCAL);
      break;
  }
  return qos;
}

}  // namespace

void DdsHandle::Reset() {
  if (entity_ > 0) dds_delete(entity_);
  entity_ = 0;
}

dds_domainid_t RosDomainId() {
  const char* text = std::getenv("ROS_DOMAIN_ID");
  if (text == nullptr || *text == '\0') return 0;
  const std::string value(text);
  std::size_t used = 0;
  long domain = -1;
  try {
    domain = std::stol(value, &used);
  } catch (const std::exception&) {
    used = 0;
  }
  // 232 is the largest domain whose ports stay valid with ROS 2's default port mapping.
  if (used != value.size() || domain < 0 || domain > 232) {
    throw Error("ROS_DOMAIN_ID=" + value + ": expected an integer 0..232");
  }
  return static_cast<dds_domainid_t>(domain);
}

dds_entity_t CheckDds(dds_entity_t result, const std::string& what) {
  if (result < 0) throw Error(what + ": " + dds_strretcode(result));
  return result;
}

DdsHandle CreateParticipant(dds_domainid_t domain) {
  return DdsHandle(
      CheckDds(dds_create_participant(domain, nullptr, nullptr),
               "DDS participant on domain " + std::to_string(domain) + " (check CYCLONEDDS_URI)"));
}

DdsHandle CreateTopic(const DdsHandle& participant, const dds_topic_descriptor_t& descriptor,
                      const std::string& ros_topic) {
  std::string dds_name;
  try {
    dds_name = DdsTopicName(ros_topic);
  } catch (const std::invalid_argument& error) {
    throw Error(error.what());
  }
  return DdsHandle(
      CheckDds(dds_create_topic(participant.Get(), &descriptor, dds_name.c_str(), nullptr, nullptr),
               "topic " + ros_topic));
}

DdsHandle CreateReader(const DdsHandle& participant, const DdsHandle& topic, TopicQos qos,
                       std::int32_t depth, const std::string& ros_topic) {
  const QosPointer reader_qos = MakeQos(qos, depth);
  return DdsHandle(
      CheckDds(dds_create_reader(participant.Get(), topic.Get(), reader_qos.get(), nullptr),
               "subscription to " + ros_topic));
}

DdsHandle CreateWriter(const DdsHandle& participant, const DdsHandle& topic, TopicQos qos,
                       std::int32_t depth, const std::string& ros_topic) {
  const QosPointer writer_qos = MakeQos(qos, depth);
  return DdsHandle(
      CheckDds(dds_create_writer(participant.Get(), topic.Get(), writer_qos.get(), nullptr),
               "publisher of " + ros_topic));
}

DataWaiter::DataWaiter(const DdsHandle& participant)
    : waitset_(CheckDds(dds_create_waitset(participant.Get()), "DDS waitset")) {}

void DataWaiter::Attach(dds_entity_t reader) {
  DdsHandle condition(
      CheckDds(dds_create_readcondition(reader, DDS_ANY_STATE), "DDS read condition"));
  CheckDds(dds_waitset_attach(waitset_.Get(), condition.Get(), 0), "attaching a read condition");
  conditions_.push_back(std::move(condition));
}

bool DataWaiter::Wait(dds_duration_t timeout) {
  return CheckDds(dds_waitset_wait(waitset_.Get(), nullptr, 0, timeout), "waiting for data") > 0;
}

}  // namespace drvslam::ros2
