// MaskFileSegmenter: segmentations computed offline, one label PNG per frame in a folder (8- or
// 16-bit instance ids, 0 = background; a binary 0/255 mask is one instance). Files are found by
// the colour image's name, by timestamp stem or by frame index. Classes come from an optional
// instances.txt beside the masks (or in the folder above), else Segmentation.maskClass.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "drvslam/semantic/label_masks.h"
#include "drvslam/semantic/segmentation_options.h"
#include "drvslam/semantic/segmenter.h"

namespace drvslam {

class MaskFileSegmenter : public Segmenter {
 public:
  // `frame_names` (optional) holds each frame's colour image file; frame i's mask is then
  // masks_dir/<its stem>.png. Otherwise options.mask_naming decides. instances.txt lines are
  // "[instance] ID CLASS_NAME [COCO_ID]" (underscores for spaces, COCO id -1 or absent for a
  // class named only by name; the drvslam synth format is one such file); other lines
  // ("frame ...", "# ...") are ignored. Throws drvslam::Error naming the
  // folder or file (and line) when the folder is missing or empty, or instances.txt is malformed.
  MaskFileSegmenter(const std::string& masks_dir, const SegmentationOptions& options,
                    std::vector<std::string> frame_names = {});

  // Thread-safe (reads files only). Throws Error naming the expected file when the frame has
  // no mask file, or it does not match the image's size.
  Segmentation Segment(const cv::Mat& bgr, double timestamp, std::size_t frame_index) override;
  std::string Name() const override;
  // COCO-80 (class id = COCO id), then any other classes instances.txt names, in file order.
  const std::vector<std::string>& ClassNames() const override { return class_names_; }

  // The file that holds frame `frame_index` (at `timestamp`); throws Error when none does.
  std::string MaskPath(double timestamp, std::size_t frame_index) const;

 private:
  void ReadInstancesFile(const std::string& path);

  std::string dir_;
  std::vector<std::string> frame_names_;
  bool by_timestamp_ = false;
  StampIndex stamps_;
  std::map<std::size_t, std::string> indices_;
  int default_class_ = 0;
  std::map<int, int> class_of_id_;
  std::vector<std::string> class_names_;
};

}  // namespace drvslam
