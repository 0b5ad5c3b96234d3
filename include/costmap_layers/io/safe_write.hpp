// Replacing a file so that no reader sees half of it and no planted link redirects the write: the text
// goes to a temporary file created exclusively (O_CREAT | O_EXCL | O_NOFOLLOW, a random name) in the
// target's own folder, takes the target's mode and owner, is synced, and is renamed over the target;
// the folder is synced after. Every failure removes the temporary file.
#pragma once

#include <string>

namespace costmap_layers
{
namespace io
{
/// Writes `text` to `path` atomically. When `path` exists it must be a regular file (a symbolic link,
/// a folder, a FIFO is refused: the caller resolves links first and decides whether the target may be
/// replaced); the new file keeps its permission bits, owner and group. A new file gets 0666 minus the
/// umask, as any file the process creates. Throws std::runtime_error naming the path and the failing
/// step (nothing at `path` has changed then).
void replaceFileAtomically(const std::string& path, const std::string& text);
}  // namespace io
}  // namespace costmap_layers
