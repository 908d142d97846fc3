#include "drvslam/semantic/segmentation_options.h"

#include <cmath>
#include <sstream>
#include <utility>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"

namespace drvslam {
namespace {

template <typename Enum>
struct Spelling {
  const char* name;
  Enum value;
};

template <typename Enum, std::size_t N>
Enum ParseEnum(const std::string& text, const std::string& key, const Spelling<Enum> (&table)[N]) {
  std::string allowed;
  for (const Spelling<Enum>& entry : table) {
    if (text == entry.name) return entry.value;
    allowed += allowed.empty() ? "" : ", ";
    allowed += entry.name;
  }
  throw Error(key + " = '" + text + "' must be one of " + allowed);
}

template <typename Enum, std::size_t N>
std::string EnumName(Enum value, const Spelling<Enum> (&table)[N]) {
  for (const Spelling<Enum>& entry : table) {
    if (entry.value == value) return entry.name;
  }
  return "?";
}

constexpr Spelling<SegmenterBackend> kBackends[] = {{"yolo", SegmenterBackend::kYolo},
                                                    {"masks", SegmenterBackend::kMaskFiles},
                                                    {"gt", SegmenterBackend::kGroundTruth},
                                                    {"none", SegmenterBackend::kNone}};
constexpr Spelling<DnnBackend> kDnnBackends[] = {
    {"auto", DnnBackend::kAuto}, {"opencv", DnnBackend::kOpenCv}, {"cuda", DnnBackend::kCuda}};
constexpr Spelling<DnnTarget> kDnnTargets[] = {{"auto", DnnTarget::kAuto},
                                               {"cpu", DnnTarget::kCpu},
                                               {"opencl", DnnTarget::kOpenCl},
                                               {"cuda", DnnTarget::kCuda},
                                               {"cuda_fp16", DnnTarget::kCudaFp16}};
constexpr Spelling<MaskNaming> kNamings[] = {
    {"auto", MaskNaming::kAuto}, {"stamp", MaskNaming::kTimestamp}, {"index", MaskNaming::kIndex}};
constexpr Spelling<MaskPropagation> kPropagations[] = {{"dense", MaskPropagation::kDenseFlow},
                                                       {"sparse", MaskPropagation::kSparseFlow},
                                                       {"none", MaskPropagation::kNone},
                                                       {"objects", MaskPropagation::kObjects}};

template <typename T>
void Require(bool ok, const char* key, const T& value, const char* rule) {
  if (ok) return;
  std::ostringstream message;
  message << key << " = " << value << " " << rule;
  throw Error(message.str());
}

bool InUnitInterval(double value) { return std::isfinite(value) && value >= 0.0 && value <= 1.0; }

}  // namespace

void SegmentationOptions::Check() const {
  Require(InUnitInterval(score_threshold), "Segmentation.scoreThreshold", score_threshold,
          "must be in [0, 1]");
  Require(InUnitInterval(nms_threshold), "Segmentation.nmsThreshold", nms_threshold,
          "must be in [0, 1]");
  Require(std::isfinite(mask_threshold) && mask_threshold > 0.0 && mask_threshold < 1.0,
          "Segmentation.maskThreshold", mask_threshold, "must be in (0, 1)");
  Require(max_detections >= 1 && max_detections <= 10000, "Segmentation.maxDetections",
          max_detections, "must be in 1..10000");
  Require(dnn_threads >= 0 && dnn_threads <= 1024, "Segmentation.dnnThreads", dnn_threads,
          "must be in 0..1024 (0 = the thread budget)");
  Require(std::isfinite(keyframe_wait_ms) && keyframe_wait_ms >= 0.0 && keyframe_wait_ms <= 1000.0,
          "Segmentation.keyframeWaitMs", keyframe_wait_ms, "must be in [0, 1000] ms");
  const bool cuda_target = dnn_target == DnnTarget::kCuda || dnn_target == DnnTarget::kCudaFp16;
  Require(!(dnn_backend == DnnBackend::kOpenCv && cuda_target), "Segmentation.dnnTarget",
          dnn_target == DnnTarget::kCuda ? "cuda" : "cuda_fp16",
          "needs Segmentation.dnnBackend cuda (or auto)");
  Require(!(dnn_backend == DnnBackend::kCuda &&
            (dnn_target == DnnTarget::kCpu || dnn_target == DnnTarget::kOpenCl)),
          "Segmentation.dnnTarget", dnn_target == DnnTarget::kCpu ? "cpu" : "opencl",
          "cannot run on Segmentation.dnnBackend cuda (use cuda, cuda_fp16 or auto)");
  Require(backend != SegmenterBackend::kYolo || !model.empty(), "Segmentation.model", "''",
          "must name an ONNX file when Segmentation.backend is yolo");
  Require(!masks_dir.empty(), "Segmentation.masksDir", "''", "must not be empty");
  Require(CocoClassId(mask_class) >= 0, "Segmentation.maskClass", "'" + mask_class + "'",
          "is not a COCO class name (e.g. person)");
  Require(carry_frames >= 1 && carry_frames <= 1000, "Segmentation.carryFrames", carry_frames,
          "must be in 1..1000");
  Require(carry_min_support >= 1, "Segmentation.carryMinSupport", carry_min_support,
          "must be at least 1");
  for (const std::string& name : class_names) {
    Require(!name.empty(), "Segmentation.classNames", "(list)", "must not hold empty names");
  }
}

const Choices<SegmenterBackend>& BackendChoices() {
  static const Choices<SegmenterBackend> choices = {{"yolo", SegmenterBackend::kYolo},
                                                    {"masks", SegmenterBackend::kMaskFiles},
                                                    {"gt", SegmenterBackend::kGroundTruth},
                                                    {"none", SegmenterBackend::kNone}};
  return choices;
}

const Choices<MaskPropagation>& PropagationChoices() {
  static const Choices<MaskPropagation> choices = {{"dense", MaskPropagation::kDenseFlow},
                                                   {"sparse", MaskPropagation::kSparseFlow},
                                                   {"none", MaskPropagation::kNone},
                                                   {"objects", MaskPropagation::kObjects}};
  return choices;
}

const OptionTable<SegmentationOptions>& SegmentationOptionTable() {
  static const OptionTable<SegmentationOptions> table = [] {
    using S = SegmentationOptions;
    const Choices<DnnBackend> dnn_backends = {
        {"auto", DnnBackend::kAuto}, {"opencv", DnnBackend::kOpenCv}, {"cuda", DnnBackend::kCuda}};
    const Choices<DnnTarget> dnn_targets = {{"auto", DnnTarget::kAuto},
                                            {"cpu", DnnTarget::kCpu},
                                            {"opencl", DnnTarget::kOpenCl},
                                            {"cuda", DnnTarget::kCuda},
                                            {"cuda_fp16", DnnTarget::kCudaFp16}};
    const Choices<MaskNaming> namings = {{"auto", MaskNaming::kAuto},
                                         {"stamp", MaskNaming::kTimestamp},
                                         {"index", MaskNaming::kIndex}};
    OptionTable<S> t("Segmentation",
                     "which backend segments the frames, the network's thresholds and device, "
                     "mask files, and which classes may move or matter to the dense map");
    t.Choice("backend", &S::backend, BackendChoices(),
             "yolo: the ONNX network; masks: mask files; gt: a synthetic sequence's ground truth "
             "(an oracle); none.")
        .Text("model", &S::model, "YOLOv8/YOLO11-seg ONNX file (yolo).")
        .List("classNames", &S::class_names,
              "Class names overriding the model's metadata (empty: the model's).")
        .Real("scoreThreshold", &S::score_threshold, Bounds::In(0, 1),
              "Detections scoring below this are dropped.")
        .Real("nmsThreshold", &S::nms_threshold, Bounds::In(0, 1),
              "IoU above which the weaker box of one class is dropped.")
        .Real("maskThreshold", &S::mask_threshold, Bounds::Between(0, 1),
              "Threshold on sigmoid(coefficients x prototypes).")
        .Int("maxDetections", &S::max_detections, Bounds::In(1, 10000),
             "Detections kept per frame at most.")
        .Choice("dnnBackend", &S::dnn_backend, dnn_backends,
                "OpenCV DNN backend (auto: CUDA when OpenCV has it).")
        .Choice("dnnTarget", &S::dnn_target, dnn_targets, "OpenCV DNN target device.")
        .Int("dnnThreads", &S::dnn_threads, Bounds::In(0, 1024).Note("0 = the thread budget"),
             "OpenCV's process-wide thread pool size.")
        .Real("keyframeWaitMs", &S::keyframe_wait_ms, Bounds::In(0, 1000).Note("ms"),
              "--realtime: a likely keyframe waits this long for its own masks (0 = never).")
        .Text("masksDir", &S::masks_dir, "Mask files folder (masks); relative to the dataset.")
        .Choice("maskNaming", &S::mask_naming, namings,
                "How mask files match frames: timestamp stems, frame indices, or auto.")
        .Text("maskClass", &S::mask_class,
              "COCO class of mask ids no instances.txt names, and of binary masks.")
        .Choice("propagation", &S::propagation, PropagationChoices(),
                "How late masks are carried to the current frame (--realtime).")
        .Int("carryFrames", &S::carry_frames, Bounds::In(1, 1000),
             "objects propagation: masks older than this many frames expire.")
        .Int("carryMinSupport", &S::carry_min_support, Bounds::AtLeast(1),
             "objects propagation: flow tracks an instance needs to be carried.")
        .List("movingClasses", &S::moving_classes,
              "COCO classes that may move (potentially-moving objects).")
        .List("keyObjects", &S::key_objects, "COCO classes the dense map enhances when static.")
        .Rule(
            "dnnTarget",
            [](const S& o) {
              const bool cuda =
                  o.dnn_target == DnnTarget::kCuda || o.dnn_target == DnnTarget::kCudaFp16;
              return !(o.dnn_backend == DnnBackend::kOpenCv && cuda);
            },
            "needs Segmentation.dnnBackend cuda (or auto)")
        .Rule(
            "dnnTarget",
            [](const S& o) {
              return !(o.dnn_backend == DnnBackend::kCuda &&
                       (o.dnn_target == DnnTarget::kCpu || o.dnn_target == DnnTarget::kOpenCl));
            },
            "cannot run on Segmentation.dnnBackend cuda (use cuda, cuda_fp16 or auto)")
        .Rule(
            "model",
            [](const S& o) { return o.backend != SegmenterBackend::kYolo || !o.model.empty(); },
            "must name an ONNX file when Segmentation.backend is yolo")
        .Rule(
            "masksDir", [](const S& o) { return !o.masks_dir.empty(); }, "must not be empty")
        .Rule(
            "maskClass", [](const S& o) { return CocoClassId(o.mask_class) >= 0; },
            "is not a COCO class name (e.g. person)")
        .Rule(
            "classNames",
            [](const S& o) {
              for (const std::string& name : o.class_names) {
                if (name.empty()) return false;
              }
              return true;
            },
            "must not hold empty names");
    return t;
  }();
  return table;
}

SegmentationOptions LoadSegmentationOptions(const SettingsFile& file) {
  SegmentationOptions o;
  try {
    o.backend = ParseEnum(file.GetString("Segmentation.backend", ToString(o.backend)),
                          "Segmentation.backend", kBackends);
    o.model = file.GetString("Segmentation.model", o.model);
    o.class_names = file.GetStringList("Segmentation.classNames", o.class_names);
    o.score_threshold = file.GetDouble("Segmentation.scoreThreshold", o.score_threshold);
    o.nms_threshold = file.GetDouble("Segmentation.nmsThreshold", o.nms_threshold);
    o.mask_threshold = file.GetDouble("Segmentation.maskThreshold", o.mask_threshold);
    o.max_detections = file.GetInt("Segmentation.maxDetections", o.max_detections);
    o.dnn_backend =
        ParseEnum(file.GetString("Segmentation.dnnBackend", EnumName(o.dnn_backend, kDnnBackends)),
                  "Segmentation.dnnBackend", kDnnBackends);
    o.dnn_target =
        ParseEnum(file.GetString("Segmentation.dnnTarget", EnumName(o.dnn_target, kDnnTargets)),
                  "Segmentation.dnnTarget", kDnnTargets);
    o.dnn_threads = file.GetInt("Segmentation.dnnThreads", o.dnn_threads);
    o.keyframe_wait_ms = file.GetDouble("Segmentation.keyframeWaitMs", o.keyframe_wait_ms);
    o.masks_dir = file.GetString("Segmentation.masksDir", o.masks_dir);
    o.mask_naming =
        ParseEnum(file.GetString("Segmentation.maskNaming", EnumName(o.mask_naming, kNamings)),
                  "Segmentation.maskNaming", kNamings);
    o.mask_class = file.GetString("Segmentation.maskClass", o.mask_class);
    o.propagation = ParseEnum(file.GetString("Segmentation.propagation", ToString(o.propagation)),
                              "Segmentation.propagation", kPropagations);
    o.carry_frames = file.GetInt("Segmentation.carryFrames", o.carry_frames);
    o.carry_min_support = file.GetInt("Segmentation.carryMinSupport", o.carry_min_support);
    o.moving_classes = file.GetStringList("Segmentation.movingClasses", o.moving_classes);
    o.key_objects = file.GetStringList("Segmentation.keyObjects", o.key_objects);
    o.Check();
  } catch (const Error& e) {
    const std::string message = e.what();
    if (message.rfind(file.Path(), 0) == 0) throw;
    throw Error(file.Path() + ": " + message);
  }
  return o;
}

std::string ToString(SegmenterBackend backend) { return EnumName(backend, kBackends); }
std::string ToString(MaskPropagation propagation) { return EnumName(propagation, kPropagations); }

SegmenterBackend ParseSegmenterBackend(const std::string& name, const std::string& key) {
  return ParseEnum(name, key, kBackends);
}

}  // namespace drvslam
