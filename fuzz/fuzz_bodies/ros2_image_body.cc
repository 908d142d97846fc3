// Input layout (FuzzInput, little-endian):
//   byte kind: even = sensor_msgs/Image, odd = sensor_msgs/CameraInfo
//   Image:      u32 height, u32 width, u8 is_bigendian, u32 step, encoding (length byte, up to 32
//               bytes), then the pixel data: every byte left, whatever the sizes say.
//   CameraInfo: u32 height, u32 width, distortion model (length byte, up to 32 bytes),
//               u8 count of D (up to 15), then D, K[9], R[9], P[12] as float64 and
//               u32 binning_x, binning_y.
// A message the DDS reader hands over has a data length that matches its buffer, so the body
// sets _length to the bytes present and leaves every size field free.
#include <vector>

#include "drvslam/ros2/image_messages.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/fuzz_input.h"
#include "fuzz_bodies/rejection.h"

namespace drvslam::fuzz {
namespace {

constexpr std::size_t kMaxTextLength = 32;
constexpr std::uint8_t kMaxDistortionCoefficients = 15;

void RunImage(FuzzInput& in) {
  sensor_msgs_msg_dds__Image_ image{};
  image.height = in.U32();
  image.width = in.U32();
  image.is_bigendian = in.Byte();
  image.step = in.U32();
  std::string encoding = in.ShortString(kMaxTextLength);
  image.encoding = encoding.data();
  std::vector<std::uint8_t> data = in.Rest();
  image.data._buffer = data.data();
  image.data._length = static_cast<std::uint32_t>(data.size());
  image.data._maximum = image.data._length;
  AllowRejection([&] { ros2::ColourImage(image, "/fuzz/colour"); });
  AllowRejection([&] { ros2::DepthImageMetres(image, "/fuzz/depth"); });
}

void RunCameraInfo(FuzzInput& in) {
  sensor_msgs_msg_dds__CameraInfo_ info{};
  info.height = in.U32();
  info.width = in.U32();
  std::string model = in.ShortString(kMaxTextLength);
  info.distortion_model = model.data();
  std::vector<double> d(in.Byte() % (kMaxDistortionCoefficients + 1));
  for (double& value : d) value = in.Double();
  info.d._buffer = d.data();
  info.d._length = static_cast<std::uint32_t>(d.size());
  info.d._maximum = info.d._length;
  for (double& value : info.k) value = in.Double();
  for (double& value : info.r) value = in.Double();
  for (double& value : info.p) value = in.Double();
  info.binning_x = in.U32();
  info.binning_y = in.U32();
  AllowRejection([&] { ros2::CameraFromInfo(info, CameraOptions(), "/fuzz/camera_info"); });
}

}  // namespace

void RunRos2ImageBody(const std::uint8_t* data, std::size_t size) {
  FuzzInput in(data, size);
  if (in.Byte() % 2 == 0) {
    RunImage(in);
  } else {
    RunCameraInfo(in);
  }
}

}  // namespace drvslam::fuzz
