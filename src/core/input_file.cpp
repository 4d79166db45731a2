#include "core/input_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <mutex>
#include <stdexcept>
#include <string>
#include <utility>
#include <vector>

#include "core/file_message.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;

// The files read while inputs are protected: their identity (device and inode, so that another
// spelling of the path or a hard link is the same file) and the path the messages name.
struct ReadFile {
  dev_t device;
  ino_t inode;
  fs::path path;
};

std::atomic<bool> protecting{false};
std::mutex read_files_mutex;
std::vector<ReadFile> read_files;

}  // namespace

InputFile::InputFile(const fs::path& path, const char* what) : path_(path), what_(what) {
  const std::string cannot = "cannot read " + quoted(path) + ": ";
  // O_NONBLOCK: opening a FIFO without a writer would wait for one.
  const int descriptor = ::open(path.c_str(), O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  if (descriptor < 0) {
    const int error = errno;
    if (error == ENOENT) throw Error(ErrorCode::io, cannot + "no such file; check the path");
    if (error == EISDIR)
      throw Error(ErrorCode::io, cannot + "it is a folder, not " + what + "; give a file");
    throw Error(ErrorCode::io, cannot + errno_message(error));
  }
  struct stat status {};
  if (::fstat(descriptor, &status) != 0) {
    const int error = errno;
    ::close(descriptor);
    throw Error(ErrorCode::io, cannot + errno_message(error));
  }
  if (const char* kind = kind_of_file(status.st_mode)) {
    ::close(descriptor);
    throw Error(ErrorCode::io,
                cannot + "it is " + kind + ", not " + what + "; give a regular file");
  }
  const int flags = ::fcntl(descriptor, F_GETFL);
  stream_ = flags < 0 || ::fcntl(descriptor, F_SETFL, flags & ~O_NONBLOCK) != 0
                ? nullptr
                : ::fdopen(descriptor, "rb");
  if (stream_ == nullptr) {
    const int error = errno;
    ::close(descriptor);
    throw Error(ErrorCode::io, cannot + errno_message(error));
  }
  size_ = static_cast<std::uint64_t>(status.st_size);
  if (protecting.load()) {
    const std::lock_guard lock(read_files_mutex);
    read_files.push_back({status.st_dev, status.st_ino, path});
  }
}

InputFile::~InputFile() {
  std::fclose(stream_);
}

std::string InputFile::read_all(std::uint64_t max_bytes, const std::string& remedy) {
  if (size_ > max_bytes)
    throw Error(ErrorCode::invalid_input, quoted(path_) + " has " + std::to_string(size_) +
                                              " bytes, more than the " + std::to_string(max_bytes) +
                                              " that " + what_ +
                                              " may have within the memory budget; " + remedy);
  std::string bytes(static_cast<std::size_t>(size_), '\0');
  if (std::fread(bytes.data(), 1, bytes.size(), stream_) != bytes.size())
    throw Error(ErrorCode::io, "cannot read " + quoted(path_) + ": " +
                                   (std::ferror(stream_) ? errno_message(errno)
                                                         : std::string("it became shorter")));
  return bytes;
}

void protect_inputs() {
  protecting.store(true);
}

void check_not_an_input(const fs::path& target) {
  if (!protecting.load()) return;
  struct stat status {};
  if (::stat(target.c_str(), &status) != 0) return;
  const std::lock_guard lock(read_files_mutex);
  for (const ReadFile& file : read_files)
    if (file.device == status.st_dev && file.inode == status.st_ino)
      throw output_is_input(target, file.path);
}

}  // namespace stochtex
