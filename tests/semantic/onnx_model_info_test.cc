#include "drvslam/semantic/onnx_model_info.h"

#include <gtest/gtest.h>

#include <fstream>
#include <string>

#include "drvslam/core/error.h"
#include "onnx_builder.h"
#include "test_data.h"

namespace drvslam {
namespace {

using testing::TinyModel;

TEST(OnnxModelInfoTest, ReadsInputShapeOutputsAndMetadata) {
  TinyModel model;
  model.input_dims = {1, 3, 256, 320};
  model.outputs = {"output0", "output1"};
  model.metadata = {{"names", "{0: 'person', 1: 'bicycle'}"}, {"stride", "32"}};
  model.with_initializer = true;
  const OnnxModelInfo info = ParseOnnxModelInfo(model.Bytes(), "tiny.onnx");
  EXPECT_EQ(info.ir_version, 7);
  EXPECT_EQ(info.producer_name, "drvslam-test");
  EXPECT_EQ(info.input_name, "images");  // the initializer listed as an input is skipped
  EXPECT_EQ(info.input_shape, (std::vector<std::int64_t>{1, 3, 256, 320}));
  EXPECT_EQ(info.output_names, (std::vector<std::string>{"output0", "output1"}));
  ASSERT_EQ(info.metadata.count("names"), 1u);
  EXPECT_EQ(info.metadata.at("stride"), "32");
  EXPECT_EQ(ParseClassNamesMetadata(info.metadata.at("names")),
            (std::vector<std::string>{"person", "bicycle"}));
}

TEST(OnnxModelInfoTest, SymbolicDimensionsAreMinusOne) {
  TinyModel model;
  model.input_dims = {-1, 3, -1, 640};
  const OnnxModelInfo info = ParseOnnxModelInfo(model.Bytes(), "dynamic.onnx");
  EXPECT_EQ(info.input_shape, (std::vector<std::int64_t>{-1, 3, -1, 640}));
}

TEST(OnnxModelInfoTest, GarbageAndTruncatedFilesAreNotOnnx) {
  const std::string good = TinyModel().Bytes();
  const auto expect_error = [](const std::string& bytes, const std::string& needle) {
    try {
      ParseOnnxModelInfo(bytes, "bad.onnx");
      FAIL() << "no error for " << needle;
    } catch (const Error& e) {
      const std::string message = e.what();
      EXPECT_NE(message.find("bad.onnx"), std::string::npos) << message;
      EXPECT_NE(message.find(needle), std::string::npos) << message;
    }
  };
  expect_error(good.substr(0, good.size() - 7), "not an ONNX model");
  expect_error("hello, this is a text file\n", "not an ONNX model");
  expect_error(std::string("\x89PNG\r\n\x1a\n", 8) + std::string(100, '\0'), "not an ONNX model");
  expect_error("", "not an ONNX model");
  expect_error(std::string(64, '\xff'), "not an ONNX model");
}

TEST(OnnxModelInfoTest, MissingFileIsNamed) {
  try {
    ReadOnnxModelInfo("/nonexistent/model.onnx");
    FAIL();
  } catch (const Error& e) {
    EXPECT_NE(std::string(e.what()).find("/nonexistent/model.onnx"), std::string::npos);
    EXPECT_NE(std::string(e.what()).find("does not exist"), std::string::npos);
  }
}

TEST(ClassNamesMetadataTest, ParsesPythonAndJsonDicts) {
  EXPECT_EQ(ParseClassNamesMetadata("{0: 'person', 1: 'traffic light', 2: \"it's\"}"),
            (std::vector<std::string>{"person", "traffic light", "it's"}));
  EXPECT_EQ(ParseClassNamesMetadata(R"({"0": "a", "1": "b"})"),
            (std::vector<std::string>{"a", "b"}));
  // Out of order keys are placed by id.
  EXPECT_EQ(ParseClassNamesMetadata("{1: 'b', 0: 'a'}"), (std::vector<std::string>{"a", "b"}));
  EXPECT_TRUE(ParseClassNamesMetadata("{0: 'a', 2: 'c'}").empty());  // gap
  EXPECT_TRUE(ParseClassNamesMetadata("{0: 'a', 0: 'b'}").empty());  // duplicate
  EXPECT_TRUE(ParseClassNamesMetadata("['a', 'b']").empty());
  EXPECT_TRUE(ParseClassNamesMetadata("{0: 'a'").empty());
  EXPECT_TRUE(ParseClassNamesMetadata("").empty());
}

TEST(OnnxModelInfoTest, SharedModelsDeclareTheirSizeAndCocoNames) {
  const std::string path = testing::SharedModel("yolov8n-seg-320x256.onnx");
  DRVSLAM_SKIP_IF_MISSING(path, "yolov8n-seg-320x256.onnx");
  const OnnxModelInfo info = ReadOnnxModelInfo(path);
  EXPECT_EQ(info.input_name, "images");
  EXPECT_EQ(info.input_shape, (std::vector<std::int64_t>{1, 3, 256, 320}));
  EXPECT_EQ(info.output_names, (std::vector<std::string>{"output0", "output1"}));
  ASSERT_EQ(info.metadata.count("names"), 1u);
  const std::vector<std::string> names = ParseClassNamesMetadata(info.metadata.at("names"));
  ASSERT_EQ(names.size(), 80u);
  EXPECT_EQ(names[0], "person");
  EXPECT_EQ(names[67], "cell phone");
  EXPECT_EQ(names[79], "toothbrush");
}

}  // namespace
}  // namespace drvslam
