// SegmentationOptions: the Segmentation.* section of a settings file (which backend segments the
// frames, the network's thresholds and device, where mask files live, and which classes may move
// or matter to the dense map), with defaults that work without any settings file.
#pragma once

#include <string>
#include <vector>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/option_table.h"
#include "drvslam/core/settings_file.h"

namespace drvslam {

// kAuto: the run's default, so that a settings file can say "as if I named no backend" (a
// `drvslam config --dump` file does): `drvslam run` and `benchmark` take gt for a sequence with
// ground-truth masks (masks/ and instances.txt, a synthetic sequence), else none; the runtime
// library, which knows no dataset, creates no segmenter for it (CreateSegmenter).
enum class SegmenterBackend { kYolo, kMaskFiles, kGroundTruth, kNone, kAuto };
// kAuto picks CUDA when OpenCV was built with it, else OpenCV's own CPU code.
enum class DnnBackend { kAuto, kOpenCv, kCuda };
enum class DnnTarget { kAuto, kCpu, kOpenCl, kCuda, kCudaFp16 };
// How mask files are matched to frames: by a timestamp stem ("1305031102.175304.png"), by the
// frame index ("12.png", "000012.png"), or kAuto: timestamps when any stem has a decimal point.
enum class MaskNaming { kAuto, kTimestamp, kIndex };
// How older masks are carried to the current frame when segmentation lags (--realtime):
// kObjects moves each instance by the dynamic front end's own flow tracks, frame to frame
// (ObjectMaskCarrier); kDenseFlow / kSparseFlow warp them from the masks' image to the current
// one by optical flow computed for the purpose (MaskPropagator); kNone uses them unmoved.
enum class MaskPropagation { kDenseFlow, kSparseFlow, kNone, kObjects };

struct SegmentationOptions {
  SegmenterBackend backend = SegmenterBackend::kAuto;
  std::string model;                     // ONNX file (yolo)
  std::vector<std::string> class_names;  // overrides the model's metadata names when set
  double score_threshold = 0.25;
  double nms_threshold = 0.45;  // IoU above which the weaker box of one class is dropped
  double mask_threshold = 0.5;  // on sigmoid(coefficients x prototypes)
  int max_detections = 100;
  DnnBackend dnn_backend = DnnBackend::kAuto;
  DnnTarget dnn_target = DnnTarget::kAuto;
  // Segmentation.dnnThreads: OpenCV's thread pool for the whole process. The pool is
  // process-global (cv::dnn shares it with ORB's image pyramid, optical flow and imgproc on the
  // tracking thread), so it is applied once, by ApplyOpenCvThreadBudget (core/thread_budget.h),
  // never by a segmenter. 0 = the budget: 1 when the pipeline threads run concurrently (each
  // stage then is one OS thread and the scheduler shares the cores), OpenCV's default (every
  // core) in sequential runs.
  int dnn_threads = 0;
  // Segmentation.keyframeWaitMs (--realtime only): a frame that tracking expects to become a
  // keyframe (Tracker::KeyFrameLikely) waits at most this long for its own masks, and only when
  // the network is expected to finish its image within that time (from its recent forward-pass
  // times); other frames never wait. Short, because a frame that overruns the camera's period
  // makes the next camera frame replace the one after it: with 50 ms a 30 Hz run skipped 6-19
  // frames of 300, with 15 ms 5-8 (3 runs each). 0 = keyframes never wait.
  double keyframe_wait_ms = 15.0;
  // Segmentation.mapStartWaitMs (--realtime only): a frame that would start a map (the first
  // one, or the first after a reset) waits at most this long for its own masks, whatever the
  // network's expected time. Its features become the whole first map: started without masks,
  // the map took in the people in view and tracking followed them (real Bonn crowd dev half
  // started at frame 250: 479 of its first frame's 1000 features lie on people). It waits before
  // extraction, so the masks' share of people raises the frame's feature target. Once per map,
  // so the bound can cover a first forward pass on a loaded machine; 0 = never waits.
  double map_start_wait_ms = 200.0;
  // Segmentation.lateKeyFrameMasks (--realtime only): a keyframe made without its own masks
  // keeps its image queued for the network, and when the masks come the points it created on
  // potentially-moving objects are culled (dynamic/late_keyframe_masks.h).
  bool late_keyframe_masks = true;
  // Segmentation.backoffPasses (--realtime only): when frames are skipped because tracking fell
  // behind, the network takes no new frame for this many of its own pass times
  // (semantic/segmentation_pacer.h); 0 = it never backs off. Off by default: on the real Bonn
  // dev half (realtime, 2 cores, idle and loaded) it skipped about as many frames and its later
  // masks cost accuracy.
  double backoff_passes = 0.0;

  std::string masks_dir = "masks";  // mask-file backend; relative paths are under the dataset
  MaskNaming mask_naming = MaskNaming::kAuto;
  // COCO class given to mask ids that no instances.txt names, and to binary (0/255) masks.
  std::string mask_class = "person";

  MaskPropagation propagation = MaskPropagation::kObjects;  // Segmentation.propagation
  // Segmentation.carryFrames (objects propagation): when the network delivers no newer masks
  // that can be carried for this many frames, the carried ones expire (an object it has not
  // re-detected for that long disappears); masks that finish up to twice this late are still
  // carried. Keyframes wait while people's masks are older than this (docs/real-time.md).
  int carry_frames = 8;
  // Segmentation.carryMinSupport (objects propagation): an instance with fewer flow tracks
  // starting inside it cannot be carried and disappears.
  int carry_min_support = 3;

  std::vector<std::string> moving_classes = DefaultMovingCocoClasses();
  std::vector<std::string> key_objects = {"book", "laptop", "keyboard",   "mouse", "tv",
                                          "cup",  "bottle", "cell phone", "remote"};

  // Throws drvslam::Error naming the first bad Segmentation.* key and its value.
  void Check() const;
};

// Every Segmentation.* key: name, type, bounds and doc, bound to its field (core/option_table.h).
const OptionTable<SegmentationOptions>& SegmentationOptionTable();

// Reads every Segmentation.* key (absent keys keep their defaults) and checks the result; errors
// name the file and the key.
SegmentationOptions LoadSegmentationOptions(const SettingsFile& file);

// Settings spellings of the enums ("yolo", "masks", "gt", "none", "auto", ...), for logs and help
// text.
std::string ToString(SegmenterBackend backend);
std::string ToString(MaskPropagation propagation);
// Parses a backend name; throws Error naming `key` on anything else.
SegmenterBackend ParseSegmenterBackend(const std::string& name, const std::string& key);

}  // namespace drvslam
