#include "io/atomic_file.hpp"

#include <fcntl.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <cstdio>
#include <cstring>
#include <filesystem>
#include <streambuf>

#include "core/errors.hpp"

namespace vdec {

namespace {

std::string systemMessage(int error) { return std::strerror(error); }

// Writes all of [data, data + size) to fd; false (errno set) on failure.
bool writeAll(int fd, const char* data, std::size_t size) {
  while (size > 0) {
    const ssize_t n = ::write(fd, data, size);
    if (n < 0) {
      if (errno == EINTR) continue;
      return false;
    }
    data += n;
    size -= static_cast<std::size_t>(n);
  }
  return true;
}

}  // namespace

// A stream buffer over a file descriptor: the standard library cannot open a stream on a file
// created with O_EXCL, and reopening it by name would follow whatever the name then points to.
struct AtomicFile::Buffer : std::streambuf {
  explicit Buffer(int fd) : fd_(fd) { setp(data_, data_ + sizeof data_); }
  int error = 0;  // errno of the first failed write

 protected:
  int_type overflow(int_type c) override {
    if (!flushBuffer()) return traits_type::eof();
    if (!traits_type::eq_int_type(c, traits_type::eof())) {
      *pptr() = traits_type::to_char_type(c);
      pbump(1);
    }
    return traits_type::not_eof(c);
  }
  int sync() override { return flushBuffer() ? 0 : -1; }

 private:
  bool flushBuffer() {
    if (error != 0) return false;
    if (!writeAll(fd_, pbase(), static_cast<std::size_t>(pptr() - pbase()))) {
      error = errno;
      return false;
    }
    setp(data_, data_ + sizeof data_);
    return true;
  }
  int fd_;
  char data_[1 << 16];
};

AtomicFile::AtomicFile(std::string target) : target_(std::move(target)) {
  static std::atomic<unsigned> counter{0};
  const std::filesystem::path path(target_);
  for (int attempt = 0; attempt < 100 && fd_ < 0; ++attempt) {
    temporary_ = (path.parent_path() / ("." + path.filename().string() + ".tmp-" + std::to_string(getpid()) + "-" +
                                        std::to_string(counter++)))
                     .string();
    // 0666 less the umask, as for any file the user creates; O_EXCL refuses an existing name,
    // link or not.
    fd_ = ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (fd_ < 0 && errno != EEXIST) break;
  }
  if (fd_ < 0)
    throw OutputError(target_ + ": cannot write (" + systemMessage(errno) + " creating the temporary file " +
                      temporary_ + ")");
  buffer_ = std::make_unique<Buffer>(fd_);
  stream_ = std::make_unique<std::ostream>(buffer_.get());
}

AtomicFile::~AtomicFile() {
  if (fd_ >= 0) ::close(fd_);
  if (!temporary_.empty()) ::unlink(temporary_.c_str());
}

std::ostream& AtomicFile::stream() { return *stream_; }

void AtomicFile::commit() {
  stream_->flush();
  if (!*stream_ || buffer_->error != 0)
    throw OutputError(target_ + ": write failed (" + systemMessage(buffer_->error ? buffer_->error : EIO) + ")");
  // On disk before the rename, so that a crash of the machine cannot leave the new name on an
  // empty file.
  if (::fsync(fd_) != 0) throw OutputError(target_ + ": write failed (" + systemMessage(errno) + ")");
  const int closed = ::close(fd_);
  fd_ = -1;
  if (closed != 0) throw OutputError(target_ + ": write failed (" + systemMessage(errno) + ")");
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0)
    throw OutputError(target_ + ": cannot replace it with the new file (" + systemMessage(errno) + ")");
  temporary_.clear();
}

void writeFileAtomically(const std::string& target, std::string_view content) {
  AtomicFile file(target);
  file.stream().write(content.data(), static_cast<std::streamsize>(content.size()));
  file.commit();
}

}  // namespace vdec
