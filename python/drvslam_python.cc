// The Python module `drvslam`: System (settings resolved as `drvslam run` resolves them) fed
// numpy frames by any camera SDK, its trajectories as numpy arrays and as the CLI's files, and
// the two helpers a folder-reading loop needs (read_image, associate). drvslam::Error becomes
// drvslam.Error (a ValueError) with the same message. docs/python.md shows the loop.
#include <pybind11/eigen.h>
#include <pybind11/numpy.h>
#include <pybind11/pybind11.h>
#include <pybind11/stl.h>

#include <cstdint>
#include <cstring>
#include <filesystem>
#include <memory>
#include <mutex>
#include <opencv2/imgcodecs.hpp>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "drvslam/core/error.h"
#include "drvslam/io/association.h"
#include "drvslam/io/trajectory_formats.h"
#include "drvslam/map/keyframe.h"
#include "drvslam/system.h"
#include "drvslam/system_stats.h"
#include "drvslam/tools/runner/sequence_runner.h"

namespace py = pybind11;

namespace drvslam::python {
namespace {

std::string Shape(const py::array& array) {
  std::string text = "(";
  for (py::ssize_t k = 0; k < array.ndim(); ++k) {
    text += (k ? ", " : "") + std::to_string(array.shape(k));
  }
  return text + (array.ndim() == 1 ? ",)" : ")");
}

std::string DtypeName(const py::array& array) {
  return py::str(static_cast<py::object>(array.dtype())).cast<std::string>();
}

// A cv::Mat over the array's memory (no copy: System copies what it keeps). Only C-contiguous
// arrays qualify: OpenCV rows must be packed pixels.
cv::Mat WrapArray(const py::array& array, int cv_depth, int channels, const std::string& what) {
  if (!(array.flags() & py::array::c_style)) {
    throw Error(what + " is not C-contiguous (a slice or a transposed view?); pass " +
                "numpy.ascontiguousarray(" + what + ")");
  }
  const int rows = static_cast<int>(array.shape(0));
  const int cols = static_cast<int>(array.shape(1));
  return cv::Mat(rows, cols, CV_MAKETYPE(cv_depth, channels), const_cast<void*>(array.data()),
                 static_cast<std::size_t>(array.strides(0)));
}

cv::Mat ColourMat(const py::array& bgr) {
  const bool colour = bgr.ndim() == 3 && bgr.shape(2) == 3;
  if (!colour && bgr.ndim() != 2) {
    throw Error("track_rgbd: bgr has shape " + Shape(bgr) +
                "; expected (height, width, 3) BGR or (height, width) grey");
  }
  if (!bgr.dtype().is(py::dtype::of<std::uint8_t>())) {
    throw Error("track_rgbd: bgr has dtype " + DtypeName(bgr) + "; expected uint8");
  }
  return WrapArray(bgr, CV_8U, colour ? 3 : 1, "bgr");
}

cv::Mat DepthMat(const py::array& depth) {
  if (depth.ndim() != 2) {
    throw Error("track_rgbd: depth has shape " + Shape(depth) + "; expected (height, width)");
  }
  if (depth.dtype().is(py::dtype::of<float>())) return WrapArray(depth, CV_32F, 1, "depth");
  if (depth.dtype().is(py::dtype::of<std::uint16_t>())) return WrapArray(depth, CV_16U, 1, "depth");
  throw Error("track_rgbd: depth has dtype " + DtypeName(depth) +
              "; expected float32 (metres) or uint16 (raw, DepthMapFactor per metre)");
}

// Timestamps (N,) and camera-to-world poses (N, 4, 4).
std::pair<py::array_t<double>, py::array_t<double>> ToArrays(const Trajectory& trajectory) {
  const py::ssize_t n = static_cast<py::ssize_t>(trajectory.size());
  py::array_t<double> stamps(n);
  py::array_t<double> poses({n, py::ssize_t{4}, py::ssize_t{4}});
  auto s = stamps.mutable_unchecked<1>();
  auto p = poses.mutable_unchecked<3>();
  for (py::ssize_t i = 0; i < n; ++i) {
    s(i) = trajectory[i].timestamp;
    const Eigen::Matrix4d m = trajectory[i].T_wc.Matrix();
    for (int r = 0; r < 4; ++r) {
      for (int c = 0; c < 4; ++c) p(i, r, c) = m(r, c);
    }
  }
  return {std::move(stamps), std::move(poses)};
}

// What track_rgbd returns: TrackResult with the poses as 4x4 matrices.
struct PyTrackResult {
  double timestamp = 0.0;
  long frame_id = -1;
  TrackingState state = TrackingState::kNotInitialized;
  LocalizationQuality quality = LocalizationQuality::kLost;
  bool pose_valid = false;
  Eigen::Matrix4d T_cw = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d T_wc = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d T_cw_tracked = Eigen::Matrix4d::Identity();
  Eigen::Matrix4d T_wc_tracked = Eigen::Matrix4d::Identity();
  Eigen::Vector3d linear_velocity = Eigen::Vector3d::Zero();
  Eigen::Vector3d angular_velocity = Eigen::Vector3d::Zero();
  Eigen::Matrix<double, 6, 6> pose_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  Eigen::Matrix<double, 6, 6> twist_covariance = Eigen::Matrix<double, 6, 6>::Zero();
  int inliers = 0;
  std::optional<long> keyframe_id;  // set when the frame became a keyframe
};

std::string OnOff(const std::optional<bool>& value) {
  if (!value) return "";
  return *value ? "on" : "off";
}

struct SystemArguments {
  std::optional<std::string> settings;
  std::optional<std::string> dataset;
  std::optional<std::string> vocabulary;
  bool sequential = false;
  std::optional<std::string> segmenter;
  std::optional<std::string> model;
  std::optional<bool> dynamic;
  std::optional<bool> dense;
  std::optional<bool> loop;
  bool realtime = false;
  bool strict_settings = false;
  std::optional<std::string> load_map;
  bool localization = false;
};

// One drvslam::System behind a mutex: Python threads may call in at once. Every call into the
// System releases the GIL first (then takes the mutex), so other Python threads run meanwhile
// and a thread waiting for the mutex never holds the GIL.
class PySystem {
 public:
  explicit PySystem(const SystemArguments& args) {
    RunOptions options;
    options.config = args.settings.value_or("");
    options.dataset = args.dataset.value_or("");
    options.sequential = args.sequential;
    options.dynamic.segmenter = args.segmenter.value_or("");
    options.dynamic.model = args.model.value_or("");
    options.dynamic.dynamic = OnOff(args.dynamic);
    options.dynamic.realtime = args.realtime;
    options.dense = OnOff(args.dense);
    options.loop = OnOff(args.loop);
    options.strict_settings = args.strict_settings;
    options.load_map = args.load_map.value_or("");
    options.localization = args.localization;
    if (args.segmenter && *args.segmenter != "yolo" && *args.segmenter != "masks" &&
        *args.segmenter != "gt" && *args.segmenter != "none") {
      throw Error("segmenter = '" + *args.segmenter + "' must be yolo, masks, gt or none");
    }
    RunSetup setup = PrepareRun(options);
    if (args.vocabulary) setup.system.relocalization.vocabulary = *args.vocabulary;
    settings_source_ = setup.settings_source;
    segmenter_ = setup.dynamic.segmenter_label;
    oracle_ = setup.dynamic.oracle;
    width_ = setup.settings.camera.width;
    height_ = setup.settings.camera.height;
    depth_map_factor_ = setup.settings.depth.depth_map_factor;
    py::gil_scoped_release release;  // loading the vocabulary takes a while
    system_ = std::make_unique<System>(setup.settings, setup.tracker, setup.system);
  }

  // Runs fn(System&) with the GIL released, under the mutex. Every call into the System goes
  // through here, so a new System method is bound in a line:
  // .def("name", [](PySystem& self) { return self.Call([](System& s) { return s.Name(); }); })
  template <typename Fn>
  auto Call(Fn&& fn) {
    py::gil_scoped_release release;
    std::lock_guard<std::mutex> lock(mutex_);
    return fn(*system_);
  }

  PyTrackResult TrackRgbd(const py::array& bgr, const std::optional<py::array>& depth,
                          double timestamp) {
    const cv::Mat colour = ColourMat(bgr);
    const cv::Mat depth_mat = depth ? DepthMat(*depth) : cv::Mat();
    const TrackResult result =
        Call([&](System& system) { return system.TrackRGBD(colour, depth_mat, timestamp); });
    PyTrackResult out;
    out.timestamp = result.timestamp;
    out.frame_id = result.frame_id;
    out.state = result.state;
    out.quality = result.quality;
    out.pose_valid = result.pose_valid;
    out.T_cw = result.T_cw.Matrix();
    out.T_wc = result.T_wc.Matrix();
    out.T_cw_tracked = result.T_cw_tracked.Matrix();
    out.T_wc_tracked = result.T_wc_tracked.Matrix();
    out.linear_velocity = result.linear_velocity;
    out.angular_velocity = result.angular_velocity;
    out.pose_covariance = result.pose_covariance;
    out.twist_covariance = result.twist_covariance;
    out.inliers = result.inliers;
    if (result.new_keyframe) out.keyframe_id = result.new_keyframe->Id();
    return out;
  }

  std::string WriteTrajectories(const std::string& out_dir, const std::string& format) {
    const TrajectoryFormat parsed = ParseTrajectoryFormat(format, "format");
    std::error_code error;
    std::filesystem::create_directories(out_dir, error);
    if (error || !std::filesystem::is_directory(out_dir)) {
      throw Error(out_dir + ": cannot create output folder");
    }
    return Call([&](System& system) { return WriteRunTrajectories(system, out_dir, parsed); });
  }

  py::dict Stats() {
    const SystemStats stats = Call([](System& system) { return system.Stats(); });
    py::dict out;
    out["frames"] = stats.frames;
    out["tracked"] = stats.tracked;
    out["keyframes"] = stats.keyframes;
    out["map_points"] = stats.map_points;
    out["frames_lost"] = stats.frames_lost;
    out["relocalizations"] = stats.relocalizations;
    out["tracking_fps"] = stats.tracking_fps;
    return out;
  }

  const std::string& SettingsSource() const { return settings_source_; }
  const std::string& Segmenter() const { return segmenter_; }
  bool Oracle() const { return oracle_; }
  int Width() const { return width_; }
  int Height() const { return height_; }
  double DepthMapFactor() const { return depth_map_factor_; }

 private:
  std::mutex mutex_;
  std::unique_ptr<System> system_;
  std::string settings_source_;
  std::string segmenter_;
  bool oracle_ = false;
  int width_ = 0;
  int height_ = 0;
  double depth_map_factor_ = 0.0;
};

// cv::imread(path, IMREAD_UNCHANGED) as a numpy array (uint8 (H, W) or (H, W, C) in BGR order,
// uint16 or float32 (H, W)): images decode exactly as `drvslam run` decodes them.
py::array ReadImage(const std::string& path) {
  cv::Mat image;
  {
    py::gil_scoped_release release;
    image = cv::imread(path, cv::IMREAD_UNCHANGED);
  }
  if (image.empty()) {
    throw Error(path + ": cannot read image (missing, corrupt or unsupported format)");
  }
  py::dtype dtype;
  switch (image.depth()) {
    case CV_8U:
      dtype = py::dtype::of<std::uint8_t>();
      break;
    case CV_16U:
      dtype = py::dtype::of<std::uint16_t>();
      break;
    case CV_32F:
      dtype = py::dtype::of<float>();
      break;
    default:
      throw Error(path + ": image depth " + std::to_string(image.depth()) +
                  " is not uint8, uint16 or float32");
  }
  std::vector<py::ssize_t> shape{image.rows, image.cols};
  if (image.channels() > 1) shape.push_back(image.channels());
  py::array out(dtype, shape);
  const std::size_t row_bytes = image.cols * image.elemSize();
  auto* dst = static_cast<std::uint8_t*>(out.mutable_data());
  for (int r = 0; r < image.rows; ++r) {
    std::memcpy(dst + r * row_bytes, image.ptr(r), row_bytes);
  }
  return out;
}

std::vector<std::pair<std::size_t, std::size_t>> Associate(const std::vector<double>& first,
                                                           const std::vector<double>& second,
                                                           double max_difference, double offset) {
  std::vector<std::pair<std::size_t, std::size_t>> pairs;
  for (const StampMatch& match : AssociateStamps(first, second, offset, max_difference)) {
    pairs.emplace_back(match.first, match.second);
  }
  return pairs;
}

}  // namespace
}  // namespace drvslam::python

PYBIND11_MODULE(drvslam, m) {
  using namespace drvslam;          // NOLINT: the module binds this namespace
  using namespace drvslam::python;  // NOLINT
  m.doc() =
      "drvslam: real-time semantic RGB-D SLAM for dynamic scenes. Feed System.track_rgbd with "
      "numpy frames from any camera; read the trajectory back as numpy arrays or files.";

  // Bad input and settings: the library's message, as a ValueError subclass.
  py::register_exception<Error>(m, "Error", PyExc_ValueError);

  py::enum_<TrackingState>(m, "TrackingState", "Where tracking stands after a frame.")
      .value("NOT_INITIALIZED", TrackingState::kNotInitialized)
      .value("OK", TrackingState::kOk)
      .value("LOST", TrackingState::kLost);

  py::enum_<LocalizationQuality>(
      m, "LocalizationQuality",
      "How far a pose may be trusted: VERIFIED (act on it), TENTATIVE (just found again after "
      "a loss, not confirmed: may be wrong by a repeat of the scene), LOST (no pose).")
      .value("LOST", LocalizationQuality::kLost)
      .value("TENTATIVE", LocalizationQuality::kTentative)
      .value("VERIFIED", LocalizationQuality::kVerified);

  py::class_<PyTrackResult>(m, "TrackResult", "What track_rgbd says about one frame.")
      .def_readonly("timestamp", &PyTrackResult::timestamp, "seconds, as given")
      .def_readonly("frame_id", &PyTrackResult::frame_id,
                    "accepted frames are numbered from 0 in call order")
      .def_readonly("state", &PyTrackResult::state, "TrackingState after this frame")
      .def_readonly("quality", &PyTrackResult::quality,
                    "LocalizationQuality: act on the pose only when VERIFIED")
      .def_readonly("pose_valid", &PyTrackResult::pose_valid,
                    "True when the frame was tracked (T_cw, T_wc hold its pose); else both are "
                    "the identity")
      .def_readonly("T_cw", &PyTrackResult::T_cw,
                    "4x4 float64, world -> camera: the causal pose (this frame and the ones "
                    "before it, with a constant-velocity motion model)")
      .def_readonly("T_wc", &PyTrackResult::T_wc,
                    "4x4 float64, camera -> world: the causal pose (the one to act on)")
      .def_readonly("T_cw_tracked", &PyTrackResult::T_cw_tracked,
                    "4x4 float64, world -> camera, as tracked (this frame's own solve)")
      .def_readonly("T_wc_tracked", &PyTrackResult::T_wc_tracked,
                    "4x4 float64, camera -> world, as tracked")
      .def_readonly("linear_velocity", &PyTrackResult::linear_velocity,
                    "(3,) float64, m/s, in the camera frame (x right, y down, z forward)")
      .def_readonly("angular_velocity", &PyTrackResult::angular_velocity,
                    "(3,) float64, rad/s, in the camera frame")
      .def_readonly("pose_covariance", &PyTrackResult::pose_covariance,
                    "6x6 float64 over (x, y, z, rotation about the world's x, y, z) of T_wc, "
                    "world frame (nav_msgs/Odometry's pose covariance)")
      .def_readonly("twist_covariance", &PyTrackResult::twist_covariance,
                    "6x6 float64 over (linear_velocity, angular_velocity), camera frame")
      .def_readonly("inliers", &PyTrackResult::inliers, "map points the pose was estimated from")
      .def_readonly("keyframe_id", &PyTrackResult::keyframe_id,
                    "the new keyframe's id when this frame became one, else None")
      .def("__repr__", [](const PyTrackResult& r) {
        return "TrackResult(frame_id=" + std::to_string(r.frame_id) +
               ", state=" + TrackingStateName(r.state) +
               ", quality=" + LocalizationQualityName(r.quality) +
               ", pose_valid=" + (r.pose_valid ? "True" : "False") +
               ", inliers=" + std::to_string(r.inliers) + ")";
      });

  py::class_<PySystem>(m, "System",
                       "SLAM on RGB-D frames. Settings are resolved as `drvslam run` resolves "
                       "them: `settings` (an ORB-SLAM2/drvslam YAML file), else "
                       "DATASET/settings.yaml when `dataset` is given, else TUM fr3 defaults.")
      .def(
          py::init([](std::optional<std::string> settings, std::optional<std::string> dataset,
                      std::optional<std::string> vocabulary, bool sequential,
                      std::optional<std::string> segmenter, std::optional<std::string> model,
                      std::optional<bool> dynamic, std::optional<bool> dense,
                      std::optional<bool> loop, bool realtime, bool strict_settings,
                      std::optional<std::string> load_map, bool localization) {
            SystemArguments args;
            args.settings = std::move(settings);
            args.dataset = std::move(dataset);
            args.vocabulary = std::move(vocabulary);
            args.sequential = sequential;
            args.segmenter = std::move(segmenter);
            args.model = std::move(model);
            args.dynamic = dynamic;
            args.dense = dense;
            args.loop = loop;
            args.realtime = realtime;
            args.strict_settings = strict_settings;
            args.load_map = std::move(load_map);
            args.localization = localization;
            return std::make_unique<PySystem>(args);
          }),
          py::arg("settings") = py::none(), py::kw_only(), py::arg("dataset") = py::none(),
          py::arg("vocabulary") = py::none(), py::arg("sequential") = false,
          py::arg("segmenter") = py::none(), py::arg("model") = py::none(),
          py::arg("dynamic") = py::none(), py::arg("dense") = py::none(),
          py::arg("loop") = py::none(), py::arg("realtime") = false,
          py::arg("strict_settings") = false, py::arg("load_map") = py::none(),
          py::arg("localization") = false,
          "settings: YAML file. dataset: sequence folder (settings.yaml, masks for "
          "segmenter 'masks'/'gt'). vocabulary: BoW file (default: the settings', else the "
          "build's). sequential: every stage on the calling thread, bit-identical runs. "
          "segmenter: 'yolo' (with model=ONNX), 'masks', 'gt' (ground-truth masks of a "
          "synthetic dataset: an ORACLE), 'none'; default as `drvslam run`. dynamic, dense, "
          "loop: True/False override the settings (None: as `drvslam run`). realtime: never "
          "wait for masks. strict_settings: unknown settings keys are errors. load_map: start from "
          "a map saved with save_map (the first frame relocalizes in it). localization: with "
          "load_map, track against it without adding keyframes or map points.")
      .def("track_rgbd", &PySystem::TrackRgbd, py::arg("bgr"), py::arg("depth"),
           py::arg("timestamp"),
           "Tracks one frame. bgr: uint8 (H, W, 3) BGR or (H, W) grey, C-contiguous, of the "
           "settings' Camera.width x height. depth: float32 (H, W) metres or uint16 (H, W) raw "
           "(DepthMapFactor per metre), 0 = no measurement; None: nothing is tracked. "
           "timestamp: seconds. Returns a TrackResult; the GIL is released while tracking. Bad "
           "input raises drvslam.Error and changes nothing.")
      .def(
          "shutdown", [](PySystem& self) { self.Call([](System& system) { system.Shutdown(); }); },
          "Lets mapping finish its queue and stops its threads (idempotent); call it before "
          "reading the final trajectory.")
      .def(
          "save_map",
          [](PySystem& self, const std::string& path) {
            self.Call([&](System& system) { system.SaveMap(path); });
          },
          py::arg("path"),
          "Writes the map (keyframes, map points, graph, dense map) for load_map; call "
          "shutdown() first for the complete map.")
      .def(
          "trajectory",
          [](PySystem& self) {
            return ToArrays(self.Call([](System& system) { return system.CameraTrajectory(); }));
          },
          "(timestamps (N,) float64, poses (N, 4, 4) float64 T_wc) of every tracked frame, with "
          "the poses as mapping and loop closing refined them, smoothed with a motion prior "
          "when Tracking.smoothTrajectory is on.")
      .def(
          "tracked_trajectory",
          [](PySystem& self) {
            return ToArrays(
                self.Call([](System& system) { return system.TrackedCameraTrajectory(); }));
          },
          "(timestamps, poses) as trajectory(), never smoothed.")
      .def(
          "online_trajectory",
          [](PySystem& self) {
            return ToArrays(
                self.Call([](System& system) { return system.OnlineCameraTrajectory(); }));
          },
          "(timestamps, poses) of every tracked frame's causal pose, T_wc as track_rgbd "
          "returned it (never corrected afterwards).")
      .def(
          "keyframe_trajectory",
          [](PySystem& self) {
            return ToArrays(self.Call([](System& system) { return system.KeyFrameTrajectory(); }));
          },
          "(timestamps, poses) of the keyframes, as trajectory().")
      .def("write_trajectories", &PySystem::WriteTrajectories, py::arg("out_dir"),
           py::arg("format") = "tum",
           "Writes OUT_DIR/CameraTrajectory, TrackedCameraTrajectory, OnlineCameraTrajectory and "
           "KeyFrameTrajectory in "
           "format 'tum' (.txt), "
           "'kitti' (.txt + _times.txt) or 'euroc' (.csv), byte for byte as `drvslam run "
           "--trajectory-format` writes them; returns the camera trajectory's path.")
      .def("stats", &PySystem::Stats,
           "dict: frames, tracked, keyframes, map_points, frames_lost, relocalizations, "
           "tracking_fps.")
      .def_property_readonly("settings_source", &PySystem::SettingsSource)
      .def_property_readonly("segmenter", &PySystem::Segmenter,
                             "where the masks come from, e.g. 'none', 'yolo (model.onnx)'")
      .def_property_readonly("oracle", &PySystem::Oracle,
                             "True when the masks are a dataset's ground truth")
      .def_property_readonly("width", &PySystem::Width, "Camera.width")
      .def_property_readonly("height", &PySystem::Height, "Camera.height")
      .def_property_readonly("depth_map_factor", &PySystem::DepthMapFactor,
                             "raw uint16 depth units per metre")
      .def("__enter__", [](PySystem& self) -> PySystem& { return self; })
      .def("__exit__", [](PySystem& self, const py::args&) {
        self.Call([](System& system) { system.Shutdown(); });
      });

  m.def("read_image", &ReadImage, py::arg("path"),
        "An image file as stored (OpenCV imread, IMREAD_UNCHANGED): uint8 (H, W, 3) BGR, "
        "(H, W) grey, uint16 or float32 (H, W) depth; decoded as `drvslam run` decodes it.");
  m.def("associate", &Associate, py::arg("first"), py::arg("second"),
        py::arg("max_difference") = 0.02, py::arg("offset") = 0.0,
        "Pairs two timestamp lists as the TUM benchmark's associate.py (and `drvslam run`) do: "
        "list of (index in first, index in second), sorted by the first.");
}
