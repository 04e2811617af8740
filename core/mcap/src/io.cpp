#include "rover/mcap/io.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstring>

namespace rover::mcap {
namespace {

constexpr std::size_t kSinkBufferBytes = 1 << 20;

std::string Reason(int err) { return std::strerror(err); }

std::string ReadFailure(const std::string& name, std::uint64_t n, std::uint64_t offset,
                        const std::string& why) {
  return name + ": read of " + std::to_string(n) + " bytes at offset " + std::to_string(offset) +
         " failed: " + why;
}

}  // namespace

// ---- FileSink -----------------------------------------------------------------------------------

Result<std::unique_ptr<FileSink>> FileSink::Create(const std::string& path) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) {
    const int err = errno;
    return Unavailable(path + ": cannot create: " + Reason(err));
  }
  return std::unique_ptr<FileSink>(new FileSink(path, fd));
}

FileSink::FileSink(std::string path, int fd) : path_(std::move(path)), fd_(fd) {
  buffer_.reserve(kSinkBufferBytes);
}

FileSink::~FileSink() {
  if (fd_ >= 0) ::close(fd_);
}

Status FileSink::WriteAll(const std::uint8_t* data, std::size_t size) {
  std::size_t done = 0;
  while (done < size) {
    const ssize_t n = ::write(fd_, data + done, size - done);
    if (n < 0) {
      const int err = errno;
      if (err == EINTR) continue;
      return Unavailable(path_ + ": write of " + std::to_string(size - done) + " bytes at offset " +
                         std::to_string(flushed_ + done) + " failed: " + Reason(err));
    }
    done += static_cast<std::size_t>(n);
  }
  flushed_ += size;
  return Status::Ok();
}

Status FileSink::Flush() {
  Status s = WriteAll(buffer_.data(), buffer_.size());
  buffer_.clear();
  return s;
}

Status FileSink::Write(std::span<const std::uint8_t> bytes) {
  if (fd_ < 0) return FailedPrecondition(path_ + ": write after close");
  if (buffer_.size() + bytes.size() > kSinkBufferBytes) ROVER_RETURN_IF_ERROR(Flush());
  if (bytes.size() >= kSinkBufferBytes) {
    return WriteAll(bytes.data(), bytes.size());  // large pieces skip the buffer
  }
  buffer_.insert(buffer_.end(), bytes.begin(), bytes.end());
  return Status::Ok();
}

Status FileSink::Close() {
  if (fd_ < 0) return FailedPrecondition(path_ + ": closed twice");
  Status s = Flush();
  if (s.ok() && ::fsync(fd_) != 0) {
    const int err = errno;
    s = Unavailable(path_ + ": fsync failed: " + Reason(err));
  }
  if (::close(fd_) != 0 && s.ok()) {
    const int err = errno;
    s = Unavailable(path_ + ": close failed: " + Reason(err));
  }
  fd_ = -1;
  return s;
}

// ---- FileSource ---------------------------------------------------------------------------------

Result<std::unique_ptr<FileSource>> FileSource::Open(const std::string& path) {
  const int fd = ::open(path.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) {
    const int err = errno;
    const std::string m = path + ": cannot open: " + Reason(err);
    return err == ENOENT ? NotFound(m) : Unavailable(m);
  }
  struct stat st {};
  if (::fstat(fd, &st) != 0) {
    const int err = errno;
    ::close(fd);
    return Unavailable(path + ": cannot stat: " + Reason(err));
  }
  if (!S_ISREG(st.st_mode)) {
    ::close(fd);
    return InvalidArgument(path + ": not a regular file");
  }
  return std::unique_ptr<FileSource>(
      new FileSource(path, fd, static_cast<std::uint64_t>(st.st_size)));
}

FileSource::~FileSource() {
  if (fd_ >= 0) ::close(fd_);
}

Status FileSource::Read(std::uint64_t offset, std::span<std::uint8_t> out) const {
  if (offset > size_ || out.size() > size_ - offset) {
    return InvalidArgument(
        ReadFailure(path_, out.size(), offset, "the file ends at " + std::to_string(size_)));
  }
  std::size_t done = 0;
  while (done < out.size()) {
    const ssize_t n =
        ::pread(fd_, out.data() + done, out.size() - done, static_cast<off_t>(offset + done));
    if (n < 0) {
      const int err = errno;
      if (err == EINTR) continue;
      return Unavailable(ReadFailure(path_, out.size(), offset, Reason(err)));
    }
    if (n == 0) {
      return Unavailable(
          ReadFailure(path_, out.size(), offset, "the file shrank while being read"));
    }
    done += static_cast<std::size_t>(n);
  }
  return Status::Ok();
}

// ---- BufferSource -------------------------------------------------------------------------------

Status BufferSource::Read(std::uint64_t offset, std::span<std::uint8_t> out) const {
  if (offset > bytes_.size() || out.size() > bytes_.size() - offset) {
    return InvalidArgument(ReadFailure(name_, out.size(), offset,
                                       "the data ends at " + std::to_string(bytes_.size())));
  }
  if (!out.empty()) std::memcpy(out.data(), bytes_.data() + offset, out.size());
  return Status::Ok();
}

}  // namespace rover::mcap
