// The one safe way of writing a file (core/atomic_file.hpp, docs/design.md §6): unique
// temporaries, replacement of regular files only, no temporary left by a failure or a signal,
// several files all or none; and of reading one (core/input_file.hpp): regular files only, never
// replaced by an output once inputs are protected.

#include "core/atomic_file.hpp"

#include <gtest/gtest.h>
#include <sys/resource.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <csignal>
#include <filesystem>
#include <fstream>
#include <iterator>
#include <stdexcept>
#include <string>

#include "core/input_file.hpp"
#include "stochtex/error.hpp"
#include "test_support.hpp"

namespace stochtex::atomic_file_test {
namespace {

namespace fs = std::filesystem;
using AtomicFileTest = test_support::FolderTest;

std::string contents(const fs::path& path) {
  std::ifstream file(path, std::ios::binary);
  return {std::istreambuf_iterator<char>(file), std::istreambuf_iterator<char>()};
}

// The message of the Error that `write` throws, or "" when it throws none.
template <typename Write>
std::string error_message(Write write) {
  try {
    write();
  } catch (const Error& error) {
    EXPECT_EQ(error.code(), ErrorCode::io);
    return error.what();
  }
  return "";
}

TEST_F(AtomicFileTest, WritesAndReplacesLeavingOnlyTheTarget) {
  write_file_atomically(file("out.txt"), "first");
  write_file_atomically(file("out.txt"), "second, longer");
  EXPECT_EQ(contents(file("out.txt")), "second, longer");
  EXPECT_EQ(folder_contents(), std::vector<fs::path>{file("out.txt")});
}

TEST_F(AtomicFileTest, NewFilesFollowTheUmask) {
  const mode_t mask = ::umask(022);
  write_file_atomically(file("out.txt"), "x");
  ::umask(mask);
  EXPECT_EQ(fs::status(file("out.txt")).permissions(),
            fs::perms::owner_read | fs::perms::owner_write | fs::perms::group_read |
                fs::perms::others_read);
}

TEST_F(AtomicFileTest, TwoWritersOfOnePathHaveTheirOwnTemporaries) {
  write_file_atomically(file("out.txt"), "old");
  AtomicFile first(file("out.txt"));
  AtomicFile second(file("out.txt"));
  EXPECT_NE(first.temporary(), second.temporary());
  std::fputs("first", first.stream());
  std::fputs("second", second.stream());
  EXPECT_EQ(contents(file("out.txt")), "old");  // a reader sees the old file until a commit
  first.commit();
  EXPECT_EQ(contents(file("out.txt")), "first");
  second.commit();
  EXPECT_EQ(contents(file("out.txt")), "second");
  EXPECT_EQ(folder_contents(), std::vector<fs::path>{file("out.txt")});
}

TEST_F(AtomicFileTest, AnUncommittedFileLeavesTheTargetAndNoTemporary) {
  write_file_atomically(file("out.txt"), "old");
  {
    AtomicFile abandoned(file("out.txt"));
    std::fputs("partial", abandoned.stream());
    EXPECT_TRUE(fs::exists(abandoned.temporary()));
  }
  EXPECT_EQ(contents(file("out.txt")), "old");
  EXPECT_EQ(folder_contents(), std::vector<fs::path>{file("out.txt")});
}

TEST_F(AtomicFileTest, OnlyRegularFilesAreReplaced) {
  write_file_atomically(file("kept.txt"), "kept");
  fs::create_directory(file("folder"));
  fs::create_symlink(file("kept.txt"), file("link"));
  ASSERT_EQ(::mkfifo(file("fifo").c_str(), 0600), 0);
  for (const auto& [name, kind] :
       {std::pair{"folder", "a folder"}, std::pair{"link", "a symbolic link"},
        std::pair{"fifo", "a FIFO"}}) {
    const fs::path target = file(name);  // clang 14 cannot capture a structured binding
    const std::string message = error_message([&] { write_file_atomically(target, "x"); });
    EXPECT_NE(message.find(target.string()), std::string::npos) << message;
    EXPECT_NE(message.find(kind), std::string::npos) << message;
  }
  const std::string device = error_message([] { check_output_target("/dev/null"); });
  EXPECT_NE(device.find("a device"), std::string::npos) << device;
  EXPECT_TRUE(fs::is_symlink(file("link")));
  EXPECT_EQ(contents(file("kept.txt")), "kept");
  EXPECT_EQ(folder_contents().size(), 4u);
}

TEST_F(AtomicFileTest, AMissingFolderIsNamed) {
  const std::string message =
      error_message([&] { write_file_atomically(file("missing") / "out.txt", "x"); });
  EXPECT_NE(message.find("does not exist"), std::string::npos) << message;
  EXPECT_TRUE(folder_contents().empty());
}

TEST_F(AtomicFileTest, AnOutputThatIsTheInputIsAUsageError) {
  write_file_atomically(file("in.txt"), "in");
  fs::create_hard_link(file("in.txt"), file("hard_link.txt"));
  EXPECT_THROW(check_output_is_not_input(file("in.txt"), file("in.txt")), std::invalid_argument);
  EXPECT_THROW(check_output_is_not_input(file("hard_link.txt"), file("in.txt")),
               std::invalid_argument);
  EXPECT_THROW(check_output_is_not_input(folder_ / "." / "in.txt", file("in.txt")),
               std::invalid_argument);
  EXPECT_NO_THROW(check_output_is_not_input(file("other.txt"), file("in.txt")));
  write_file_atomically(file("other.txt"), "other");
  EXPECT_NO_THROW(check_output_is_not_input(file("other.txt"), file("in.txt")));
}

// A set commits all its files or none: a failed write (a file size limit, as a full disk) of
// its second file leaves neither file nor temporary nor the folder the set made.
TEST_F(AtomicFileTest, AFileSetWritesAllOrNone) {
  write_file_atomically(file("first.txt"), "old");
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    std::signal(SIGXFSZ, SIG_IGN);
    const rlimit limit{16, 16};
    ::setrlimit(RLIMIT_FSIZE, &limit);
    try {
      AtomicFileSet files;
      files.create_folder(file("made") / "deeper");
      files.write(file("first.txt"), "new");
      files.write(file("made") / "deeper" / "second.txt", std::string(64, 'x'));
      files.commit();
    } catch (const Error&) {
      ::_exit(3);
    }
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 3) << status;
  EXPECT_EQ(contents(file("first.txt")), "old");
  EXPECT_EQ(folder_contents(), std::vector<fs::path>{file("first.txt")});

  AtomicFileSet files;
  files.create_folder(file("made"));
  files.write(file("first.txt"), "new");
  files.write(file("made") / "second.txt", "second");
  EXPECT_EQ(contents(file("first.txt")), "old");
  files.commit();
  EXPECT_EQ(contents(file("first.txt")), "new");
  EXPECT_EQ(contents(file("made") / "second.txt"), "second");
}

// An input is opened without blocking and only when it is a regular file: a FIFO without a writer
// is refused at once. Once inputs are protected, no output replaces a file read as one.
TEST_F(AtomicFileTest, InputsAreRegularFilesThatNoOutputReplaces) {
  ASSERT_EQ(::mkfifo(file("fifo").c_str(), 0600), 0);
  try {
    InputFile fifo(file("fifo"), "an image");
    ADD_FAILURE() << "a FIFO was opened as an input";
  } catch (const Error& error) {
    EXPECT_NE(std::string(error.what()).find("it is a FIFO, not an image"), std::string::npos)
        << error.what();
  }
  EXPECT_THROW(InputFile(folder_, "an image"), Error);
  EXPECT_THROW(InputFile(file("missing"), "an image"), Error);

  // Protection is for the whole process: it is turned on in a child, which exits with 0 when
  // every step did as expected, or with the number of the first step that did not.
  write_file_atomically(file("in.txt"), "in");
  write_file_atomically(file("read_before.txt"), "before");
  fs::create_hard_link(file("in.txt"), file("link.txt"));
  const pid_t child = ::fork();
  ASSERT_GE(child, 0);
  if (child == 0) {
    const auto refused = [](const auto& write) {
      try {
        write();
      } catch (const std::invalid_argument&) {
        return true;
      }
      return false;
    };
    const InputFile before(file("read_before.txt"), "a text");
    protect_inputs();
    InputFile input(file("in.txt"), "a text");
    if (input.read_all(2, "-") != "in") ::_exit(1);
    if (!refused([&] { write_file_atomically(file("link.txt"), "out"); })) ::_exit(2);
    if (!refused([&] { check_output_target(folder_ / "." / "in.txt"); })) ::_exit(3);
    if (refused([&] { write_file_atomically(file("read_before.txt"), "after"); })) ::_exit(4);
    if (refused([&] { write_file_atomically(file("other.txt"), "other"); })) ::_exit(5);
    ::_exit(0);
  }
  int status = 0;
  ASSERT_EQ(::waitpid(child, &status, 0), child);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 0) << status;
  EXPECT_EQ(contents(file("in.txt")), "in");
  EXPECT_EQ(contents(file("read_before.txt")), "after");
}

// A child process is ended by the signal while its file is being written: the temporary goes,
// the old target stays, and the exit status still names the signal.
TEST_F(AtomicFileTest, ASignalRemovesTheTemporaries) {
  write_file_atomically(file("out.txt"), "old");
  for (const int signal_number : {SIGINT, SIGTERM}) {
    const pid_t child = ::fork();
    ASSERT_GE(child, 0);
    if (child == 0) {
      std::signal(signal_number, SIG_DFL);
      remove_temporaries_on_signals();
      AtomicFile first(file("out.txt"));
      AtomicFile second(file("other.txt"));
      std::fputs("partial", first.stream());
      std::fflush(first.stream());
      std::raise(signal_number);
      ::_exit(0);  // not reached when the handler works
    }
    int status = 0;
    ASSERT_EQ(::waitpid(child, &status, 0), child);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == signal_number) << status;
    EXPECT_EQ(contents(file("out.txt")), "old");
    EXPECT_EQ(folder_contents(), std::vector<fs::path>{file("out.txt")});
  }
}

}  // namespace
}  // namespace stochtex::atomic_file_test
