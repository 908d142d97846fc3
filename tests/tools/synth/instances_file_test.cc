#include "drvslam/tools/synth/instances_file.h"

#include <gtest/gtest.h>

#include "drvslam/core/error.h"
#include "test_folder.h"

namespace drvslam::synth {
namespace {

using testing::TestFolder;
using testing::WriteFileText;

InstancesFile Example() {
  InstancesFile file;
  file.instances = {{1, "person", 0}, {2, "book", 73}, {7, "cell phone", 67}};
  file.frame_stamps = {1305031102.175304, 1305031102.208637};
  file.moving = {{true, false, false}, {false, false, true}};
  return file;
}

// The error message of reading `text` as an instances file, or "" when it reads fine.
std::string ReadError(const TestFolder& folder, const std::string& text) {
  const std::string path = folder / "instances.txt";
  WriteFileText(path, text);
  try {
    ReadInstancesFile(path);
  } catch (const Error& e) {
    return e.what();
  }
  return "";
}

TEST(InstancesFileTest, RoundTripKeepsEverything) {
  TestFolder folder("instances_round_trip");
  const InstancesFile written = Example();
  WriteInstancesFile(folder / "instances.txt", written);
  const InstancesFile read = ReadInstancesFile(folder / "instances.txt");
  ASSERT_EQ(read.instances.size(), 3u);
  EXPECT_EQ(read.instances[2].id, 7);
  EXPECT_EQ(read.instances[2].class_name, "cell phone");
  EXPECT_EQ(read.instances[2].coco_id, 67);
  ASSERT_EQ(read.frame_stamps.size(), 2u);
  EXPECT_NEAR(read.frame_stamps[0], 1305031102.175304, 1e-6);
  EXPECT_EQ(read.moving, written.moving);
}

TEST(InstancesFileTest, WritesTheFixedFormat) {
  const std::string text = FormatInstancesFile(Example());
  EXPECT_EQ(text,
            "# drvslam synthetic instances\n"
            "# instance <id> <class_name_with_spaces_as_underscores> <coco_id>\n"
            "instance 1 person 0\n"
            "instance 2 book 73\n"
            "instance 7 cell_phone 67\n"
            "# frame <rgb timestamp> <moving flag 0/1 for each instance above, in the same "
            "order>\n"
            "frame 1305031102.175304 1 0 0\n"
            "frame 1305031102.208637 0 0 1\n");
}

TEST(InstancesFileTest, AcceptsNoInstancesAndNonCocoClasses) {
  TestFolder folder("instances_empty");
  const std::string path = folder / "instances.txt";
  WriteFileText(path, "frame 1.0\nframe 2.0\n");
  const InstancesFile file = ReadInstancesFile(path);
  EXPECT_TRUE(file.instances.empty());
  EXPECT_EQ(file.frame_stamps.size(), 2u);
  WriteFileText(path, "instance 3 robot_arm -1\nframe 1.0 1\n");
  EXPECT_EQ(ReadInstancesFile(path).instances[0].class_name, "robot arm");
}

TEST(InstancesFileTest, BadInputNamesFileAndLine) {
  TestFolder folder("instances_bad");
  const std::string head = "# comment\ninstance 1 person 0\n";
  const struct {
    std::string text;
    std::string expected;
  } cases[] = {
      {head + "frame 1.0 1 0\n", ":3: expected a timestamp and 1 moving flags, found 3"},
      {head + "frame 1.0 2\n", ":3: moving flag '2' for instance 1 is not 0 or 1"},
      {head + "frame 2.0 1\nframe 1.0 0\n", ":4: timestamp 1.0 does not increase"},
      {head + "frame abc 1\n", ":3: 'abc' is not a number"},
      {head + "frame nan 1\n", ":3: timestamp 'nan' is not finite"},
      {head + "instance 1 book 73\n", ":3: duplicate instance id 1"},
      {head + "instance 0 book 73\n", ":3: instance id 0 is outside 1..65535"},
      {head + "instance 70000 book 73\n", ":3: instance id 70000 is outside 1..65535"},
      {head + "instance 2 book 74\n", ":3: class 'book' does not match COCO id 74 ('clock')"},
      {head + "instance 2 book 80\n", ":3: COCO id 80 is outside -1..79"},
      {head + "instance 2 book x\n", ":3: COCO id 'x' is not an integer"},
      {head + "instance 2.5 book 73\n", ":3: instance id '2.5' is not an integer"},
      {head + "instance 2 book\n", ":3: expected 'instance <id> <class_name> <coco_id>'"},
      {head + "frame 1.0 1\ninstance 2 book 73\n", ":4: instance line after the first frame"},
      {head + "object 2 book 73\n", ":3: unknown keyword 'object'"},
  };
  for (const auto& c : cases) {
    const std::string message = ReadError(folder, c.text);
    EXPECT_NE(message.find(folder / "instances.txt"), std::string::npos) << message;
    EXPECT_NE(message.find(c.expected), std::string::npos)
        << "got: " << message << "\nexpected: " << c.expected;
  }
  EXPECT_THROW(ReadInstancesFile(folder / "missing.txt"), Error);
}

TEST(InstancesFileTest, RefusesToWriteInconsistentContents) {
  InstancesFile file = Example();
  file.moving[1].pop_back();
  EXPECT_THROW(FormatInstancesFile(file), Error);
  file = Example();
  file.instances[1].id = 1;
  EXPECT_THROW(FormatInstancesFile(file), Error);
  file = Example();
  file.frame_stamps.pop_back();
  EXPECT_THROW(FormatInstancesFile(file), Error);
}

}  // namespace
}  // namespace drvslam::synth
