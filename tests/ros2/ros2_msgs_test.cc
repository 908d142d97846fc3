// The ROS 2 message types against the wire format a ROS 2 node expects: each sample goes through
// Cyclone DDS's own serializer (a writer and a reader on one participant, the reader's serialized
// sample read back) and the bytes must equal a CDR layout written out here by hand: XCDR1 little
// endian, encapsulation header 00 01 00 0p (p: the padding bytes Cyclone adds to reach a multiple
// of 4), primitives aligned to their size (doubles to 8) counted from the end of that header,
// strings and sequences with a 4-byte length first. Also the registered DDS type names and
// ROS 2's rt/ topic names.
#include "drvslam/ros2/ros2_msgs.h"

#include <gtest/gtest.h>

#include <cstdint>
#include <cstdlib>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "dds/dds.h"
#include "dds/ddsi/ddsi_serdata.h"

namespace drvslam::ros2 {
namespace {

using Bytes = std::vector<std::uint8_t>;

// Loopback only, no multicast, a domain nobody else is likely to use: the test sends nothing
// beyond this machine and meets no other participant.
constexpr dds_domainid_t kDomain = 171;
constexpr const char* kLoopbackConfig =
    "<CycloneDDS><Domain><General><Interfaces><NetworkInterface name=\"lo\"/></Interfaces>"
    "<AllowMulticast>false</AllowMulticast></General></Domain></CycloneDDS>";

// The expected bytes, built field by field with the alignment rules above.
class Cdr {
 public:
  Cdr() : bytes_{0x00, 0x01, 0x00, 0x00} {}

  void Octet(std::uint8_t value) { bytes_.push_back(value); }
  void Bool(bool value) { Octet(value ? 1 : 0); }
  void U32(std::uint32_t value) { Put(value, 4); }
  void I32(std::int32_t value) { Put(static_cast<std::uint32_t>(value), 4); }
  void F32(float value) {
    std::uint32_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    Put(bits, 4);
  }
  void F64(double value) {
    std::uint64_t bits = 0;
    std::memcpy(&bits, &value, sizeof bits);
    Put(bits, 8);
  }
  // Length including the terminating NUL, the characters, the NUL.
  void String(const std::string& text) {
    U32(static_cast<std::uint32_t>(text.size() + 1));
    for (char c : text) {
      Octet(static_cast<std::uint8_t>(c));
    }
    Octet(0);
  }
  void OctetSequence(const Bytes& data) {
    U32(static_cast<std::uint32_t>(data.size()));
    bytes_.insert(bytes_.end(), data.begin(), data.end());
  }

  void Time(std::int32_t sec, std::uint32_t nanosec) {
    I32(sec);
    U32(nanosec);
  }
  void Header(std::int32_t sec, std::uint32_t nanosec, const std::string& frame_id) {
    Time(sec, nanosec);
    String(frame_id);
  }
  void Doubles(const std::vector<double>& values) {
    for (double value : values) {
      F64(value);
    }
  }

  // Cyclone DDS pads the payload to a multiple of 4 bytes and, as XTypes 1.3 (7.6.3.1.2) asks,
  // says how many padding bytes it added in the low two bits of the options field.
  Bytes Finish() const {
    Bytes out = bytes_;
    const std::size_t padding = (4 - out.size() % 4) % 4;
    out.resize(out.size() + padding, 0);
    out[3] = static_cast<std::uint8_t>(padding);
    return out;
  }

 private:
  // Little endian, aligned to `size` counted from the end of the encapsulation header.
  void Put(std::uint64_t value, std::size_t size) {
    while ((bytes_.size() - 4) % size != 0) {
      bytes_.push_back(0);
    }
    for (std::size_t i = 0; i < size; ++i) {
      bytes_.push_back(static_cast<std::uint8_t>(value >> (8 * i)));
    }
  }

  Bytes bytes_;
};

char* Text(const char* text) { return const_cast<char*>(text); }

std_msgs_msg_dds__Header_ MakeHeader(std::int32_t sec, std::uint32_t nanosec, const char* frame) {
  std_msgs_msg_dds__Header_ header{};
  header.stamp.sec = sec;
  header.stamp.nanosec = nanosec;
  header.frame_id = Text(frame);
  return header;
}

geometry_msgs_msg_dds__Pose_ MakePose(double x, double y, double z) {
  geometry_msgs_msg_dds__Pose_ pose{};
  pose.position = {x, y, z};
  pose.orientation = {0.0, 0.0, 0.6, 0.8};
  return pose;
}

void ExpectPose(Cdr& cdr, double x, double y, double z) {
  cdr.Doubles({x, y, z, 0.0, 0.0, 0.6, 0.8});
}

class Ros2MsgsTest : public ::testing::Test {
 protected:
  static void SetUpTestSuite() {
    ASSERT_EQ(setenv("CYCLONEDDS_URI", kLoopbackConfig, 1), 0);
    participant_ = dds_create_participant(kDomain, nullptr, nullptr);
    ASSERT_GT(participant_, 0) << dds_strretcode(participant_);
  }
  static void TearDownTestSuite() {
    if (participant_ > 0) {
      dds_delete(participant_);
    }
    participant_ = 0;
  }

  // What Cyclone DDS puts on the wire for `sample` on the ROS 2 topic `ros_topic`; also checks
  // the topic's DDS name and registered type name.
  template <typename Message>
  static Bytes Serialize(const Message& sample, const std::string& ros_topic,
                         const std::string& type_name) {
    const dds_entity_t topic = dds_create_topic(participant_, &MessageTraits<Message>::Descriptor(),
                                                DdsTopicName(ros_topic).c_str(), nullptr, nullptr);
    EXPECT_GT(topic, 0) << dds_strretcode(topic);
    char name[256] = {};
    // Both return the name's length.
    EXPECT_GT(dds_get_name(topic, name, sizeof name), 0);
    EXPECT_EQ(std::string(name), "rt" + ros_topic);
    EXPECT_GT(dds_get_type_name(topic, name, sizeof name), 0);
    EXPECT_EQ(std::string(name), type_name);

    const dds_entity_t reader = dds_create_reader(participant_, topic, nullptr, nullptr);
    const dds_entity_t writer = dds_create_writer(participant_, topic, nullptr, nullptr);
    EXPECT_GT(reader, 0);
    EXPECT_GT(writer, 0);
    EXPECT_EQ(dds_write(writer, &sample), DDS_RETCODE_OK);
    // Delivery to a reader of the same participant is synchronous: the sample is there now.
    ddsi_serdata* serdata = nullptr;
    dds_sample_info_t info{};
    Bytes bytes;
    if (dds_takecdr(reader, &serdata, 1, &info, DDS_ANY_STATE) == 1) {
      bytes.resize(ddsi_serdata_size(serdata));
      ddsi_serdata_to_ser(serdata, 0, bytes.size(), bytes.data());
      ddsi_serdata_unref(serdata);
    } else {
      ADD_FAILURE() << "no sample received on " << ros_topic;
    }
    dds_delete(writer);
    dds_delete(reader);
    dds_delete(topic);
    return bytes;
  }

  static dds_entity_t participant_;
};

dds_entity_t Ros2MsgsTest::participant_ = 0;

TEST(DdsTopicNameTest, AddsTheRtPrefix) {
  EXPECT_EQ(DdsTopicName("/camera/color/image_raw"), "rt/camera/color/image_raw");
  EXPECT_EQ(DdsTopicName("/tf"), "rt/tf");
  // Relative names resolve against the root namespace.
  EXPECT_EQ(DdsTopicName("odom"), "rt/odom");
  EXPECT_EQ(DdsTopicName("map_2/grid"), "rt/map_2/grid");
}

TEST(DdsTopicNameTest, RejectsWhatRos2Rejects) {
  for (const char* bad :
       {"", "/", "//tf", "/a//b", "/tf/", "~/odom", "/cam-1", "/2d/grid", "/a/9b", "/a b"}) {
    EXPECT_THROW(DdsTopicName(bad), std::invalid_argument) << bad;
  }
}

TEST(MessageTraitsTest, NamesMatchRos2) {
  EXPECT_STREQ(MessageTraits<sensor_msgs_msg_dds__Image_>::Descriptor().m_typename,
               "sensor_msgs::msg::dds_::Image_");
  EXPECT_STREQ(MessageTraits<sensor_msgs_msg_dds__Image_>::kRosName, "sensor_msgs/msg/Image");
  EXPECT_STREQ(MessageTraits<tf2_msgs_msg_dds__TFMessage_>::Descriptor().m_typename,
               "tf2_msgs::msg::dds_::TFMessage_");
  EXPECT_STREQ(MessageTraits<nav_msgs_msg_dds__OccupancyGrid_>::kRosName,
               "nav_msgs/msg/OccupancyGrid");
  EXPECT_STREQ(geometry_msgs_msg_dds__TwistWithCovariance__desc.m_typename,
               "geometry_msgs::msg::dds_::TwistWithCovariance_");
  EXPECT_STREQ(sensor_msgs_msg_dds__RegionOfInterest__desc.m_typename,
               "sensor_msgs::msg::dds_::RegionOfInterest_");
  EXPECT_STREQ(nav_msgs_msg_dds__MapMetaData__desc.m_typename, "nav_msgs::msg::dds_::MapMetaData_");
  EXPECT_STREQ(builtin_interfaces_msg_dds__Time__desc.m_typename,
               "builtin_interfaces::msg::dds_::Time_");
}

TEST_F(Ros2MsgsTest, Header) {
  const std_msgs_msg_dds__Header_ header = MakeHeader(1, 2, "map");
  // Written out in full once, to pin the helper: sec, nanosec, length 4, "map\0".
  const Bytes expected = {0x00, 0x01, 0x00, 0x00, 0x01, 0x00, 0x00, 0x00, 0x02, 0x00,
                          0x00, 0x00, 0x04, 0x00, 0x00, 0x00, 'm',  'a',  'p',  0x00};
  Cdr cdr;
  cdr.Header(1, 2, "map");
  EXPECT_EQ(cdr.Finish(), expected);
  EXPECT_EQ(Serialize(header, "/header", "std_msgs::msg::dds_::Header_"), expected);
}

TEST_F(Ros2MsgsTest, Image) {
  Bytes pixels = {10, 20, 30, 40, 50, 60};
  sensor_msgs_msg_dds__Image_ image{};
  image.header = MakeHeader(1700000000, 123456789, "camera_color_optical_frame");
  image.height = 1;
  image.width = 2;
  image.encoding = Text("rgb8");
  image.is_bigendian = 0;
  image.step = 6;
  image.data = BorrowSequence<dds_sequence_octet>(pixels);

  Cdr cdr;
  cdr.Header(1700000000, 123456789, "camera_color_optical_frame");  // 27 bytes: height pads 1
  cdr.U32(1);
  cdr.U32(2);
  cdr.String("rgb8");
  cdr.Octet(0);
  cdr.U32(6);  // after 3 padding bytes
  cdr.OctetSequence(pixels);
  const Bytes expected = cdr.Finish();
  EXPECT_EQ(expected[3], 2);  // 54 payload bytes: 2 of padding
  EXPECT_EQ(Serialize(image, "/camera/color/image_raw", "sensor_msgs::msg::dds_::Image_"),
            expected);
}

TEST_F(Ros2MsgsTest, CameraInfo) {
  std::vector<double> d = {0.1, -0.2, 0.001, 0.002, 0.05};
  sensor_msgs_msg_dds__CameraInfo_ info{};
  info.header = MakeHeader(5, 6, "cam");
  info.height = 480;
  info.width = 640;
  info.distortion_model = Text("plumb_bob");
  info.d = BorrowSequence<dds_sequence_double>(d);
  const double k[9] = {525.0, 0.0, 319.5, 0.0, 525.0, 239.5, 0.0, 0.0, 1.0};
  const double r[9] = {1.0, 0.0, 0.0, 0.0, 1.0, 0.0, 0.0, 0.0, 1.0};
  const double p[12] = {525.0, 0.0, 319.5, 0.0, 0.0, 525.0, 239.5, 0.0, 0.0, 0.0, 1.0, 0.0};
  std::memcpy(info.k, k, sizeof k);
  std::memcpy(info.r, r, sizeof r);
  std::memcpy(info.p, p, sizeof p);
  info.binning_x = 1;
  info.binning_y = 2;
  info.roi = {3, 4, 100, 200, true};

  Cdr cdr;
  cdr.Header(5, 6, "cam");
  cdr.U32(480);
  cdr.U32(640);
  cdr.String("plumb_bob");
  cdr.U32(5);  // d's length, then its doubles from the next multiple of 8
  cdr.Doubles(d);
  cdr.Doubles(std::vector<double>(k, k + 9));
  cdr.Doubles(std::vector<double>(r, r + 9));
  cdr.Doubles(std::vector<double>(p, p + 12));
  cdr.U32(1);
  cdr.U32(2);
  for (std::uint32_t value : {3u, 4u, 100u, 200u}) {
    cdr.U32(value);
  }
  cdr.Bool(true);
  EXPECT_EQ(Serialize(info, "/camera/color/camera_info", "sensor_msgs::msg::dds_::CameraInfo_"),
            cdr.Finish());
}

TEST_F(Ros2MsgsTest, PointCloud2) {
  std::vector<sensor_msgs_msg_dds__PointField_> fields = {
      {Text("x"), 0, point_field::kFloat32, 1},
      {Text("y"), 4, point_field::kFloat32, 1},
      {Text("z"), 8, point_field::kFloat32, 1},
      {Text("rgb"), 12, point_field::kUint32, 1}};
  Bytes points(2 * 16);
  for (std::size_t i = 0; i < points.size(); ++i) {
    points[i] = static_cast<std::uint8_t>(i * 7);
  }
  sensor_msgs_msg_dds__PointCloud2_ cloud{};
  cloud.header = MakeHeader(9, 10, "map");
  cloud.height = 1;
  cloud.width = 2;
  cloud.fields = BorrowSequence<dds_sequence_sensor_msgs_msg_dds__PointField_>(fields);
  cloud.is_bigendian = false;
  cloud.point_step = 16;
  cloud.row_step = 32;
  cloud.data = BorrowSequence<dds_sequence_octet>(points);
  cloud.is_dense = true;

  Cdr cdr;
  cdr.Header(9, 10, "map");
  cdr.U32(1);
  cdr.U32(2);
  cdr.U32(4);
  const char* names[] = {"x", "y", "z", "rgb"};
  for (std::size_t i = 0; i < 4; ++i) {
    cdr.String(names[i]);
    cdr.U32(static_cast<std::uint32_t>(4 * i));
    cdr.Octet(i < 3 ? 7 : 6);
    cdr.U32(1);
  }
  cdr.Bool(false);
  cdr.U32(16);
  cdr.U32(32);
  cdr.OctetSequence(points);
  cdr.Bool(true);
  EXPECT_EQ(Serialize(cloud, "/drvslam/dense_map", "sensor_msgs::msg::dds_::PointCloud2_"),
            cdr.Finish());
}

TEST_F(Ros2MsgsTest, Odometry) {
  nav_msgs_msg_dds__Odometry_ odometry{};
  odometry.header = MakeHeader(11, 12, "odom");
  odometry.child_frame_id = Text("camera_link");
  odometry.pose.pose = MakePose(1.5, -2.25, 0.125);
  std::vector<double> covariance(36);
  for (std::size_t i = 0; i < covariance.size(); ++i) {
    covariance[i] = 0.01 * static_cast<double>(i);
    odometry.pose.covariance[i] = covariance[i];
    odometry.twist.covariance[i] = -covariance[i];
  }
  odometry.twist.twist.linear = {0.5, 0.0, -0.5};
  odometry.twist.twist.angular = {0.0, 0.1, 0.0};

  Cdr cdr;
  cdr.Header(11, 12, "odom");  // ends at 4+4+4+5 = 17
  cdr.String("camera_link");   // 20 + 4 + 12 = 36: the pose starts at 40
  ExpectPose(cdr, 1.5, -2.25, 0.125);
  cdr.Doubles(covariance);
  cdr.Doubles({0.5, 0.0, -0.5, 0.0, 0.1, 0.0});
  for (double value : covariance) {
    cdr.F64(-value);
  }
  EXPECT_EQ(Serialize(odometry, "/drvslam/odom", "nav_msgs::msg::dds_::Odometry_"), cdr.Finish());
}

TEST_F(Ros2MsgsTest, PoseStamped) {
  geometry_msgs_msg_dds__PoseStamped_ pose{};
  pose.header = MakeHeader(13, 14, "map");
  pose.pose = MakePose(0.25, 0.5, 0.75);

  Cdr cdr;
  cdr.Header(13, 14, "map");  // 16 bytes: the pose starts at 16 with no padding
  ExpectPose(cdr, 0.25, 0.5, 0.75);
  EXPECT_EQ(Serialize(pose, "/drvslam/pose", "geometry_msgs::msg::dds_::PoseStamped_"),
            cdr.Finish());
}

TEST_F(Ros2MsgsTest, TFMessage) {
  std::vector<geometry_msgs_msg_dds__TransformStamped_> transforms(2);
  transforms[0].header = MakeHeader(15, 16, "map");
  transforms[0].child_frame_id = Text("odom");
  transforms[0].transform.translation = {1.0, 2.0, 3.0};
  transforms[0].transform.rotation = {0.0, 0.0, 0.0, 1.0};
  transforms[1].header = MakeHeader(15, 16, "odom");
  transforms[1].child_frame_id = Text("camera_color_optical_frame");
  transforms[1].transform.translation = {-1.0, 0.5, 0.0};
  transforms[1].transform.rotation = {0.5, -0.5, 0.5, -0.5};
  tf2_msgs_msg_dds__TFMessage_ message{};
  message.transforms =
      BorrowSequence<dds_sequence_geometry_msgs_msg_dds__TransformStamped_>(transforms);

  Cdr cdr;
  cdr.U32(2);
  cdr.Header(15, 16, "map");
  cdr.String("odom");
  cdr.Doubles({1.0, 2.0, 3.0, 0.0, 0.0, 0.0, 1.0});
  cdr.Header(15, 16, "odom");
  cdr.String("camera_color_optical_frame");
  cdr.Doubles({-1.0, 0.5, 0.0, 0.5, -0.5, 0.5, -0.5});
  EXPECT_EQ(Serialize(message, "/tf", "tf2_msgs::msg::dds_::TFMessage_"), cdr.Finish());
}

TEST_F(Ros2MsgsTest, OccupancyGrid) {
  std::vector<std::int8_t> cells = {-1, 0, 100, 0, -1, 100, 50};
  nav_msgs_msg_dds__OccupancyGrid_ grid{};
  grid.header = MakeHeader(17, 18, "map");
  grid.info.map_load_time = {19, 20};
  grid.info.resolution = 0.05f;
  grid.info.width = 7;
  grid.info.height = 1;
  grid.info.origin = MakePose(-3.0, -2.0, 0.0);
  grid.data = BorrowSequence<dds_sequence_int8>(cells);

  Cdr cdr;
  cdr.Header(17, 18, "map");
  cdr.Time(19, 20);
  cdr.F32(0.05f);
  cdr.U32(7);
  cdr.U32(1);  // ends at 36: the origin's doubles start at 40
  ExpectPose(cdr, -3.0, -2.0, 0.0);
  cdr.U32(7);
  for (std::int8_t cell : cells) {
    cdr.Octet(static_cast<std::uint8_t>(cell));
  }
  EXPECT_EQ(Serialize(grid, "/map", "nav_msgs::msg::dds_::OccupancyGrid_"), cdr.Finish());
}

}  // namespace
}  // namespace drvslam::ros2
