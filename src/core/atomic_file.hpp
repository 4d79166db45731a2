#pragma once
// The one way stochtex writes a file (models, images, text; docs/design.md §6: "a failed command
// leaves no partial file"). The bytes go to a temporary of a unique name in the target's folder,
// are flushed and fsync'ed, and the temporary is renamed over the target, so that a reader sees
// the old file or the new one, never a part, and two writers of one path never share a
// temporary. Only a missing target or a regular file is replaced: a folder, a symbolic link, a
// FIFO or a device is refused. POSIX only, no other library: stochtex::runtime's save_model uses
// it.

#include <sys/stat.h>

#include <cstdio>
#include <filesystem>
#include <memory>
#include <mutex>
#include <string_view>
#include <vector>

namespace stochtex {

// Throws Error(io), one sentence naming `target`, when its folder is missing or `target` exists
// and is not a regular file, and std::invalid_argument when it is a protected input
// (core/input_file.hpp). Writers call it first and again just before the rename; callers may
// call it earlier to refuse an output before any long work.
void check_output_target(const std::filesystem::path& target);

// Throws std::invalid_argument (a usage error) when `output` is the same file as `input` (by
// filesystem identity: hard links and other spellings of the path too), so that an output never
// replaces the file it is made from. Nothing is checked while either file does not exist.
void check_output_is_not_input(const std::filesystem::path& output,
                               const std::filesystem::path& input);

// A file being written: `stream()` writes into a new temporary beside the target (opened with
// O_EXCL and O_CLOEXEC, named after the target, the process id and a counter); `commit()` moves
// it over the target. Destroyed uncommitted (a write failed, an exception), it removes the
// temporary. Every failure throws Error(io) with one sentence naming the target.
class AtomicFile {
 public:
  explicit AtomicFile(std::filesystem::path target);
  AtomicFile(const AtomicFile&) = delete;
  AtomicFile& operator=(const AtomicFile&) = delete;
  ~AtomicFile();

  std::FILE* stream() const { return stream_; }
  const std::filesystem::path& temporary() const { return temporary_; }

  // Flushes, fsyncs and closes the temporary: what can fail for want of space fails here. The
  // temporary stays until commit() or the destructor.
  void finish();

  // finish(), then renames the temporary over the target and fsyncs the folder. It fails, rather
  // than report a success, when the file at the target afterwards is not the one written (another
  // process replaced it in between).
  void commit();

 private:
  [[noreturn]] void fail(const std::string& reason);

  std::filesystem::path target_;
  std::filesystem::path temporary_;
  std::FILE* stream_ = nullptr;
  struct stat written_ {};  // the temporary's identity, for the check after the rename
  int slot_ = -1;           // the signal-cleanup slot holding the temporary's path
};

// The files of one output that is several files (a material's maps, a report, an export): all
// of them or none. Each is written to its temporary; commit() finishes every one (a full disk
// fails there, before any target is replaced) and then renames them all. Destroyed uncommitted,
// it removes the temporaries and the folders create_folder made. open and write may be called
// from several threads.
class AtomicFileSet {
 public:
  AtomicFileSet() = default;
  AtomicFileSet(const AtomicFileSet&) = delete;
  AtomicFileSet& operator=(const AtomicFileSet&) = delete;
  ~AtomicFileSet();

  // Creates `folder` and its missing parents, removed again if the set is not committed.
  void create_folder(const std::filesystem::path& folder);
  // A new file of the set, to be written through its stream; the set commits it.
  AtomicFile& open(const std::filesystem::path& target);
  // A new file of the set holding `bytes`, finished at once (its stream closed).
  void write(const std::filesystem::path& target, std::string_view bytes);
  void commit();

 private:
  std::mutex mutex_;
  std::vector<std::unique_ptr<AtomicFile>> files_;
  std::vector<std::filesystem::path> created_;
};

// Writes `bytes` to `target` through an AtomicFile.
void write_file_atomically(const std::filesystem::path& target, std::string_view bytes);

// Makes SIGINT, SIGTERM and SIGHUP remove every temporary still being written, then end the
// process with the signal's default action (so its exit status still says which signal). A signal
// the process ignores stays ignored. For programs (the CLI); a library never installs handlers.
void remove_temporaries_on_signals();

}  // namespace stochtex
