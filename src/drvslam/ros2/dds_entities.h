// Cyclone DDS entities as C++ objects for the ROS 2 node: a handle that deletes its entity, the
// domain ROS 2 would join (ROS_DOMAIN_ID), the two QoS profiles drvslam uses, and typed readers
// and writers of the message types of ros2_msgs.h. Every failing call throws drvslam::Error
// naming the topic and Cyclone's reason.
#pragma once

#include <cstdint>
#include <functional>
#include <string>
#include <utility>
#include <vector>

#include "dds/dds.h"
#include "drvslam/core/error.h"
#include "drvslam/ros2/ros2_msgs.h"

namespace drvslam::ros2 {

// Owns one DDS entity (participant, topic, reader, writer, waitset, condition) and deletes it,
// with its children, when destroyed.
class DdsHandle {
 public:
  DdsHandle() = default;
  explicit DdsHandle(dds_entity_t entity) : entity_(entity) {}
  ~DdsHandle() { Reset(); }
  DdsHandle(DdsHandle&& other) noexcept : entity_(std::exchange(other.entity_, 0)) {}
  DdsHandle& operator=(DdsHandle&& other) noexcept {
    if (this != &other) {
      Reset();
      entity_ = std::exchange(other.entity_, 0);
    }
    return *this;
  }
  DdsHandle(const DdsHandle&) = delete;
  DdsHandle& operator=(const DdsHandle&) = delete;

  dds_entity_t Get() const { return entity_; }
  void Reset();

 private:
  dds_entity_t entity_ = 0;
};

// ROS_DOMAIN_ID as ROS 2 reads it: unset or empty is domain 0; otherwise an integer 0..232.
// Throws Error naming the variable and its value otherwise.
dds_domainid_t RosDomainId();

// Throws Error "`what`: Cyclone's reason" when `result` is a DDS error code (negative).
dds_entity_t CheckDds(dds_entity_t result, const std::string& what);

// How a topic is read or written (each maps onto ROS 2's QoS profile of the same name).
enum class TopicQos {
  // Best effort, keep last `depth`, volatile: matches both sensor-data and default publishers.
  kSensorData,
  // Reliable, keep last `depth`, volatile: ROS 2's default profile.
  kReliable,
  // Reliable, keep last 1, transient local: a late subscriber still gets the last sample (the
  // map_server convention for maps).
  kLatched,
};

// A participant on `domain`; Cyclone's configuration (CYCLONEDDS_URI) applies.
DdsHandle CreateParticipant(dds_domainid_t domain);

// The DDS topic of ROS 2 topic `ros_topic` (DdsTopicName) with message type `descriptor`.
DdsHandle CreateTopic(const DdsHandle& participant, const dds_topic_descriptor_t& descriptor,
                      const std::string& ros_topic);

DdsHandle CreateReader(const DdsHandle& participant, const DdsHandle& topic, TopicQos qos,
                       std::int32_t depth, const std::string& ros_topic);
DdsHandle CreateWriter(const DdsHandle& participant, const DdsHandle& topic, TopicQos qos,
                       std::int32_t depth, const std::string& ros_topic);

// Publishes messages of one type on one ROS 2 topic.
template <typename Message>
class TopicWriter {
 public:
  TopicWriter(const DdsHandle& participant, const std::string& ros_topic, TopicQos qos,
              std::int32_t depth = 10)
      : ros_topic_(ros_topic),
        topic_(CreateTopic(participant, MessageTraits<Message>::Descriptor(), ros_topic)),
        writer_(CreateWriter(participant, topic_, qos, depth, ros_topic)) {}

  void Write(const Message& message) {
    CheckDds(dds_write(writer_.Get(), &message), "writing " + ros_topic_);
    ++written_;
  }
  // Readers matched so far (ROS 2 subscriptions of this topic).
  std::uint32_t Subscribers() const {
    dds_publication_matched_status_t status{};
    CheckDds(dds_get_publication_matched_status(writer_.Get(), &status),
             "matched status of " + ros_topic_);
    return status.current_count;
  }
  // Waits up to `timeout` for every matched reliable reader to acknowledge what was written;
  // false when it ran out.
  bool WaitForAcknowledgements(dds_duration_t timeout) {
    return dds_wait_for_acks(writer_.Get(), timeout) == DDS_RETCODE_OK;
  }
  std::size_t Written() const { return written_; }
  const std::string& RosTopic() const { return ros_topic_; }

 private:
  std::string ros_topic_;
  DdsHandle topic_;
  DdsHandle writer_;
  std::size_t written_ = 0;
};

// Takes messages of one type from one ROS 2 topic. Take() hands each valid sample to a callback
// while the sample is loaned from the reader (copy what is kept).
template <typename Message>
class TopicReader {
 public:
  TopicReader(const DdsHandle& participant, const std::string& ros_topic, TopicQos qos,
              std::int32_t depth)
      : ros_topic_(ros_topic),
        topic_(CreateTopic(participant, MessageTraits<Message>::Descriptor(), ros_topic)),
        reader_(CreateReader(participant, topic_, qos, depth, ros_topic)) {}

  // Takes every waiting sample, oldest first; returns how many valid ones it handed over.
  std::size_t Take(const std::function<void(const Message&)>& use) {
    constexpr std::size_t kBatch = 16;
    std::size_t taken = 0;
    for (;;) {
      void* samples[kBatch] = {};
      dds_sample_info_t infos[kBatch];
      const dds_return_t count = dds_take(reader_.Get(), samples, infos, kBatch, kBatch);
      CheckDds(count, "taking from " + ros_topic_);
      if (count == 0) return taken;
      struct Loan {
        dds_entity_t reader;
        void** samples;
        dds_return_t count;
        ~Loan() { dds_return_loan(reader, samples, count); }
      } loan{reader_.Get(), samples, count};
      for (dds_return_t i = 0; i < count; ++i) {
        if (!infos[i].valid_data) continue;
        use(*static_cast<const Message*>(samples[i]));
        ++taken;
      }
      if (static_cast<std::size_t>(count) < kBatch) return taken;
    }
  }
  // Writers matched so far (ROS 2 publishers of this topic).
  std::uint32_t Publishers() const {
    dds_subscription_matched_status_t status{};
    CheckDds(dds_get_subscription_matched_status(reader_.Get(), &status),
             "matched status of " + ros_topic_);
    return status.current_count;
  }
  dds_entity_t Entity() const { return reader_.Get(); }
  const std::string& RosTopic() const { return ros_topic_; }

 private:
  std::string ros_topic_;
  DdsHandle topic_;
  DdsHandle reader_;
};

// Blocks until any of the attached readers has data, or the timeout passes.
class DataWaiter {
 public:
  explicit DataWaiter(const DdsHandle& participant);
  void Attach(dds_entity_t reader);
  // False when the timeout passed with nothing to read.
  bool Wait(dds_duration_t timeout);

 private:
  DdsHandle waitset_;
  std::vector<DdsHandle> conditions_;
};

}  // namespace drvslam::ros2
