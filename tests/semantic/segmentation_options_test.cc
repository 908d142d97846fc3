#include "drvslam/semantic/segmentation_options.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>
#include <vector>

#include "drvslam/core/coco_classes.h"
#include "drvslam/core/error.h"
#include "drvslam/semantic/class_table.h"
#include "drvslam/semantic/segmenter_factory.h"
#include "test_data.h"

namespace drvslam {
namespace {

class SegmentationOptionsTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::FreshTempDir("segmentation_options"); }
  void TearDown() override { std::filesystem::remove_all(dir_); }

  std::string Write(const std::string& body) {
    const std::string path = (dir_ / "settings.yaml").string();
    std::ofstream(path) << "%YAML:1.0\n" << body;
    return path;
  }

  void ExpectError(const std::string& body, const std::string& key) {
    const std::string path = Write(body);
    try {
      LoadSegmentationOptions(SettingsFile(path));
      FAIL() << "no error for:\n" << body;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(key), std::string::npos) << message;
    }
  }

  std::filesystem::path dir_;
};

TEST_F(SegmentationOptionsTest, DefaultsPassAndAbsentKeysKeepThem) {
  const SegmentationOptions defaults;
  EXPECT_NO_THROW(defaults.Check());
  const SegmentationOptions loaded =
      LoadSegmentationOptions(SettingsFile(Write("Camera.fx: 500\n")));
  EXPECT_EQ(loaded.backend, SegmenterBackend::kAuto);
  EXPECT_DOUBLE_EQ(loaded.score_threshold, 0.25);
  EXPECT_EQ(loaded.moving_classes.size(), 12u);
  EXPECT_EQ(loaded.key_objects.size(), 9u);
  EXPECT_EQ(loaded.propagation, MaskPropagation::kObjects);
}

TEST_F(SegmentationOptionsTest, AutoIsTheDefaultBackendAndTheRuntimeBuildsNothingForIt) {
  // `drvslam config --dump` writes the default back: it must load as the same backend.
  const SegmentationOptions dumped =
      LoadSegmentationOptions(SettingsFile(Write("Segmentation.backend: \"auto\"\n")));
  EXPECT_EQ(dumped.backend, SegmenterBackend::kAuto);
  EXPECT_EQ(ToString(dumped.backend), "auto");
  EXPECT_EQ(CreateSegmenter(dumped), nullptr);
}

TEST_F(SegmentationOptionsTest, ReadsEveryKey) {
  const SegmentationOptions o =
      LoadSegmentationOptions(SettingsFile(Write("Segmentation.backend: yolo\n"
                                                 "Segmentation.model: \"models/yolo.onnx\"\n"
                                                 "Segmentation.classNames: [a, b]\n"
                                                 "Segmentation.scoreThreshold: 0.4\n"
                                                 "Segmentation.nmsThreshold: 0.6\n"
                                                 "Segmentation.maskThreshold: 0.3\n"
                                                 "Segmentation.maxDetections: 7\n"
                                                 "Segmentation.dnnBackend: opencv\n"
                                                 "Segmentation.dnnTarget: cpu\n"
                                                 "Segmentation.dnnThreads: 2\n"
                                                 "Segmentation.masksDir: seg\n"
                                                 "Segmentation.maskNaming: index\n"
                                                 "Segmentation.maskClass: dog\n"
                                                 "Segmentation.propagation: sparse\n"
                                                 "Segmentation.carryFrames: 4\n"
                                                 "Segmentation.carryMinSupport: 5\n"
                                                 "Segmentation.movingClasses: \"person, dog\"\n"
                                                 "Segmentation.keyObjects: [cup]\n")));
  EXPECT_EQ(o.backend, SegmenterBackend::kYolo);
  EXPECT_EQ(o.model, "models/yolo.onnx");
  EXPECT_EQ(o.class_names, (std::vector<std::string>{"a", "b"}));
  EXPECT_DOUBLE_EQ(o.score_threshold, 0.4);
  EXPECT_DOUBLE_EQ(o.nms_threshold, 0.6);
  EXPECT_DOUBLE_EQ(o.mask_threshold, 0.3);
  EXPECT_EQ(o.max_detections, 7);
  EXPECT_EQ(o.dnn_backend, DnnBackend::kOpenCv);
  EXPECT_EQ(o.dnn_target, DnnTarget::kCpu);
  EXPECT_EQ(o.dnn_threads, 2);
  EXPECT_EQ(o.masks_dir, "seg");
  EXPECT_EQ(o.mask_naming, MaskNaming::kIndex);
  EXPECT_EQ(o.mask_class, "dog");
  EXPECT_EQ(o.propagation, MaskPropagation::kSparseFlow);
  EXPECT_EQ(o.carry_frames, 4);
  EXPECT_EQ(o.carry_min_support, 5);
  EXPECT_EQ(o.moving_classes, (std::vector<std::string>{"person", "dog"}));
  EXPECT_EQ(o.key_objects, (std::vector<std::string>{"cup"}));
}

TEST_F(SegmentationOptionsTest, BadValuesNameTheirKey) {
  ExpectError("Segmentation.backend: detectron\n", "Segmentation.backend");
  ExpectError("Segmentation.backend: yolo\n", "Segmentation.model");
  ExpectError("Segmentation.scoreThreshold: 1.5\n", "Segmentation.scoreThreshold");
  ExpectError("Segmentation.nmsThreshold: -0.1\n", "Segmentation.nmsThreshold");
  ExpectError("Segmentation.maskThreshold: 1.0\n", "Segmentation.maskThreshold");
  ExpectError("Segmentation.maxDetections: 0\n", "Segmentation.maxDetections");
  ExpectError("Segmentation.dnnThreads: -2\n", "Segmentation.dnnThreads");
  ExpectError("Segmentation.dnnBackend: tensorrt\n", "Segmentation.dnnBackend");
  ExpectError("Segmentation.dnnBackend: opencv\nSegmentation.dnnTarget: cuda\n",
              "Segmentation.dnnTarget");
  ExpectError("Segmentation.maskNaming: alphabetical\n", "Segmentation.maskNaming");
  ExpectError("Segmentation.maskClass: unicorn\n", "Segmentation.maskClass");
  ExpectError("Segmentation.propagation: magic\n", "Segmentation.propagation");
  ExpectError("Segmentation.carryFrames: 0\n", "Segmentation.carryFrames");
  ExpectError("Segmentation.carryMinSupport: 0\n", "Segmentation.carryMinSupport");
  ExpectError("Segmentation.scoreThreshold: high\n", "Segmentation.scoreThreshold");
}

std::vector<std::string> CocoNames() {
  std::vector<std::string> names;
  for (std::string_view name : CocoClassNames()) names.emplace_back(name);
  return names;
}

TEST(ClassTableTest, DefaultListsSplitCocoIntoMovingKeyAndStatic) {
  const ClassTable table(CocoNames(), SegmentationOptions());
  EXPECT_EQ(table.Size(), 80);
  for (const char* name : {"person", "bicycle", "car", "motorcycle", "bus", "truck", "bird", "cat",
                           "dog", "horse", "sheep", "cow"}) {
    EXPECT_TRUE(table.IsPotentiallyMoving(CocoClassId(name))) << name;
    EXPECT_FALSE(table.IsKeyObject(CocoClassId(name))) << name;
  }
  for (const char* name :
       {"book", "laptop", "keyboard", "mouse", "tv", "cup", "bottle", "cell phone", "remote"}) {
    EXPECT_TRUE(table.IsKeyObject(CocoClassId(name))) << name;
    EXPECT_FALSE(table.IsPotentiallyMoving(CocoClassId(name))) << name;
  }
  int moving = 0;
  int key = 0;
  for (int id = 0; id < 80; ++id) {
    moving += table.IsPotentiallyMoving(id);
    key += table.IsKeyObject(id);
  }
  EXPECT_EQ(moving, 12);
  EXPECT_EQ(key, 9);
  EXPECT_TRUE(table.IsStatic(CocoClassId("chair")));
  EXPECT_TRUE(table.IsStatic(-1));
  EXPECT_TRUE(table.IsStatic(80));
  EXPECT_EQ(table.Name(67), "cell phone");
  EXPECT_EQ(table.Name(99), "class99");
}

TEST(ClassTableTest, NamesMatchIgnoringCaseAndUnderscores) {
  const ClassTable table({"Person", "cell phone", "forklift"}, {"person", "forklift", "zebra"},
                         {"cell_phone"});
  EXPECT_TRUE(table.IsPotentiallyMoving(0));
  EXPECT_TRUE(table.IsPotentiallyMoving(2));
  EXPECT_TRUE(table.IsKeyObject(1));
  EXPECT_FALSE(table.IsPotentiallyMoving(1));
  EXPECT_EQ(table.Id("CELL_PHONE"), 1);
  EXPECT_EQ(table.Id("zebra"), -1);
}

}  // namespace
}  // namespace drvslam
