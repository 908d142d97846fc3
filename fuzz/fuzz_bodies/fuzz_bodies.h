// The fuzz bodies: for each parser of input from outside (network messages, files from other
// users and robots), a function that turns arbitrary bytes into that parser's input and runs
// it. A parser may reject its input only with drvslam::Error, the one error type the library
// throws for bad input: a body catches that and nothing else, so any other exception, a crash,
// a sanitizer report, a hang or an unbounded allocation is a finding. The libFuzzer targets
// (fuzz/<name>_fuzzer.cc) call one body each; fuzz_regression_test replays fuzz/corpus/<name>/
// and fuzz/regressions/<name>/ through them in every build.
#pragma once

#include <cstddef>
#include <cstdint>
#include <vector>

namespace drvslam::fuzz {

// ros2_image: sensor_msgs/Image through ColourImage and DepthImageMetres, and
// sensor_msgs/CameraInfo through CameraFromInfo (ros2/image_messages.h), every field of the
// messages taken from the bytes (layout in ros2_image_body.cc). Only with Cyclone DDS.
void RunRos2ImageBody(const std::uint8_t* data, std::size_t size);
// map_file: `--load-map`: ReadMapFile, then RestoreMap into an empty map. The first byte is a
// flag: odd rewrites the header's file length and the trailing CRC-32 to match the bytes that
// follow, so mutations get past the checksum into the sections; even leaves them as they are.
void RunMapFileBody(const std::uint8_t* data, std::size_t size);
// settings: `--config`: SettingsFile (OpenCV FileStorage), every module's option loader and the
// unknown-key check (strict and not), as the runner resolves a settings file.
void RunSettingsBody(const std::uint8_t* data, std::size_t size);
// tum_text: the TUM-layout text files; the first byte picks the reader (tum_text_body.cc).
void RunTumTextBody(const std::uint8_t* data, std::size_t size);
// vocabulary: LoadVocabulary (text or binary, by the magic), then one bag of words through the
// loaded tree.
void RunVocabularyBody(const std::uint8_t* data, std::size_t size);
// onnx_metadata: what the YOLO segmenter reads of an ONNX file besides the network: the first
// byte even: ParseOnnxModelInfo of the rest, then ParseClassNamesMetadata of its "names";
// odd: ParseClassNamesMetadata of the rest.
void RunOnnxMetadataBody(const std::uint8_t* data, std::size_t size);

struct FuzzBody {
  const char* name;  // the corpus folder and the fuzzer: fuzz/corpus/<name>, <name>_fuzzer
  void (*run)(const std::uint8_t* data, std::size_t size);
};

// Every body of this build (ros2_image only with Cyclone DDS).
const std::vector<FuzzBody>& FuzzBodies();

// Turns logging off: parsers warn about what they tolerate, and at millions of inputs that
// output would cost more than the parsing.
void SilenceLogging();

}  // namespace drvslam::fuzz
