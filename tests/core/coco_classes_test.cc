#include "drvslam/core/coco_classes.h"

#include <gtest/gtest.h>

namespace drvslam {
namespace {

TEST(CocoClassesTest, KnownIdsMatchTheYoloOrder) {
  EXPECT_EQ(CocoClassId("person"), 0);
  EXPECT_EQ(CocoClassId("car"), 2);
  EXPECT_EQ(CocoClassId("cup"), 41);
  EXPECT_EQ(CocoClassId("laptop"), 63);
  EXPECT_EQ(CocoClassId("keyboard"), 66);
  EXPECT_EQ(CocoClassId("book"), 73);
  EXPECT_EQ(CocoClassId("toothbrush"), 79);
  EXPECT_EQ(CocoClassId("unicorn"), -1);
  EXPECT_EQ(CocoClassName(73), "book");
  EXPECT_EQ(CocoClassName(80), "class80");
}

}  // namespace
}  // namespace drvslam
