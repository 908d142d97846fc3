#include "drvslam/semantic/segmentation_options.h"

#include <string>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"

namespace drvslam {
namespace {

const Choices<MaskPropagation>& PropagationChoices() {
  static const Choices<MaskPropagation> choices = {{"dense", MaskPropagation::kDenseFlow},
                                                   {"sparse", MaskPropagation::kSparseFlow},
                                                   {"none", MaskPropagation::kNone},
                                                   {"objects", MaskPropagation::kObjects}};
  return choices;
}

const Choices<SegmenterBackend>& BackendChoices() {
  static const Choices<SegmenterBackend> choices = {{"yolo", SegmenterBackend::kYolo},
                                                    {"masks", SegmenterBackend::kMaskFiles},
                                                    {"gt", SegmenterBackend::kGroundTruth},
                                                    {"none", SegmenterBackend::kNone},
                                                    {"auto", SegmenterBackend::kAuto}};
  return choices;
}

}  // namespace

void SegmentationOptions::Check() const { SegmentationOptionTable().Check(*this); }

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
    t.Choice(
         "backend", &S::backend, BackendChoices(),
         "yolo: the ONNX network; masks: mask files; gt: a synthetic sequence's ground truth "
         "(an oracle); none; auto: the run's default (gt for a sequence with ground-truth masks, "
         "else none).")
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
              "--realtime: a likely keyframe waits at most this long for masks due by then (0 = "
              "never).")
        .Real("mapStartWaitMs", &S::map_start_wait_ms, Bounds::In(0, 10000).Note("ms"),
              "--realtime: a frame that would start a map waits at most this long for its masks "
              "(0 = never).")
        .Bool("lateKeyFrameMasks", &S::late_keyframe_masks,
              "--realtime: a keyframe made without its masks has them segmented later, and its "
              "points on potentially-moving objects are then culled.")
        .Real("backoffPasses", &S::backoff_passes, Bounds::In(0, 100).Note("0 = never"),
              "--realtime: after skipped frames the network rests this many of its pass times.")
        .Text("masksDir", &S::masks_dir, "Mask files folder (masks); relative to the dataset.")
        .Choice("maskNaming", &S::mask_naming, namings,
                "How mask files match frames: timestamp stems, frame indices, or auto.")
        .Text("maskClass", &S::mask_class,
              "COCO class of mask ids no instances.txt names, and of binary masks.")
        .Choice("propagation", &S::propagation, PropagationChoices(),
                "How late masks are carried to the current frame (--realtime).")
        .Int("carryFrames", &S::carry_frames, Bounds::In(1, 1000),
             "objects propagation: masks expire after this many frames without newer ones.")
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
  return SegmentationOptionTable().Load(file);
}

std::string ToString(SegmenterBackend backend) { return ChoiceName(backend, BackendChoices()); }
std::string ToString(MaskPropagation propagation) {
  return ChoiceName(propagation, PropagationChoices());
}

SegmenterBackend ParseSegmenterBackend(const std::string& name, const std::string& key) {
  return ParseChoice(name, key, BackendChoices());
}

}  // namespace drvslam
