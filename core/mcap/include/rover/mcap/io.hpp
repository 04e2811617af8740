#pragma once
/// @file
/// Where a writer puts bytes and where a reader gets them: files (buffered write(2), pread(2))
/// or memory (tests, tools). Errors name the path, the offset and the system's reason:
///   "run.mcap: write of 1048576 bytes at offset 73400320 failed: No space left on device"
///   "run.mcap: read of 29 bytes at offset 4096 failed: the file ends at 4000"

#include <cstdint>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "rover/base/status.hpp"

namespace rover::mcap {

/// A sequential byte sink.
class Sink {
 public:
  virtual ~Sink() = default;
  /// Appends `bytes`; may buffer.
  virtual Status Write(std::span<const std::uint8_t> bytes) = 0;
  /// Makes everything written durable (files: flush, fsync, close). Called once, last.
  virtual Status Close() = 0;
  /// For messages: the path or "<memory>".
  virtual const std::string& name() const = 0;
};

/// A file created (or truncated) at `path`, mode 0644, written through a 1 MiB buffer.
class FileSink final : public Sink {
 public:
  /// Fails (kUnavailable) with "<path>: cannot create: <reason>".
  static Result<std::unique_ptr<FileSink>> Create(const std::string& path);
  ~FileSink() override;
  Status Write(std::span<const std::uint8_t> bytes) override;
  Status Close() override;
  const std::string& name() const override { return path_; }

 private:
  FileSink(std::string path, int fd);
  Status Flush();
  Status WriteAll(const std::uint8_t* data, std::size_t size);

  std::string path_;
  int fd_ = -1;
  std::vector<std::uint8_t> buffer_;
  std::uint64_t flushed_ = 0;  ///< bytes handed to the kernel so far
};

/// Appends to a vector the caller owns (which must outlive the sink).
class BufferSink final : public Sink {
 public:
  explicit BufferSink(std::vector<std::uint8_t>* out, std::string name = "<memory>")
      : out_(out), name_(std::move(name)) {}
  Status Write(std::span<const std::uint8_t> bytes) override {
    out_->insert(out_->end(), bytes.begin(), bytes.end());
    return Status::Ok();
  }
  Status Close() override { return Status::Ok(); }
  const std::string& name() const override { return name_; }

 private:
  std::vector<std::uint8_t>* out_;
  std::string name_;
};

/// Random-access bytes of a fixed size.
class Source {
 public:
  virtual ~Source() = default;
  virtual std::uint64_t size() const = 0;
  /// Fills `out` with the bytes at [offset, offset + out.size()); fails if they are not all there.
  virtual Status Read(std::uint64_t offset, std::span<std::uint8_t> out) const = 0;
  virtual const std::string& name() const = 0;
};

/// A file opened read-only; its size is taken once, at Open.
class FileSource final : public Source {
 public:
  /// Fails (kNotFound or kUnavailable) with "<path>: cannot open: <reason>".
  static Result<std::unique_ptr<FileSource>> Open(const std::string& path);
  ~FileSource() override;
  std::uint64_t size() const override { return size_; }
  Status Read(std::uint64_t offset, std::span<std::uint8_t> out) const override;
  const std::string& name() const override { return path_; }

 private:
  FileSource(std::string path, int fd, std::uint64_t size)
      : path_(std::move(path)), fd_(fd), size_(size) {}
  std::string path_;
  int fd_ = -1;
  std::uint64_t size_ = 0;
};

/// Bytes held in memory.
class BufferSource final : public Source {
 public:
  explicit BufferSource(std::vector<std::uint8_t> bytes, std::string name = "<memory>")
      : bytes_(std::move(bytes)), name_(std::move(name)) {}
  std::uint64_t size() const override { return bytes_.size(); }
  Status Read(std::uint64_t offset, std::span<std::uint8_t> out) const override;
  const std::string& name() const override { return name_; }

 private:
  std::vector<std::uint8_t> bytes_;
  std::string name_;
};

}  // namespace rover::mcap
