#include "drvslam/tools/synth/synth_sequence.h"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <opencv2/core/utility.hpp>
#include <opencv2/features2d.hpp>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>

#include "drvslam/core/error.h"
#include "drvslam/core/settings.h"
#include "drvslam/core/settings_file.h"
#include "drvslam/io/trajectory_io.h"
#include "drvslam/io/tum_dataset.h"
#include "drvslam/tools/synth/sequence_writer.h"
#include "drvslam/tools/synth/synth_generator.h"
#include "test_folder.h"
#include "test_support/missing_data.h"

namespace drvslam::synth {
namespace {

using testing::ReadFileBytes;
using testing::TestFolder;

SynthOptions SmallSequenceOptions(const std::string& scenario, int frames, int width = 320,
                                  int height = 240) {
  SynthOptions options;
  options.scenario = scenario;
  options.frames = frames;
  options.width = width;
  options.height = height;
  options.seed = 3;
  options.sensor = SensorOptions::Clean();
  return options;
}

const SynthSequence& Walking() {
  static const SynthSequence sequence(SmallSequenceOptions("walking_xyz", 90));
  return sequence;
}

const SynthSequence& Sitting() {
  static const SynthSequence sequence(SmallSequenceOptions("sitting_xyz", 300, 160, 120));
  return sequence;
}

bool IsStatic(const SynthSequence& sequence, int id) {
  return id == 0 || id > sequence.Actors().Count();
}

// Reprojects static pixels of frame `a` into frame `b` through the ground-truth poses and
// compares with frame b's depth, interpolated exactly for a plane (1/z is affine in the image).
// Returns the errors (metres) of the points that are visible in both frames.
std::vector<double> ReprojectionErrors(const SynthSequence& sequence, const cv::Mat& depth_a,
                                       const cv::Mat& ids_a, const cv::Mat& depth_b,
                                       const cv::Mat& ids_b, int a, int b) {
  const PinholeCamera camera(sequence.Camera());
  const SE3 T_bw = sequence.Pose(b).Inverse();
  std::vector<double> errors;
  for (int y = 3; y < depth_a.rows - 3; y += 5) {
    for (int x = 3; x < depth_a.cols - 3; x += 5) {
      const float z = depth_a.at<float>(y, x);
      if (z <= 0.0f || !IsStatic(sequence, ids_a.at<uint16_t>(y, x))) continue;
      const Eigen::Vector3d world = sequence.Pose(a) * camera.Backproject({x, y}, z);
      const Eigen::Vector3d in_b = T_bw * world;
      if (in_b.z() < 0.2) continue;
      const Eigen::Vector2d p = camera.Project(in_b);
      const int x0 = static_cast<int>(std::floor(p.x())), y0 = static_cast<int>(std::floor(p.y()));
      if (x0 < 0 || y0 < 0 || x0 + 1 >= depth_b.cols || y0 + 1 >= depth_b.rows) continue;
      double inverse[2][2];
      bool usable = true;
      for (int dy = 0; dy < 2 && usable; ++dy) {
        for (int dx = 0; dx < 2 && usable; ++dx) {
          const float d = depth_b.at<float>(y0 + dy, x0 + dx);
          usable = d > 0.0f && IsStatic(sequence, ids_b.at<uint16_t>(y0 + dy, x0 + dx));
          inverse[dy][dx] = usable ? 1.0 / d : 0.0;
        }
      }
      // The four neighbours must lie on one plane (affine 1/z).
      if (!usable || std::abs(inverse[0][0] + inverse[1][1] - inverse[0][1] - inverse[1][0]) >
                         1e-4 * inverse[0][0]) {
        continue;
      }
      const double fx = p.x() - x0, fy = p.y() - y0;
      const double predicted =
          1.0 / ((1 - fx) * (1 - fy) * inverse[0][0] + fx * (1 - fy) * inverse[0][1] +
                 (1 - fx) * fy * inverse[1][0] + fx * fy * inverse[1][1]);
      if (in_b.z() > predicted + 0.01) continue;  // hidden behind something in frame b
      errors.push_back(std::abs(predicted - in_b.z()));
    }
  }
  return errors;
}

double Quantile(std::vector<double> values, double q) {
  std::sort(values.begin(), values.end());
  return values[static_cast<std::size_t>(q * (values.size() - 1))];
}

TEST(SynthSequenceTest, StaticPixelsReprojectExactly) {
  const SynthSequence& sequence = Walking();
  const RenderBuffers a = sequence.Render(0);
  const RenderBuffers b = sequence.Render(75);
  const std::vector<double> errors =
      ReprojectionErrors(sequence, a.depth, a.instance, b.depth, b.instance, 0, 75);
  ASSERT_GT(errors.size(), 500u);
  EXPECT_LT(Quantile(errors, 0.5), 1e-5);
  EXPECT_LT(Quantile(errors, 0.99), 5e-4);
  // The camera did move, so this is not trivially true.
  EXPECT_GT((sequence.Pose(0).Translation() - sequence.Pose(75).Translation()).norm(), 0.05);
}

TEST(SynthSequenceTest, ActorHeadsProjectOntoTheirMaskAndMasksComposite) {
  const Rasterizer rasterizer(Walking().Camera());
  int head_checks = 0, actor_pixels = 0;
  for (const SynthSequence* sequence : {&Walking(), &Sitting()}) {
    const PinholeCamera camera(sequence->Camera());
    for (int f = 0; f < std::min(sequence->FrameCount(), 90); f += 6) {
      const RenderBuffers full = sequence->Render(f);
      const SE3 T_cw = sequence->Pose(f).Inverse();
      for (int k = 0; k < sequence->Actors().Count(); ++k) {
        const int id = sequence->Actors().InstanceId(k);
        const TriangleList triangles = sequence->Actors().Triangles(k, f);
        // The head is the sixth box (after four leg parts and the torso): triangles 60..71.
        Eigen::Vector3d head = Eigen::Vector3d::Zero();
        for (int t = 60; t < 72; ++t) {
          for (const Eigen::Vector3d& p : triangles[t].p) head += p / 36.0;
        }
        const Eigen::Vector3d head_c = T_cw * head;
        if (head_c.z() > 0.3) {
          const Eigen::Vector2d p = camera.Project(head_c);
          const int px = static_cast<int>(std::lround(p.x())),
                    py = static_cast<int>(std::lround(p.y()));
          if (px >= 0 && py >= 0 && px < full.depth.cols && py < full.depth.rows &&
              full.depth.at<float>(py, px) > head_c.z() - 0.15) {
            EXPECT_EQ(full.instance.at<uint16_t>(py, px), id) << "frame " << f;
            ++head_checks;
          }
        }
        // Rendered alone, the actor covers a superset of its mask in the full frame, and
        // exactly the pixels where it is the nearest surface.
        if (sequence != &Walking()) continue;
        RenderBuffers alone;
        rasterizer.Render({&triangles}, sequence->Textures(), T_cw, &alone);
        for (int y = 0; y < full.depth.rows; ++y) {
          for (int x = 0; x < full.depth.cols; ++x) {
            const bool in_full = full.instance.at<uint16_t>(y, x) == id;
            const bool in_alone = alone.instance.at<uint16_t>(y, x) == id;
            const float z_full = full.depth.at<float>(y, x), z_alone = alone.depth.at<float>(y, x);
            if (in_full) {
              ASSERT_TRUE(in_alone && z_alone == z_full)
                  << "frame " << f << " at " << x << "," << y;
            } else if (in_alone) {
              ASSERT_GE(z_alone, z_full) << "frame " << f << " at " << x << "," << y;
            }
            actor_pixels += in_full;
          }
        }
      }
    }
  }
  EXPECT_GE(head_checks, 10);
  EXPECT_GT(actor_pixels, 1000);
}

TEST(SynthSequenceTest, WrittenSequenceReadsBackWithTheDatasetReader) {
  TestFolder folder("dataset");
  const SynthOptions options = SmallSequenceOptions("walking_xyz", 5);
  const SynthSummary summary = GenerateSequence(options, folder.Path());
  EXPECT_EQ(summary.frames, 5);
  const SynthSequence& reference = Walking();  // same options but longer: same first frames
  TumDataset dataset(folder.Path());
  ASSERT_EQ(dataset.Size(), 5u);
  ASSERT_TRUE(dataset.HasGroundTruth());
  for (std::size_t i = 0; i < 5; ++i) {
    const RgbdFrame frame = dataset.Read(i);
    EXPECT_NEAR(frame.timestamp, kDefaultStartStamp + i / 30.0, 1e-6);
    EXPECT_NEAR(dataset.GroundTruth()[i].timestamp, frame.timestamp, 1e-9);
    const SE3& truth = reference.Pose(static_cast<int>(i));
    EXPECT_LT((dataset.GroundTruth()[i].T_wc.Translation() - truth.Translation()).norm(), 2e-9);
    EXPECT_LT(RotationAngle(dataset.GroundTruth()[i].T_wc.Inverse() * truth), 1e-8);
    const RenderBuffers exact = reference.Render(static_cast<int>(i));
    EXPECT_EQ(cv::norm(frame.bgr, exact.bgr, cv::NORM_INF), 0.0);
    cv::Mat valid = exact.depth > 0;
    EXPECT_LE(cv::norm(frame.depth, exact.depth, cv::NORM_INF, valid), 0.5 / 5000 + 1e-6);
    const std::string name = SequenceWriter::StampName(frame.timestamp) + ".png";
    EXPECT_EQ(frame.rgb_path.substr(frame.rgb_path.size() - name.size()), name);
    const cv::Mat mask = cv::imread(folder / ("masks/" + name), cv::IMREAD_UNCHANGED);
    ASSERT_EQ(mask.type(), CV_16UC1);
    EXPECT_EQ(cv::norm(mask, exact.instance, cv::NORM_INF), 0.0);
  }
  // The depth files reproject as exactly as their 1/5000 m steps allow.
  const RgbdFrame first = dataset.Read(0), last = dataset.Read(4);
  const std::vector<double> errors =
      ReprojectionErrors(reference, first.depth, reference.Render(0).instance, last.depth,
                         reference.Render(4).instance, 0, 4);
  ASSERT_GT(errors.size(), 500u);
  EXPECT_LT(Quantile(errors, 0.95), 3e-4);

  const InstancesFile instances = ReadInstancesFile(folder / "instances.txt");
  EXPECT_EQ(instances.instances.size(), reference.Instances().size());
  EXPECT_EQ(instances.frame_stamps.size(), 5u);
  EXPECT_EQ(instances.instances[0].class_name, "person");
  const Settings settings = LoadSettings(folder / "settings.yaml");
  EXPECT_DOUBLE_EQ(settings.camera.fx, reference.Camera().fx);
  EXPECT_EQ(settings.camera.width, 320);
  EXPECT_DOUBLE_EQ(settings.depth.depth_map_factor, 5000.0);
  const SettingsFile file(folder / "settings.yaml");
  EXPECT_EQ(file.GetString("Synth.Scenario", ""), "walking_xyz");
  EXPECT_EQ(file.GetString("Synth.StaticCounterpart", ""), "static_xyz");
  EXPECT_EQ(file.GetInt("Synth.Seed", -1), 3);
  EXPECT_EQ(file.GetInt("Synth.DepthNoise", -1), 0);
  const std::string associations = ReadFileBytes(folder / "associations.txt");
  EXPECT_EQ(std::count(associations.begin(), associations.end(), '\n'), 5);
  EXPECT_EQ(associations.substr(0, associations.find('\n')),
            "1305031102.175304 rgb/1305031102.175304.png 1305031102.175304 "
            "depth/1305031102.175304.png");
}

TEST(SynthSequenceTest, SameSeedGivesIdenticalFilesAndAnotherSeedOtherTextures) {
  TestFolder first("seed_a"), second("seed_b"), other("seed_c");
  SynthOptions options = SmallSequenceOptions("walking_rpy", 3, 160, 120);
  options.sensor = SensorOptions();  // noise on: it must repeat too
  GenerateSequence(options, first.Path());
  GenerateSequence(options, second.Path());
  options.seed = 4;
  GenerateSequence(options, other.Path());
  int compared = 0;
  for (const auto& entry : std::filesystem::recursive_directory_iterator(first.Path())) {
    if (!entry.is_regular_file()) continue;
    const std::string relative = std::filesystem::relative(entry.path(), first.Path()).string();
    const std::string bytes = ReadFileBytes(entry.path().string());
    ASSERT_FALSE(bytes.empty()) << relative;
    EXPECT_EQ(bytes, ReadFileBytes(second / relative)) << relative;
    ++compared;
  }
  EXPECT_EQ(compared, 3 * 3 + 6);
  const std::string rgb = "rgb/" + SequenceWriter::StampName(kDefaultStartStamp) + ".png";
  const cv::Mat a = cv::imread(first / rgb), c = cv::imread(other / rgb);
  ASSERT_FALSE(a.empty());
  ASSERT_FALSE(c.empty());
  EXPECT_GT(cv::norm(a, c, cv::NORM_L1) / a.total(), 20.0);
}

TEST(SynthSequenceTest, MovingFlagsFollowTheActors) {
  const SynthSequence& walking = Walking();
  const int actors = walking.Actors().Count();
  ASSERT_EQ(actors, 2);
  int walking_frames = 0, still_frames = 0;
  for (int f = 0; f < walking.FrameCount(); ++f) {
    const std::vector<bool> flags = walking.MovingFlags(f);
    ASSERT_EQ(flags.size(), walking.Instances().size());
    for (std::size_t k = actors; k < flags.size(); ++k) EXPECT_FALSE(flags[k]);
    for (int k = 0; k < actors; ++k) {
      const ActorState& now = walking.Actors().State(k, f);
      const ActorState& before = walking.Actors().State(k, f - 1);
      const double step = (now.position - before.position).norm();
      if (step > 0.01) {
        EXPECT_TRUE(flags[k]) << "actor " << k << " walked " << step << " m in frame " << f;
        ++walking_frames;
      }
      if (step == 0.0 && now.heading == before.heading &&
          now.pose.leg_swing == before.pose.leg_swing && now.pose.sit == before.pose.sit &&
          now.pose.torso_lean == before.pose.torso_lean) {
        EXPECT_FALSE(flags[k]) << "actor " << k << " stood still in frame " << f;
        ++still_frames;
      }
    }
  }
  EXPECT_GT(walking_frames, 30);
  // Seated people move only now and then.
  const SynthSequence& sitting = Sitting();
  int moving = 0, total = 0;
  for (int f = 0; f < sitting.FrameCount(); ++f) {
    for (int k = 0; k < sitting.Actors().Count(); ++k, ++total) moving += sitting.MovingFlags(f)[k];
  }
  EXPECT_GT(moving, total / 20);
  EXPECT_LT(moving, total * 9 / 10);
  (void)still_frames;
}

TEST(SynthSequenceTest, StaticCounterpartIsTheSameWorldWithoutActors) {
  const SynthSequence& walking = Walking();
  const SynthSequence quiet(SmallSequenceOptions("static_xyz", 20));
  for (const SynthInstance& instance : quiet.Instances()) {
    EXPECT_GE(instance.id, kFirstObjectInstanceId);
    EXPECT_NE(instance.class_name, "person");
  }
  EXPECT_EQ(quiet.Actors().Count(), 0);
  EXPECT_EQ(quiet.Instances().size() + 2, walking.Instances().size());
  for (const int f : {0, 12, 19}) {
    EXPECT_EQ(quiet.Pose(f).Translation(), walking.Pose(f).Translation());
    const RenderBuffers a = walking.Render(f), b = quiet.Render(f);
    EXPECT_EQ(quiet.MoverCoverage(b.instance), 0.0);
    const cv::Mat no_actor = (a.instance == 0) | (a.instance >= kFirstObjectInstanceId);
    EXPECT_EQ(cv::norm(a.bgr, b.bgr, cv::NORM_INF, no_actor), 0.0);
    EXPECT_EQ(cv::norm(a.depth, b.depth, cv::NORM_INF, no_actor), 0.0);
  }
  for (int f = 0; f < quiet.FrameCount(); ++f) {
    for (const bool flag : quiet.MovingFlags(f)) EXPECT_FALSE(flag);
  }
}

struct OrbCount {
  std::size_t keypoints = 0;
  int cells = 0;  // of a 4x4 grid
};

OrbCount CountOrb(const cv::Mat& bgr) {
  cv::Mat grey;
  cv::cvtColor(bgr, grey, cv::COLOR_BGR2GRAY);
  std::vector<cv::KeyPoint> keypoints;
  cv::ORB::create(1000)->detect(grey, keypoints);
  int cells[16] = {0};
  for (const cv::KeyPoint& k : keypoints) {
    const int cx = std::min(3, static_cast<int>(k.pt.x * 4 / grey.cols));
    const int cy = std::min(3, static_cast<int>(k.pt.y * 4 / grey.rows));
    ++cells[cy * 4 + cx];
  }
  OrbCount count;
  count.keypoints = keypoints.size();
  for (const int c : cells) count.cells += c > 0;
  return count;
}

TEST(SynthSequenceTest, FramesAreRichInOrbFeatures) {
  for (const bool procedural : {false, true}) {
    SynthOptions options;
    options.scenario = "walking_xyz";
    options.frames = 61;
    options.procedural_textures = procedural;
    const SynthSequence sequence(options);
    for (const int f : {0, 30, 60}) {
      const RenderBuffers frame = sequence.Render(f);
      const OrbCount count = CountOrb(frame.bgr);
      std::printf(
          "[ orb      ] %s textures, frame %d: %zu keypoints, %d of 16 cells, movers %.1f%%\n",
          procedural ? "procedural" : sequence.TextureSource().c_str(), f, count.keypoints,
          count.cells, 100.0 * sequence.MoverCoverage(frame.instance));
      EXPECT_GE(count.keypoints, 800u) << "frame " << f;
      EXPECT_GE(count.cells, 12) << "frame " << f;
    }
    if (procedural) continue;
    // Threads must not change the output (sensor effects included).
    const int threads = cv::getNumThreads();
    cv::setNumThreads(1);
    const RenderBuffers one = sequence.Render(17);
    cv::setNumThreads(4);
    const RenderBuffers many = sequence.Render(17);
    cv::setNumThreads(threads);
    EXPECT_EQ(cv::norm(one.bgr, many.bgr, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(one.depth, many.depth, cv::NORM_INF), 0.0);
    EXPECT_EQ(cv::norm(one.instance, many.instance, cv::NORM_INF), 0.0);
  }
}

TEST(SynthSequenceTest, WorksWithoutPhotographs) {
  SynthOptions options = SmallSequenceOptions("walking_static", 2, 160, 120);
  options.opencv_samples = "/nonexistent/opencv-doc";
  const SynthSequence sequence(options);
  EXPECT_EQ(sequence.TextureSource(), "procedural");
  EXPECT_GT(cv::countNonZero(sequence.Render(1).depth), 160 * 120 * 9 / 10);
}

TEST(SynthSequenceTest, BillboardsCutOutTheirTransparentPart) {
  TestFolder folder("billboards");
  // A 60 x 150 picture whose opaque part is the inscribed ellipse.
  cv::Mat picture(150, 60, CV_8UC4, cv::Scalar(0, 0, 0, 0));
  cv::Mat colours(150, 60, CV_8UC3);
  cv::randu(colours, 0, 255);
  cv::Mat alpha = cv::Mat::zeros(150, 60, CV_8UC1);
  cv::ellipse(alpha, cv::Point(30, 75), cv::Size(30, 75), 0, 0, 360, cv::Scalar(255), cv::FILLED);
  cv::merge(std::vector<cv::Mat>{colours, alpha}, picture);
  cv::imwrite(folder / "person.png", picture);
  // Seated behind the table, the cut-out stands fully in view.
  SynthOptions options = SmallSequenceOptions("sitting_static", 10);
  options.actors = 1;
  options.billboards = folder.Path();
  const SynthSequence sequence(options);
  ASSERT_TRUE(sequence.Actors().IsBillboard(0));
  const Rasterizer rasterizer(sequence.Camera());
  const PinholeCamera camera(sequence.Camera());
  int measured = 0;
  for (int f = 0; f < sequence.FrameCount(); f += 4) {
    const TriangleList quad = sequence.Actors().Triangles(0, f);
    ASSERT_EQ(quad.size(), 2u);
    const SE3 T_cw = sequence.Pose(f).Inverse();
    // Projected quad area (shoelace over its four corners), if it is fully in view.
    const Eigen::Vector3d corners[4] = {quad[0].p[0], quad[0].p[1], quad[0].p[2], quad[1].p[2]};
    double area = 0.0;
    bool inside = true;
    Eigen::Vector2d pixels[4];
    for (int c = 0; c < 4; ++c) {
      const Eigen::Vector3d p = T_cw * corners[c];
      pixels[c] = camera.Project(p);
      inside = inside && p.z() > 0.3 && camera.InImage(pixels[c]);
    }
    if (!inside) continue;
    for (int c = 0; c < 4; ++c) {
      area += pixels[c].x() * pixels[(c + 1) % 4].y() - pixels[(c + 1) % 4].x() * pixels[c].y();
    }
    area = std::abs(0.5 * area);
    if (area < 2000.0) continue;
    RenderBuffers alone;
    rasterizer.Render({&quad}, sequence.Textures(), T_cw, &alone);
    const double covered = cv::countNonZero(alone.instance);
    EXPECT_NEAR(covered / area, M_PI / 4.0, 0.04) << "frame " << f;
    // Transparent pixels have no depth either.
    EXPECT_EQ(cv::countNonZero(alone.depth), covered);
    ++measured;
  }
  EXPECT_GT(measured, 0);

  cv::imwrite(folder / "person.png", colours);  // no alpha channel
  EXPECT_THROW(SynthSequence sequence2(options), Error);
}

TEST(SynthSequenceTest, ReplaysATumRecording) {
  const std::string file = std::string(DRVSLAM_SHARED_DIR) +
                           "/tum-groundtruth/rgbd_dataset_freiburg3_walking_xyz/groundtruth.txt";
  if (!std::filesystem::exists(file)) DRVSLAM_MISSING_TEST_DATA() << "missing " << file;
  SynthOptions options = SmallSequenceOptions("walking_xyz", 12, 160, 120);
  options.trajectory = file;
  const SynthSequence sequence(options);
  const Trajectory recorded = ReadTumTrajectory(file);
  ASSERT_EQ(sequence.FrameCount(), 12);
  EXPECT_DOUBLE_EQ(sequence.Stamp(0), recorded.front().timestamp);
  // Relative motion is the recording's, interpolated at the frame times.
  const auto recorded_at = [&](double stamp) {
    std::size_t i = 1;
    while (recorded[i].timestamp < stamp) ++i;
    const double alpha =
        (stamp - recorded[i - 1].timestamp) / (recorded[i].timestamp - recorded[i - 1].timestamp);
    return SE3(
        recorded[i - 1].T_wc.Quaternion().slerp(alpha, recorded[i].T_wc.Quaternion()),
        (1 - alpha) * recorded[i - 1].T_wc.Translation() + alpha * recorded[i].T_wc.Translation());
  };
  const SE3 start = recorded_at(sequence.Stamp(0));
  for (int f = 1; f < 12; ++f) {
    EXPECT_NEAR(sequence.Stamp(f) - sequence.Stamp(0), f / 30.0, 1e-6);
    const SE3 expected = start.Inverse() * recorded_at(sequence.Stamp(f));
    const SE3 actual = sequence.Pose(0).Inverse() * sequence.Pose(f);
    // Stamps near 1.3e9 s carry 2.4e-7 s of rounding, hence the tolerance.
    EXPECT_LT((expected.Translation() - actual.Translation()).norm(), 1e-5);
    EXPECT_LT(RotationAngle(expected.Inverse() * actual), 1e-5);
  }
  // Without --frames the whole recording is written.
  options.frames = -1;
  options.width = 64;
  options.height = 48;
  options.actors = 0;
  EXPECT_NEAR(SynthSequence(options).FrameCount(), 28.83 * 30, 2);
}

TEST(SynthSequenceTest, BadOptionsAreErrorsNamingTheOption) {
  TestFolder folder("bad_options");
  const auto message = [](const SynthOptions& options) {
    try {
      SynthSequence sequence(options);
    } catch (const Error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  SynthOptions options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.scenario = "running_xyz";
  EXPECT_NE(message(options).find("unknown scenario 'running_xyz'"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 0, 64, 48);
  EXPECT_NE(message(options).find("--frames 0"), std::string::npos);
  options = SmallSequenceOptions("static_rpy", 2, 64, 48);
  options.actors = 2;
  EXPECT_NE(message(options).find("--actors 2"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.actor_class = "wizard";
  EXPECT_NE(message(options).find("--actor-class"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.textures = folder.Path();
  EXPECT_NE(message(options).find("no images"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.trajectory = folder / "missing.txt";
  EXPECT_NE(message(options).find("missing.txt"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.billboard_count = 1;
  EXPECT_NE(message(options).find("--billboards"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.seed = 3000000000u;
  EXPECT_NE(message(options).find("--seed"), std::string::npos);
  options = SmallSequenceOptions("walking_xyz", 2, 64, 48);
  options.actor_class = "cell_phone";
  EXPECT_EQ(message(options), "no error");
}

}  // namespace
}  // namespace drvslam::synth
