// atomic_file.h — every output file is written under a temporary name in its own folder and then
// renamed onto its final name, so a reader (or `seasim run --resume`) sees either the old file or
// the complete new one, never a partial write, even if the process is killed mid-write.
#pragma once
#include <cstddef>
#include <functional>
#include <string>
#include <vector>

namespace seasim {

// "<dir>/.<name>.tmp-<pid>" for "<dir>/<name>": same folder (rename must not cross file systems),
// hidden, and unique per process so two shards writing one folder do not collide.
std::string atomicTempPath(const std::string& path);

// Creates the parent folders of `path`, calls write(temp_path) to produce the complete file under
// the temporary name, flushes it to disk and renames it onto `path`. If anything fails (including
// an exception from `write`) the temporary file is removed, `path` is left as it was, and a
// RuntimeError naming `path` is thrown.
void writeFileAtomic(const std::string& path, const std::function<void(const std::string& temp_path)>& write);

// Writes `size` bytes to the NEW file `path` (not atomic on its own: call it on a temporary path
// inside writeFileAtomic). Every short write, ENOSPC/EDQUOT and close error is a RuntimeError
// naming `path` and the system's reason; stream writers can lose those.
void writeBytes(const std::string& path, const void* data, std::size_t size);

// The same for several pieces written one after the other (a header and its data, without a copy).
struct ByteSpan {
  const void* data;
  std::size_t size;
};
void writeBytes(const std::string& path, const std::vector<ByteSpan>& pieces);

// Temporary files a killed writer left behind (".<name>.tmp-<pid>"): every one in folder `dir`
// (not below it), or only those of the file `path`. Only call these where no live writer can be
// at work (the job runner holds the shard's lock). Return how many were removed.
int removeTempFiles(const std::string& dir);
int removeTempFilesFor(const std::string& path);

// Writes `text` (any bytes) to `path` atomically, creating parent folders.
void writeTextAtomic(const std::string& path, const std::string& text);

}  // namespace seasim
