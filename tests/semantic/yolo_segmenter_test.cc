// YoloSegmenter on real photographs with the shared YOLOv8n-seg models (skipped when the models
// or opencv-doc photos are absent). Each forward costs ~60 ms (320x256) or ~210 ms (640x480) on
// a 2-core CPU, so every image is segmented once per model and shared by the tests.
#include "drvslam/semantic/yolo_segmenter.h"

#include <gtest/gtest.h>

#include <map>
#include <memory>
#include <opencv2/imgcodecs.hpp>
#include <opencv2/imgproc.hpp>
#include <opencv2/videoio.hpp>

#include "drvslam/core/error.h"
#include "drvslam/semantic/mask_propagator.h"
#include "test_data.h"
#include "test_support/missing_data.h"

namespace drvslam {
namespace {

constexpr const char* kSmallModel = "yolov8n-seg-320x256.onnx";
constexpr const char* kLargeModel = "yolov8n-seg-640x480.onnx";

// Loads each model once and memoizes (model, image) results.
class Photos {
 public:
  static Photos& Get() {
    static Photos photos;
    return photos;
  }

  YoloSegmenter* Model(const std::string& name) {
    auto& slot = models_[name];
    if (!slot) {
      const std::string path = testing::SharedModel(name);
      if (path.empty()) return nullptr;
      SegmentationOptions options;
      options.model = path;
      slot = std::make_unique<YoloSegmenter>(options);
    }
    return slot.get();
  }

  // "basketball1.png", "messi5.jpg" or "vtest.avi#N" (frame N of the video).
  const cv::Mat& Image(const std::string& key) {
    cv::Mat& image = images_[key];
    if (!image.empty()) return image;
    const auto hash = key.find('#');
    if (hash == std::string::npos) {
      const std::string path = testing::OpenCvData(key);
      if (!path.empty()) image = cv::imread(path, cv::IMREAD_COLOR);
      return image;
    }
    const std::string path = testing::OpenCvData(key.substr(0, hash));
    if (path.empty()) return image;
    cv::VideoCapture video(path);
    video.set(cv::CAP_PROP_POS_FRAMES, std::stoi(key.substr(hash + 1)));
    video.read(image);
    return image;
  }

  const Segmentation& Result(const std::string& model, const std::string& key) {
    const std::string id = model + "|" + key;
    auto found = results_.find(id);
    if (found == results_.end()) {
      found = results_.emplace(id, Model(model)->Segment(Image(key), 0.0, 0)).first;
    }
    return found->second;
  }

 private:
  std::map<std::string, std::unique_ptr<YoloSegmenter>> models_;
  std::map<std::string, cv::Mat> images_;
  std::map<std::string, Segmentation> results_;
};

#define REQUIRE_INPUTS(model, image)                           \
  DRVSLAM_SKIP_IF_MISSING(testing::SharedModel(model), model); \
  if (Photos::Get().Image(image).empty())                      \
  DRVSLAM_MISSING_TEST_DATA() << image << " not found (opencv-doc)"

std::vector<const Instance*> ConfidentPersons(const Segmentation& seg, float min_score) {
  std::vector<const Instance*> persons;
  for (const Instance& instance : seg.instances) {
    if (instance.class_name == "person" && instance.score >= min_score)
      persons.push_back(&instance);
  }
  return persons;
}

double BoxIoU(const cv::Rect& a, const cv::Rect& b) {
  const double overlap = (a & b).area();
  return overlap / (a.area() + b.area() - overlap);
}

// The shape checks every person mask must pass: it fills a good share of its box without
// being the box, nothing lies outside the box, and it reaches the box's edges.
void ExpectPlausiblePersonMask(const Instance& person, double min_fill, double max_fill) {
  ASSERT_EQ(person.mask.type(), CV_8UC1);
  const double area = cv::countNonZero(person.mask);
  const double fill = area / person.box.area();
  EXPECT_GE(fill, min_fill) << "box " << person.box;
  EXPECT_LE(fill, max_fill) << "box " << person.box;
  cv::Mat outside = person.mask.clone();
  outside(person.box).setTo(0);
  EXPECT_EQ(cv::countNonZero(outside), 0);
  EXPECT_GT(BoxIoU(cv::boundingRect(person.mask), person.box), 0.8) << "box " << person.box;
  EXPECT_EQ(cv::countNonZero((person.mask != 0) & (person.mask != 255)), 0);
}

TEST(YoloSegmenterTest, ModelDescribesItself) {
  DRVSLAM_SKIP_IF_MISSING(testing::SharedModel(kSmallModel), kSmallModel);
  YoloSegmenter* model = Photos::Get().Model(kSmallModel);
  EXPECT_EQ(model->InputSize(), cv::Size(320, 256));
  EXPECT_EQ(model->NumClasses(), 80);
  EXPECT_EQ(model->NumMaskCoefficients(), 32);
  ASSERT_EQ(model->ClassNames().size(), 80u);
  EXPECT_EQ(model->ClassNames()[67], "cell phone");
  EXPECT_EQ(model->Name(), "yolo(yolov8n-seg-320x256.onnx)");
  EXPECT_EQ(model->Device(), "opencv/cpu");
}

TEST(YoloSegmenterTest, TwoPlayersInBasketball1) {
  REQUIRE_INPUTS(kSmallModel, "basketball1.png");
  const Segmentation& seg = Photos::Get().Result(kSmallModel, "basketball1.png");
  EXPECT_EQ(seg.image_size, cv::Size(640, 480));
  const std::vector<const Instance*> persons = ConfidentPersons(seg, 0.5f);
  ASSERT_EQ(persons.size(), 2u);
  // One player on the left, one on the right, each most of the image tall.
  const Instance* left = persons[0]->box.x < persons[1]->box.x ? persons[0] : persons[1];
  const Instance* right = left == persons[0] ? persons[1] : persons[0];
  EXPECT_LT(left->box.br().x, 320);
  EXPECT_GT(right->box.x, 320);
  for (const Instance* person : persons) {
    EXPECT_GT(person->box.height, 300);
    ExpectPlausiblePersonMask(*person, 0.45, 0.9);
  }
  // The left player's torso is inside his mask; the wall beside him is not.
  EXPECT_EQ(left->mask.at<unsigned char>(200, 90), 255);
  EXPECT_EQ(left->mask.at<unsigned char>(300, 165), 0);
}

TEST(YoloSegmenterTest, ThePlayerInMessi5) {
  REQUIRE_INPUTS(kSmallModel, "messi5.jpg");
  const Segmentation& seg = Photos::Get().Result(kSmallModel, "messi5.jpg");
  const std::vector<const Instance*> persons = ConfidentPersons(seg, 0.8f);
  ASSERT_EQ(persons.size(), 1u);
  const Instance& player = *persons[0];
  EXPECT_GT(player.box.area(), 0.4 * 548 * 342);
  // Arms and legs spread wide: the mask fills a quarter of the box, not the box.
  ExpectPlausiblePersonMask(player, 0.2, 0.5);
  EXPECT_EQ(player.mask.at<unsigned char>(150, 230), 255);  // the shirt
  EXPECT_EQ(player.mask.at<unsigned char>(100, 400), 0);    // crowd inside the box
  // The ball is found as a ball, not as part of the player.
  bool ball = false;
  for (const Instance& instance : seg.instances) {
    ball |= instance.class_name == "sports ball" && instance.score > 0.5f;
  }
  EXPECT_TRUE(ball);
}

TEST(YoloSegmenterTest, PedestriansInVtestFrames) {
  for (int frame : {0, 100, 200}) {
    const std::string key = "vtest.avi#" + std::to_string(frame);
    REQUIRE_INPUTS(kSmallModel, key);
    const Segmentation& seg = Photos::Get().Result(kSmallModel, key);
    EXPECT_EQ(seg.image_size, cv::Size(768, 576));
    const std::vector<const Instance*> persons = ConfidentPersons(seg, 0.5f);
    EXPECT_GE(persons.size(), 3u) << key;
    for (const Instance* person : persons) {
      // Walkers are tall and narrow, and their masks fill most of their boxes.
      EXPECT_GT(person->box.height, person->box.width) << key;
      ExpectPlausiblePersonMask(*person, 0.45, 0.95);
    }
  }
}

TEST(YoloSegmenterTest, BothModelSizesAgreeOnClearDetections) {
  for (const std::string key : {"basketball1.png", "messi5.jpg", "vtest.avi#100"}) {
    REQUIRE_INPUTS(kLargeModel, key);
    DRVSLAM_SKIP_IF_MISSING(testing::SharedModel(kSmallModel), kSmallModel);
    const auto small = ConfidentPersons(Photos::Get().Result(kSmallModel, key), 0.6f);
    const auto large = ConfidentPersons(Photos::Get().Result(kLargeModel, key), 0.3f);
    ASSERT_FALSE(small.empty()) << key;
    double sum = 0.0;
    for (const Instance* a : small) {
      const Instance* best = nullptr;
      for (const Instance* b : large) {
        if (!best || BoxIoU(a->box, b->box) > BoxIoU(a->box, best->box)) best = b;
      }
      ASSERT_NE(best, nullptr) << key;
      const double box_iou = BoxIoU(a->box, best->box);
      EXPECT_GT(box_iou, 0.7) << key << " box " << a->box;
      EXPECT_GT(MaskIoU(a->mask, best->mask), 0.6) << key << " box " << a->box;
      sum += box_iou;
    }
    EXPECT_GT(sum / small.size(), 0.85) << key;
  }
}

TEST(YoloSegmenterTest, MasksOfOneFrameCarriedToTheNextMatchItsDetections) {
  // basketball1 -> basketball2: the players move a little; flow-propagated masks of frame 1
  // overlap frame 2's own masks better than frame 1's masks do.
  REQUIRE_INPUTS(kSmallModel, "basketball1.png");
  REQUIRE_INPUTS(kSmallModel, "basketball2.png");
  const Segmentation& first = Photos::Get().Result(kSmallModel, "basketball1.png");
  const Segmentation& second = Photos::Get().Result(kSmallModel, "basketball2.png");
  const Segmentation carried =
      MaskPropagator().Propagate(first, Photos::Get().Image("basketball1.png"),
                                 Photos::Get().Image("basketball2.png"), 1.0, 1);
  double before = 0.0;
  double after = 0.0;
  int matched = 0;
  for (const Instance* target : ConfidentPersons(second, 0.5f)) {
    for (std::size_t i = 0; i < first.instances.size(); ++i) {
      const Instance& source = first.instances[i];
      if (source.class_name != "person" || BoxIoU(source.box, target->box) < 0.5) continue;
      for (const Instance& moved : carried.instances) {
        if (moved.score == source.score && moved.class_id == source.class_id) {
          before += MaskIoU(source.mask, target->mask);
          after += MaskIoU(moved.mask, target->mask);
          ++matched;
        }
      }
    }
  }
  ASSERT_EQ(matched, 2);
  RecordProperty("mean_iou_unpropagated", std::to_string(before / matched));
  RecordProperty("mean_iou_propagated", std::to_string(after / matched));
  EXPECT_GT(after, before);
}

TEST(YoloSegmenterTest, GreyAndBgraImagesWorkOtherTypesAreRefused) {
  REQUIRE_INPUTS(kSmallModel, "basketball1.png");
  YoloSegmenter* model = Photos::Get().Model(kSmallModel);
  cv::Mat grey;
  cv::cvtColor(Photos::Get().Image("basketball1.png"), grey, cv::COLOR_BGR2GRAY);
  const Segmentation seg = model->Segment(grey, 0.0, 0);
  EXPECT_EQ(ConfidentPersons(seg, 0.5f).size(), 2u);  // basketball1 is a grey picture
  EXPECT_THROW(model->Segment(cv::Mat(), 0.0, 5), Error);
  EXPECT_THROW(model->Segment(cv::Mat(48, 64, CV_16UC3, cv::Scalar::all(0)), 0.0, 5), Error);
  EXPECT_THROW(model->Segment(cv::Mat(48, 64, CV_8UC2, cv::Scalar::all(0)), 0.0, 5), Error);
}

TEST(YoloSegmenterTest, SettingsClassNamesMustMatchTheModel) {
  const std::string path = testing::SharedModel(kSmallModel);
  DRVSLAM_SKIP_IF_MISSING(path, kSmallModel);
  SegmentationOptions options;
  options.model = path;
  options.class_names = {"a", "b"};
  try {
    YoloSegmenter segmenter(options);
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("Segmentation.classNames has 2 names"), std::string::npos);
  }
}

}  // namespace
}  // namespace drvslam
