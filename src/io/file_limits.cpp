#include "costmap_layers/io/file_limits.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <stdexcept>

namespace costmap_layers
{
namespace io
{
namespace
{
[[noreturn]] void fail(const std::string& path, const std::string& problem)
{
  throw std::runtime_error("'" + path + "': " + problem);
}

const char* kindOf(mode_t mode)
{
  if (S_ISDIR(mode)) return "a directory";
  if (S_ISFIFO(mode)) return "a FIFO (named pipe)";
  if (S_ISCHR(mode)) return "a character device";
  if (S_ISBLK(mode)) return "a block device";
  if (S_ISSOCK(mode)) return "a socket";
  if (S_ISLNK(mode)) return "a symbolic link";
  return "not a regular file";
}

void checkStat(const std::string& path, const std::string& what, const struct stat& st, uint64_t max_bytes)
{
  if (!S_ISREG(st.st_mode))
    fail(path, "cannot read " + what + ": it is " + kindOf(st.st_mode) + ", not a regular file");
  if (st.st_size < 0 || static_cast<uint64_t>(st.st_size) > max_bytes)
    fail(path, what + " is too large: " + std::to_string(static_cast<long long>(st.st_size)) + " bytes, the limit is " +
                   std::to_string(max_bytes));
}

/// Closes the descriptor on every way out.
struct Fd
{
  int fd = -1;
  ~Fd()
  {
    if (fd >= 0) ::close(fd);
  }
};

/// Reads up to n bytes at the end of out; returns how many were read (0 at the end of the file).
std::size_t readSome(const std::string& path, const std::string& what, int fd, std::vector<uint8_t>& out, std::size_t n)
{
  const std::size_t old = out.size();
  out.resize(old + n);
  std::size_t got = 0;
  while (got < n)
  {
    const ssize_t r = ::read(fd, out.data() + old + got, n - got);
    if (r < 0 && errno == EINTR) continue;
    if (r < 0) fail(path, "error while reading " + what + " (" + std::strerror(errno) + ")");
    if (r == 0) break;
    got += static_cast<std::size_t>(r);
  }
  out.resize(old + got);
  return got;
}
}  // namespace

std::vector<uint8_t> readRegularFile(const std::string& path, const std::string& what, uint64_t max_bytes,
                                     const FileHeadCheck& head_check)
{
  // stat before open: opening a device can have effects of its own, and a FIFO would wait.
  struct stat st;
  if (::stat(path.c_str(), &st) != 0) fail(path, "cannot open " + what + " (" + std::strerror(errno) + ")");
  checkStat(path, what, st, max_bytes);
  // O_NONBLOCK: if the path was swapped for a FIFO after stat, open returns at once instead of
  // waiting for a writer; fstat then refuses it.
  Fd f;
  f.fd = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_NOCTTY | O_CLOEXEC);
  if (f.fd < 0) fail(path, "cannot open " + what + " (" + std::strerror(errno) + ")");
  if (::fstat(f.fd, &st) != 0) fail(path, "cannot stat " + what + " (" + std::strerror(errno) + ")");
  checkStat(path, what, st, max_bytes);
  const int flags = ::fcntl(f.fd, F_GETFL);
  if (flags >= 0) ::fcntl(f.fd, F_SETFL, flags & ~O_NONBLOCK);

  const uint64_t size = static_cast<uint64_t>(st.st_size);
  std::vector<uint8_t> bytes;
  const std::size_t head_n = static_cast<std::size_t>(std::min<uint64_t>(size, kFileHeadBytes));
  bytes.reserve(head_n);
  readSome(path, what, f.fd, bytes, head_n);
  if (head_check) head_check(bytes, size);
  if (size > bytes.size())
  {
    bytes.reserve(static_cast<std::size_t>(size));
    readSome(path, what, f.fd, bytes, static_cast<std::size_t>(size) - bytes.size());
  }
  // The file may have grown since fstat: a byte more than the size checked is refused, not read.
  std::vector<uint8_t> probe;
  if (readSome(path, what, f.fd, probe, 1) != 0)
    fail(path, what + " changed while it was read (it grew beyond the " + std::to_string(size) + " bytes checked)");
  return bytes;
}
}  // namespace io
}  // namespace costmap_layers
