#include "costmap_layers/io/safe_write.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>
#include <random>
#include <stdexcept>

namespace costmap_layers
{
namespace io
{
namespace
{
/// An open descriptor, closed when it goes.
class Fd
{
public:
  explicit Fd(int fd = -1) : fd_(fd) {}
  Fd(const Fd&) = delete;
  Fd& operator=(const Fd&) = delete;
  ~Fd() { reset(); }
  int get() const { return fd_; }
  /// Closes now; returns close()'s errno (0 when it succeeded or there was nothing to close).
  int reset()
  {
    int error = 0;
    if (fd_ >= 0 && ::close(fd_) != 0) error = errno;
    fd_ = -1;
    return error;
  }

private:
  int fd_;
};

/// The temporary file's name in the folder, removed on every path that does not rename it.
class TempEntry
{
public:
  TempEntry(int dir, std::string name) : dir_(dir), name_(std::move(name)) {}
  TempEntry(const TempEntry&) = delete;
  TempEntry& operator=(const TempEntry&) = delete;
  ~TempEntry()
  {
    if (!name_.empty()) ::unlinkat(dir_, name_.c_str(), 0);
  }
  const std::string& name() const { return name_; }
  void release() { name_.clear(); }

private:
  int dir_;
  std::string name_;
};

[[noreturn]] void fail(const std::string& path, const std::string& step, int error)
{
  throw std::runtime_error("'" + path + "': " + step + ": " + std::strerror(error));
}

/// A name nobody can guess: '.', the target's name (cut so that the whole stays within NAME_MAX),
/// ".tmp-" and 12 random letters and digits.
std::string tempName(const std::string& base)
{
  static constexpr char kChars[] = "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789";
  std::random_device random;
  std::uniform_int_distribution<std::size_t> pick(0, sizeof(kChars) - 2);
  std::string name = "." + base.substr(0, 200) + ".tmp-";
  for (int k = 0; k < 12; ++k)
    name += kChars[pick(random)];
  return name;
}
}  // namespace

void replaceFileAtomically(const std::string& path, const std::string& text)
{
  const std::size_t slash = path.rfind('/');
  const std::string folder = slash == std::string::npos ? "." : (slash == 0 ? "/" : path.substr(0, slash));
  const std::string base = slash == std::string::npos ? path : path.substr(slash + 1);
  if (base.empty() || base == "." || base == "..") throw std::runtime_error("'" + path + "': not a file name");
  // Everything below is relative to the folder opened once: renaming a folder on the way cannot move
  // the write elsewhere half-way.
  const Fd dir(::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC));
  if (dir.get() < 0) fail(path, "its folder cannot be opened", errno);
  struct stat old
  {
  };
  bool exists = true;
  if (::fstatat(dir.get(), base.c_str(), &old, AT_SYMLINK_NOFOLLOW) != 0)
  {
    if (errno != ENOENT) fail(path, "cannot be examined", errno);
    exists = false;
  }
  else if (S_ISLNK(old.st_mode))
    throw std::runtime_error("'" + path + "': is a symbolic link (its target is what would be replaced)");
  else if (!S_ISREG(old.st_mode))
    throw std::runtime_error("'" + path + "': is not a regular file: not replaced");

  // O_EXCL with O_CREAT never follows a link and never opens what is there: a name planted in the
  // folder is a collision, and the next random name is tried. An existing target's copy starts as
  // 0600 (its own bits are set before any byte is written); a new file gets what the umask leaves.
  std::string temp;
  int fd = -1;
  int error = EEXIST;
  for (int attempt = 0; attempt < 100 && error == EEXIST; ++attempt)
  {
    temp = tempName(base);
    fd = ::openat(dir.get(), temp.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_NOFOLLOW | O_CLOEXEC,
                  exists ? S_IRUSR | S_IWUSR : 0666);
    error = fd < 0 ? errno : 0;
  }
  if (error != 0) fail(path, "no temporary file can be made in its folder", error);
  TempEntry entry(dir.get(), temp);  // declared before `out`: the file is closed before it is removed
  Fd out(fd);

  if (exists)
  {
    struct stat now
    {
    };
    if (::fstat(out.get(), &now) != 0) fail(path, "the temporary file cannot be examined", errno);
    // Owner first: changing it may clear set-id bits, which fchmod then sets as they were.
    if ((now.st_uid != old.st_uid || now.st_gid != old.st_gid) && ::fchown(out.get(), old.st_uid, old.st_gid) != 0)
      fail(path,
           "its owner " + std::to_string(old.st_uid) + ":" + std::to_string(old.st_gid) +
               " cannot be kept (not replaced)",
           errno);
    if (::fchmod(out.get(), old.st_mode & 07777) != 0) fail(path, "its mode cannot be kept (not replaced)", errno);
  }
  const char* data = text.data();
  std::size_t left = text.size();
  while (left > 0)
  {
    const ssize_t n = ::write(out.get(), data, left);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) fail(path, "writing the temporary file failed", n < 0 ? errno : EIO);
    data += n;
    left -= static_cast<std::size_t>(n);
  }
  if (::fsync(out.get()) != 0) fail(path, "syncing the temporary file failed", errno);
  if (const int close_error = out.reset(); close_error != 0)
    fail(path, "closing the temporary file failed", close_error);
  if (::renameat(dir.get(), entry.name().c_str(), dir.get(), base.c_str()) != 0)
    fail(path, "cannot be replaced", errno);
  entry.release();
  // The rename is durable once the folder is synced; some file systems cannot sync a folder (EINVAL).
  if (::fsync(dir.get()) != 0 && errno != EINVAL && errno != EROFS)
    fail(path, "written, but syncing its folder failed", errno);
}
}  // namespace io
}  // namespace costmap_layers
