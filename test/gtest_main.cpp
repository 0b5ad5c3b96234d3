// catkin_add_gtest links gtest without gtest_main: one shared main for every test binary.
#include <gtest/gtest.h>

int main(int argc, char** argv)
{
  testing::InitGoogleTest(&argc, argv);
  return RUN_ALL_TESTS();
}
