// A gtest fixture with a fresh temporary folder per test, removed afterwards: what the file tests
// write their inputs and outputs into.
#pragma once

#include <gtest/gtest.h>
#include <stdlib.h>

#include <filesystem>
#include <string>
#include <system_error>

class TempDirTest : public ::testing::Test
{
protected:
  void SetUp() override
  {
    char pattern[] = "/tmp/costmap_io_test_XXXXXX";
    const char* dir = mkdtemp(pattern);
    ASSERT_NE(dir, nullptr);
    tmp_ = dir;
  }
  void TearDown() override
  {
    std::error_code ec;
    if (!tmp_.empty()) std::filesystem::remove_all(tmp_, ec);
  }
  /// A path inside the folder.
  std::string tmp(const std::string& name) const { return tmp_ + "/" + name; }
  std::string tmp_;
};
