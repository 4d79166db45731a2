#include "core/atomic_file.hpp"

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <atomic>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <stdexcept>
#include <string>
#include <system_error>
#include <utility>
#include <vector>

#include "core/file_message.hpp"
#include "core/input_file.hpp"
#include "stochtex/error.hpp"

namespace stochtex {
namespace {

namespace fs = std::filesystem;

// The temporaries being written, in fixed buffers that a signal handler may read (it may not
// allocate or lock). A slot is free (kFree), being filled by its owner (kFilling), or holds the
// path of a temporary to remove on a signal (kHeld). std::atomic<int> is lock-free, so the
// handler's loads are async-signal-safe. The states lie apart from the paths, so that finding a
// slot touches only them.
constexpr int kFree = 0;
constexpr int kFilling = 1;
constexpr int kHeld = 2;
constexpr int kSlots = 4096;  // 16 MiB of paths, in pages touched only when used
constexpr std::size_t kPathBytes = 4096;
static_assert(std::atomic<int>::is_always_lock_free);

std::atomic<int> slot_states[kSlots];
char slot_paths[kSlots][kPathBytes];

// Numbers the temporaries of this process: with the process id, a name no other live writer uses.
std::atomic<unsigned long> temporary_counter{0};

// Holds `path` in a free slot.
int hold_path(const fs::path& path) {
  const std::string& text = path.native();
  if (text.size() >= kPathBytes)
    throw Error(ErrorCode::io, "cannot write " + quoted(path) + ": the path is too long");
  for (int i = 0; i < kSlots; ++i) {
    int expected = kFree;
    if (slot_states[i].compare_exchange_strong(expected, kFilling)) {
      std::memcpy(slot_paths[i], text.c_str(), text.size() + 1);
      slot_states[i].store(kHeld);
      return i;
    }
  }
  throw Error(ErrorCode::io, "cannot write " + quoted(path) + ": more than " +
                                 std::to_string(kSlots) +
                                 " files are being written at once; write fewer at a time");
}

void release_path(int slot) {
  slot_states[slot].store(kFree);
}

void remove_temporaries(int signal_number) {
  for (int i = 0; i < kSlots; ++i)
    if (slot_states[i].load() == kHeld) ::unlink(slot_paths[i]);
  std::signal(signal_number, SIG_DFL);
  std::raise(signal_number);  // delivered when the handler returns: the default action ends us
}

// Makes the rename durable. The new file is already in place, so a failure here (a file system
// that cannot sync folders) is no reason to report the write as failed.
void sync_folder(const fs::path& target) {
  const fs::path folder = target.parent_path().empty() ? fs::path(".") : target.parent_path();
  const int descriptor = ::open(folder.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (descriptor < 0) return;
  ::fsync(descriptor);
  ::close(descriptor);
}

}  // namespace

void check_output_target(const fs::path& target) {
  const fs::path folder = target.parent_path();
  std::error_code error;
  if (!folder.empty() && !fs::is_directory(folder, error))
    throw Error(ErrorCode::io, "cannot write " + quoted(target) + ": the folder " + quoted(folder) +
                                   " does not exist; create it or choose another path");
  struct stat status {};
  // Missing or not examinable (then the open says why), or a regular file: an output may go there.
  const char* kind = ::lstat(target.c_str(), &status) == 0 ? kind_of_file(status.st_mode) : nullptr;
  if (kind == nullptr) {
    check_not_an_input(target);
    return;
  }
  throw Error(ErrorCode::io, "cannot write " + quoted(target) + ": it is " + kind +
                                 ", and an output only ever replaces a regular file; "
                                 "choose another path");
}

void check_output_is_not_input(const fs::path& output, const fs::path& input) {
  std::error_code error;
  if (fs::equivalent(output, input, error)) throw output_is_input(output, input);
}

AtomicFile::AtomicFile(fs::path target) : target_(std::move(target)) {
  check_output_target(target_);
  for (;;) {
    // Appended piece by piece: "." + std::to_string(...) trips GCC 12's -Wrestrict.
    std::string suffix = ".";
    suffix += std::to_string(::getpid());
    suffix += '-';
    suffix += std::to_string(temporary_counter++);
    suffix += ".tmp";
    temporary_ = target_;
    temporary_ += suffix;
    // Held before the file exists, so that no signal finds it unlisted; the name holds our
    // process id, so whatever is removed at that name is ours or a dead process's leftover.
    slot_ = hold_path(temporary_);
    const int descriptor =
        ::open(temporary_.c_str(), O_WRONLY | O_CREAT | O_EXCL | O_CLOEXEC, 0666);
    if (descriptor >= 0) {
      stream_ = ::fdopen(descriptor, "wb");
      if (stream_ != nullptr) return;
      const int error = errno;
      ::close(descriptor);
      ::unlink(temporary_.c_str());
      release_path(std::exchange(slot_, -1));
      fail(errno_message(error));  // a throwing constructor runs no destructor: cleaned up above
    }
    const int error = errno;
    release_path(std::exchange(slot_, -1));
    if (error != EEXIST) fail(errno_message(error));
  }
}

AtomicFile::~AtomicFile() {
  if (stream_ != nullptr) std::fclose(stream_);
  if (slot_ >= 0) {
    ::unlink(temporary_.c_str());
    release_path(slot_);
  }
}

void AtomicFile::fail(const std::string& reason) {
  throw Error(ErrorCode::io, "cannot write " + quoted(target_) + ": " + reason);
}

void AtomicFile::finish() {
  if (stream_ == nullptr) return;
  std::FILE* stream = std::exchange(stream_, nullptr);
  // A write that failed earlier leaves the stream's error flag set: the commit fails with it.
  bool ok = std::fflush(stream) == 0 && !std::ferror(stream) && ::fsync(::fileno(stream)) == 0 &&
            ::fstat(::fileno(stream), &written_) == 0;
  const int error = errno;
  if (std::fclose(stream) != 0 && ok) fail(errno_message(errno));
  if (!ok) fail(errno_message(error));
}

void AtomicFile::commit() {
  finish();
  check_output_target(target_);
  if (std::rename(temporary_.c_str(), target_.c_str()) != 0) fail(errno_message(errno));
  release_path(std::exchange(slot_, -1));
  sync_folder(target_);
  struct stat present {};
  const bool ok = ::lstat(target_.c_str(), &present) == 0 && present.st_dev == written_.st_dev &&
                  present.st_ino == written_.st_ino;
  if (!ok)
    fail("another process replaced it as it was written; write each output from one process");
}

void write_file_atomically(const fs::path& target, std::string_view bytes) {
  AtomicFile file(target);
  std::fwrite(bytes.data(), 1, bytes.size(), file.stream());
  file.commit();
}

AtomicFileSet::~AtomicFileSet() {
  files_.clear();  // the temporaries first, then the folders they were in
  for (auto folder = created_.rbegin(); folder != created_.rend(); ++folder)
    ::rmdir(folder->c_str());
}

void AtomicFileSet::create_folder(const fs::path& folder) {
  std::vector<fs::path> missing;
  std::error_code error;
  for (fs::path part = folder; !part.empty() && !fs::exists(part, error);
       part = part.parent_path()) {
    missing.push_back(part);
    if (part == part.parent_path()) break;
  }
  fs::create_directories(folder, error);
  created_.insert(created_.end(), missing.rbegin(), missing.rend());
  if (error || !fs::is_directory(folder))
    throw Error(ErrorCode::io, "cannot create the folder " + quoted(folder) + ": " +
                                   (error ? error.message() : "a file of that name exists"));
}

AtomicFile& AtomicFileSet::open(const fs::path& target) {
  const std::lock_guard lock(mutex_);
  return *files_.emplace_back(std::make_unique<AtomicFile>(target));
}

void AtomicFileSet::write(const fs::path& target, std::string_view bytes) {
  AtomicFile& file = open(target);
  std::fwrite(bytes.data(), 1, bytes.size(), file.stream());
  file.finish();
}

void AtomicFileSet::commit() {
  const std::lock_guard lock(mutex_);
  for (const auto& file : files_) file->finish();
  for (const auto& file : files_) file->commit();
  files_.clear();
  created_.clear();
}

void remove_temporaries_on_signals() {
  for (const int signal_number : {SIGINT, SIGTERM, SIGHUP}) {
    struct sigaction current {};
    if (::sigaction(signal_number, nullptr, &current) != 0 || current.sa_handler == SIG_IGN)
      continue;
    struct sigaction action {};
    action.sa_handler = remove_temporaries;
    sigfillset(&action.sa_mask);
    ::sigaction(signal_number, &action, nullptr);
  }
}

}  // namespace stochtex
