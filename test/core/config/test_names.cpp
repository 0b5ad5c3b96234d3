// One rule per kind of name (input_error.hpp): frame ids, plugin names, shape names. Each case is a
// literal written from the rule as documented, not from the code's output.
#include <gtest/gtest.h>

#include <string>

#include "costmap_layers/core/config/input_error.hpp"

using costmap_layers::frameIdProblem;
using costmap_layers::kMaxNameLength;
using costmap_layers::labelProblem;
using costmap_layers::pluginNameProblem;

TEST(Names, FrameIdsTakePrintableAsciiWithoutSpaces)
{
  for (const char* good : {"map", "odom", "base_link", "robot1/base_link", "/map", "camera-depth.optical", "a"})
    EXPECT_EQ(frameIdProblem(good), "") << good;
  EXPECT_NE(frameIdProblem(""), "");
  // The example and others of the same class: a line break, a tab, a space, a DEL, a NUL, UTF-8.
  for (const std::string bad : {std::string("map\nodom"), std::string("map\todom"), std::string("map odom"),
                                std::string("map\x7f"), std::string("map\0x", 5), std::string("kar\xc3\xa9")})
  {
    const std::string why = frameIdProblem(bad);
    EXPECT_NE(why, "") << bad;
    EXPECT_NE(why.find("position 3"), std::string::npos) << why;  // the first bad character is named
  }
  EXPECT_NE(frameIdProblem("map\nodom").find("character code 10"), std::string::npos);
}

TEST(Names, LengthLimitIsInclusive)
{
  EXPECT_EQ(frameIdProblem(std::string(kMaxNameLength, 'f')), "");
  EXPECT_NE(frameIdProblem(std::string(kMaxNameLength + 1, 'f')).find("257 characters"), std::string::npos);
  EXPECT_EQ(pluginNameProblem(std::string(kMaxNameLength, 'p')), "");
  EXPECT_NE(pluginNameProblem(std::string(kMaxNameLength + 1, 'p')), "");
  EXPECT_EQ(labelProblem(std::string(kMaxNameLength, 'l')), "");
  EXPECT_NE(labelProblem(std::string(kMaxNameLength + 1, 'l')), "");
  // A megabyte name is quoted clipped, not whole.
  EXPECT_LT(frameIdProblem(std::string(1 << 20, 'x')).size(), 400u);
}

TEST(Names, PluginNamesAreRelativeRosNames)
{
  for (const char* good : {"static_layer", "obstacles", "inflation2", "sensors/obstacles", "a/_b", "L"})
    EXPECT_EQ(pluginNameProblem(good), "") << good;
  // "static layer" is what costmap_tool used to build and costmap_node refused; the rest are the same
  // class: what roscpp cannot make a namespace of.
  for (const char* bad : {"static layer", "", "/static", "~static", "static/", "a//b", "2d", "_x", "inflation-layer",
                          "sta\ntic", "caf\xc3\xa9"})
    EXPECT_NE(pluginNameProblem(bad), "") << bad;
  EXPECT_NE(pluginNameProblem("static layer").find("character code 32 at position 6"), std::string::npos)
      << pluginNameProblem("static layer");
}

TEST(Names, LabelsRefuseOnlyControlCharacters)
{
  for (const char* good : {"fence", "corner keepout", "zone #2 (dock)", "K\xc3\xbc" "che"})
    EXPECT_EQ(labelProblem(good), "") << good;
  for (const std::string bad : {std::string(""), std::string("a\nb"), std::string("a\rb"), std::string("\x1b[31m"),
                                std::string("a\x7f"), std::string("a\0b", 3)})
    EXPECT_NE(labelProblem(bad), "") << bad;
}
