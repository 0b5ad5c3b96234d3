// replaceFileAtomically: what it refuses, what it keeps of the file it replaces, and that no failure
// leaves its temporary file behind.
#include <signal.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>
#include <vector>

#include "costmap_layers/io/safe_write.hpp"
#include "temp_dir_test.hpp"

using costmap_layers::io::replaceFileAtomically;

namespace
{
std::string contents(const std::string& path)
{
  std::ifstream in(path, std::ios::binary);
  return std::string((std::istreambuf_iterator<char>(in)), std::istreambuf_iterator<char>());
}

/// The names in a folder, sorted.
std::vector<std::string> names(const std::string& dir)
{
  std::vector<std::string> out;
  for (const auto& entry : std::filesystem::directory_iterator(dir))
    out.push_back(entry.path().filename().string());
  std::sort(out.begin(), out.end());
  return out;
}
}  // namespace

class SafeWrite : public TempDirTest
{
};

TEST_F(SafeWrite, CreatesAndReplacesAFile)
{
  replaceFileAtomically(tmp("a.yaml"), "one\n");
  EXPECT_EQ(contents(tmp("a.yaml")), "one\n");
  replaceFileAtomically(tmp("a.yaml"), "two\n");
  EXPECT_EQ(contents(tmp("a.yaml")), "two\n");
  replaceFileAtomically(tmp("empty.yaml"), "");
  EXPECT_EQ(contents(tmp("empty.yaml")), "");
  EXPECT_EQ(names(tmp_), (std::vector<std::string>{"a.yaml", "empty.yaml"}));  // no temporary file left
}

TEST_F(SafeWrite, KeepsModeAndOwner)
{
  for (const mode_t mode : {mode_t{0600}, mode_t{0640}, mode_t{0604}})
  {
    std::ofstream(tmp("m.yaml")) << "old\n";
    ASSERT_EQ(::chmod(tmp("m.yaml").c_str(), mode), 0);
    replaceFileAtomically(tmp("m.yaml"), "new\n");
    struct stat st
    {
    };
    ASSERT_EQ(::stat(tmp("m.yaml").c_str(), &st), 0);
    EXPECT_EQ(st.st_mode & 07777, mode);
  }
  // Another owner and group: only root can give a file away, and the tests run as root in the package's
  // containers; as another user the owner stays the user's own, which the replacement keeps as well.
  const uid_t uid = ::geteuid() == 0 ? 1234 : ::geteuid();
  const gid_t gid = ::geteuid() == 0 ? 5678 : ::getegid();
  std::ofstream(tmp("o.yaml")) << "old\n";
  ASSERT_EQ(::chown(tmp("o.yaml").c_str(), uid, gid), 0);
  replaceFileAtomically(tmp("o.yaml"), "new\n");
  struct stat st
  {
  };
  ASSERT_EQ(::stat(tmp("o.yaml").c_str(), &st), 0);
  EXPECT_EQ(st.st_uid, uid);
  EXPECT_EQ(st.st_gid, gid);
  EXPECT_EQ(contents(tmp("o.yaml")), "new\n");
}

TEST_F(SafeWrite, RefusesLinksFoldersAndFifosAndLeavesNothing)
{
  std::ofstream(tmp("target.yaml")) << "keep\n";
  ASSERT_EQ(::symlink(tmp("target.yaml").c_str(), tmp("link.yaml").c_str()), 0);
  EXPECT_THROW(replaceFileAtomically(tmp("link.yaml"), "new\n"), std::runtime_error);
  ASSERT_EQ(::mkdir(tmp("dir.yaml").c_str(), 0755), 0);
  EXPECT_THROW(replaceFileAtomically(tmp("dir.yaml"), "new\n"), std::runtime_error);
  ASSERT_EQ(::mkfifo(tmp("fifo.yaml").c_str(), 0644), 0);
  EXPECT_THROW(replaceFileAtomically(tmp("fifo.yaml"), "new\n"), std::runtime_error);  // and does not wait
  EXPECT_THROW(replaceFileAtomically(tmp("no/such/folder.yaml"), "new\n"), std::runtime_error);
  EXPECT_EQ(contents(tmp("target.yaml")), "keep\n");
  struct stat st
  {
  };
  ASSERT_EQ(::lstat(tmp("link.yaml").c_str(), &st), 0);
  EXPECT_TRUE(S_ISLNK(st.st_mode));
  EXPECT_EQ(names(tmp_), (std::vector<std::string>{"dir.yaml", "fifo.yaml", "link.yaml", "target.yaml"}));
}

TEST_F(SafeWrite, AFailedWriteRemovesTheTemporaryFileAndKeepsTheTarget)
{
  // A file size limit of 100 bytes makes the write fail half-way (EFBIG once SIGXFSZ is ignored). In a
  // child process: the limit and the signal disposition are the process's own.
  std::ofstream(tmp("big.yaml")) << "old\n";
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0)
  {
    ::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{100, 100};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try
    {
      replaceFileAtomically(tmp("big.yaml"), std::string(1000, 'x'));
      ::_exit(1);  // written although it could not be
    }
    catch (const std::runtime_error& e)
    {
      ::_exit(std::string(e.what()).find("writing the temporary file failed") != std::string::npos ? 0 : 2);
    }
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  ASSERT_TRUE(WIFEXITED(status));
  EXPECT_EQ(WEXITSTATUS(status), 0);
  EXPECT_EQ(contents(tmp("big.yaml")), "old\n");
  EXPECT_EQ(names(tmp_), (std::vector<std::string>{"big.yaml"}));
}

TEST_F(SafeWrite, ReplacesByRenameNeverInPlace)
{
  // A reader holding the old file keeps reading the old text: the new one is another inode renamed over
  // the name, and nothing else is left in the folder.
  std::ofstream(tmp("z.yaml")) << "0\n";
  struct stat before
  {
  };
  ASSERT_EQ(::stat(tmp("z.yaml").c_str(), &before), 0);
  std::ifstream reader(tmp("z.yaml"));
  replaceFileAtomically(tmp("z.yaml"), "1\n");
  struct stat after
  {
  };
  ASSERT_EQ(::stat(tmp("z.yaml").c_str(), &after), 0);
  EXPECT_NE(before.st_ino, after.st_ino);
  std::string old;
  std::getline(reader, old);
  EXPECT_EQ(old, "0");
  EXPECT_EQ(contents(tmp("z.yaml")), "1\n");
  EXPECT_EQ(names(tmp_), (std::vector<std::string>{"z.yaml"}));
}
