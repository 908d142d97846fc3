// The first byte picks the reader (modulo 6) and whether an empty trajectory is allowed
// (bit 3 of the byte, for the trajectory readers); the rest is the file, or for the dataset
// and the KITTI times file several files separated by kFileSeparator:
//   0  TumDataset over a folder: rgb.txt, depth.txt, groundtruth.txt, associations.txt (a file
//      not given is absent; the lists are read, the images are not)
//   1  ReadTumTrajectory (groundtruth.txt, estimated trajectories)
//   2  ReadTrajectory with the format detected, as `drvslam eval` without --format: the pose
//      file, then the KITTI times file
//   3, 4, 5  ReadTrajectory as tum, kitti, euroc (`drvslam eval --format`), files as in 2
#include <string>
#include <vector>

#include "drvslam/io/trajectory_formats.h"
#include "drvslam/io/tum_dataset.h"
#include "fuzz_bodies/fuzz_bodies.h"
#include "fuzz_bodies/fuzz_input.h"
#include "fuzz_bodies/rejection.h"
#include "fuzz_bodies/scratch_file.h"

namespace drvslam::fuzz {
namespace {

const std::string kFileSeparator = "\n--8<--\n";

// Writes the given pieces under `names` (relative to the scratch folder); names without a piece
// are removed.
void WriteFiles(const std::vector<std::string>& names, const std::vector<std::string>& pieces) {
  for (std::size_t i = 0; i < names.size(); ++i) {
    if (i < pieces.size()) {
      WriteScratchFile(names[i], pieces[i]);
    } else {
      RemoveScratchFile(names[i]);
    }
  }
}

void RunDataset(const std::uint8_t* data, std::size_t size) {
  const std::vector<std::string> names = {"rgb.txt", "depth.txt", "groundtruth.txt",
                                          "associations.txt"};
  WriteFiles(names, SplitInput(data, size, kFileSeparator, names.size()));
  AllowRejection([] {
    const TumDataset dataset(ScratchFolder());
    double sum = 0.0;
    for (std::size_t i = 0; i < dataset.Size(); ++i) sum += dataset.Timestamp(i);
    for (const StampedPose& pose : dataset.GroundTruth()) sum += pose.timestamp;
    static_cast<void>(sum);
  });
}

void RunTrajectory(const std::uint8_t* data, std::size_t size,
                   std::optional<TrajectoryFormat> format, bool allow_empty) {
  const std::string pose_name = "trajectory.txt";
  const std::string path = ScratchFolder() + "/" + pose_name;
  const std::string times_name = KittiTimesPath(path).substr(ScratchFolder().size() + 1);
  WriteFiles({pose_name, times_name}, SplitInput(data, size, kFileSeparator, 2));
  AllowRejection([&] {
    TrajectoryReadOptions options;
    options.format = format ? format : DetectTrajectoryFormat(path);
    options.allow_empty = allow_empty;
    ReadTrajectory(path, options);
  });
}

}  // namespace

void RunTumTextBody(const std::uint8_t* data, std::size_t size) {
  if (size == 0) return;
  const int reader = data[0] % 6;
  const bool allow_empty = (data[0] & 8) != 0;
  ++data;
  --size;
  switch (reader) {
    case 0:
      RunDataset(data, size);
      break;
    case 1:
      AllowRejection(
          [&] { ReadTumTrajectory(WriteScratchFile("groundtruth.txt", data, size), allow_empty); });
      break;
    case 2:
      RunTrajectory(data, size, std::nullopt, allow_empty);
      break;
    default: {
      const TrajectoryFormat formats[] = {TrajectoryFormat::kTum, TrajectoryFormat::kKitti,
                                          TrajectoryFormat::kEuroc};
      RunTrajectory(data, size, formats[reader - 3], allow_empty);
      break;
    }
  }
}

}  // namespace drvslam::fuzz
