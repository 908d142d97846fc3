// Model files that must be refused with a clear error; none needs the shared models except the
// int8 one, which is skipped when absent.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "drvslam/semantic/yolo_segmenter.h"
#include "onnx_builder.h"
#include "test_data.h"

namespace drvslam {
namespace {

namespace fs = std::filesystem;

class YoloModelErrorsTest : public ::testing::Test {
 protected:
  void SetUp() override { dir_ = testing::FreshTempDir("yolo_model_errors"); }
  void TearDown() override { fs::remove_all(dir_); }

  std::string WriteFile(const std::string& name, const std::string& bytes) {
    const std::string path = (dir_ / name).string();
    std::ofstream(path, std::ios::binary) << bytes;
    return path;
  }

  // Loading `path` must throw an Error that names it and says `why`.
  static void ExpectRefused(const std::string& path, const std::string& why) {
    SegmentationOptions options;
    options.model = path;
    try {
      YoloSegmenter segmenter(options);
      FAIL() << path << " was accepted";
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find(path), std::string::npos) << message;
      EXPECT_NE(message.find(why), std::string::npos) << message;
      EXPECT_EQ(message.find('\n'), std::string::npos) << message;
    }
  }

  fs::path dir_;
};

TEST_F(YoloModelErrorsTest, MissingAndGarbageFiles) {
  ExpectRefused((dir_ / "missing.onnx").string(), "does not exist");
  ExpectRefused(WriteFile("garbage.onnx", std::string(1000, '\xfe')), "not an ONNX model");
  ExpectRefused(WriteFile("text.onnx", "this is not a network\n"), "not an ONNX model");
  ExpectRefused(dir_.string(), "folder");
  SegmentationOptions none;
  EXPECT_THROW(YoloSegmenter{none}, Error);
}

TEST_F(YoloModelErrorsTest, WrongOutputLayoutsAndInputs) {
  testing::TinyModel one_output;
  ExpectRefused(WriteFile("one_output.onnx", one_output.Bytes()), "has 1 outputs");

  testing::TinyModel two_images;  // two 4-D outputs: no detection matrix
  two_images.outputs = {"a", "b"};
  ExpectRefused(WriteFile("two_images.onnx", two_images.Bytes()), "not a YOLO segmentation layout");

  testing::TinyModel dynamic;
  dynamic.input_dims = {1, 3, -1, -1};
  ExpectRefused(WriteFile("dynamic.onnx", dynamic.Bytes()), "dynamic size");

  testing::TinyModel vector_input;
  vector_input.input_dims = {1, 100};
  ExpectRefused(WriteFile("vector.onnx", vector_input.Bytes()), "expected 1x3xHxW");
}

TEST_F(YoloModelErrorsTest, DynamicInt8ModelIsRefusedWithoutACrash) {
  const std::string path = testing::SharedModel("yolov8n-seg_int8_dynamic.onnx");
  DRVSLAM_SKIP_IF_MISSING(path, "yolov8n-seg_int8_dynamic.onnx");
  ExpectRefused(path, "OpenCV DNN cannot load this model");
}

}  // namespace
}  // namespace drvslam
