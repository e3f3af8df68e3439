#pragma once
// Output files that are never seen half-written. A file is written under a temporary name in its
// own directory and renamed over the target when complete (rename is atomic on POSIX): a reader,
// or a kill at any moment, finds the old file or the new one, never a part of one. A symlink at
// the target is replaced by the new file, not followed.
#include <memory>
#include <ostream>
#include <string>
#include <string_view>

namespace vdec {

class AtomicFile {
 public:
  // Creates the temporary file DIR/.NAME.tmp-PID-N next to DIR/NAME (exclusively: an existing
  // file or link of that name is never opened). Throws OutputError naming the target.
  explicit AtomicFile(std::string target);
  // Removes the temporary file unless commit() has renamed it.
  ~AtomicFile();
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;

  std::ostream& stream();
  // Flushes, syncs to disk and renames the file over the target. Throws OutputError.
  void commit();

 private:
  struct Buffer;
  std::string target_, temporary_;
  int fd_ = -1;
  std::unique_ptr<Buffer> buffer_;
  std::unique_ptr<std::ostream> stream_;
};

// The whole of `content` to `target` by way of AtomicFile.
void writeFileAtomically(const std::string& target, std::string_view content);

}  // namespace vdec
