// SPDX-License-Identifier: GPL-3.0-or-later
#include "atomic_file.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <csignal>
#include <cstring>
#include <memory>
#include <set>
#include <string>
#include <system_error>

#include "origamic/error.hpp"
#include "origamic/output.hpp"

namespace origamic {
namespace {

namespace fs = std::filesystem;

constexpr const char* kPart = ".part";

// A folder held for one run's files: another origamic writing into it waits, so the files of a run
// are all of that run (the last run's set, whole, rather than a mix of two).
class FolderLock {
 public:
  explicit FolderLock(const fs::path& dir) : fd_(::open(dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC)) {
    if (fd_ >= 0) ::flock(fd_, LOCK_EX);
  }
  ~FolderLock() {
    if (fd_ >= 0) ::close(fd_);  // closing releases the lock
  }
  FolderLock(const FolderLock&) = delete;
  FolderLock& operator=(const FolderLock&) = delete;

 private:
  int fd_;
};

// What a run killed while it wrote `file` left: FILE.partPID of a process that is gone. (Only the
// names this run writes: another program's files are not ours to judge.)
void remove_stale_parts(const fs::path& file) {
  const std::string prefix = file.filename().string() + kPart;
  std::error_code error;
  for (fs::directory_iterator it(file.parent_path().empty() ? fs::path(".") : file.parent_path(), error), end;
       !error && it != end; it.increment(error)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= prefix.size() || name.size() > prefix.size() + 9 || name.rfind(prefix, 0) != 0) continue;
    const std::string digits = name.substr(prefix.size());
    if (!std::ranges::all_of(digits, [](char c) { return c >= '0' && c <= '9'; })) continue;
    const auto pid = static_cast<pid_t>(std::stol(digits));
    std::error_code ignored;
    if (::kill(pid, 0) != 0 && errno == ESRCH) fs::remove(it->path(), ignored);
  }
}

// Writes all of bytes to a new file; returns errno, or 0.
int write_new_file(const fs::path& path, const std::string& bytes) {
  const int fd = ::open(path.c_str(), O_WRONLY | O_CREAT | O_TRUNC | O_CLOEXEC, 0644);
  if (fd < 0) return errno;
  std::size_t done = 0;
  int problem = 0;
  while (done < bytes.size()) {
    const ssize_t n = ::write(fd, bytes.data() + done, bytes.size() - done);
    if (n < 0 && errno == EINTR) continue;
    if (n <= 0) {
      problem = n < 0 ? errno : EIO;
      break;
    }
    done += static_cast<std::size_t>(n);
  }
  if (::close(fd) != 0 && problem == 0) problem = errno;  // a full disk may show only here
  return problem;
}

}  // namespace

void write_files(const std::vector<OutputFile>& files) {
  std::vector<fs::path> staged;
  auto discard = [&] {
    std::error_code ignored;
    for (const fs::path& temp : staged) fs::remove(temp, ignored);
  };
  // Each folder once, however it is spelled (flock waits on a second open of the same folder), and
  // in order: two runs lock the folders they share in the same order.
  std::set<fs::path> dirs;
  for (const OutputFile& file : files) {
    const fs::path dir = file.path.parent_path().empty() ? fs::path(".") : file.path.parent_path();
    make_directory(dir);
    std::error_code error;
    const fs::path real = fs::canonical(dir, error);
    dirs.insert(error ? dir : real);
  }
  std::vector<std::unique_ptr<FolderLock>> locks;
  for (const fs::path& dir : dirs) locks.push_back(std::make_unique<FolderLock>(dir));
  for (const OutputFile& file : files) remove_stale_parts(file.path);
  for (const OutputFile& file : files) {
    std::error_code error;
    if (fs::is_directory(file.path, error)) {
      discard();
      throw OutputError(file.path.string() + ": cannot write file (a folder is in the way)");
    }
    const fs::path temp = fs::path(file.path).concat(kPart + std::to_string(::getpid()));
    const int problem = write_new_file(temp, file.bytes);
    staged.push_back(temp);
    if (problem != 0) {
      discard();
      throw OutputError(file.path.string() + ": cannot write file (" + std::strerror(problem) + ")");
    }
  }
  for (std::size_t i = 0; i < files.size(); ++i) {
    std::error_code error;
    fs::rename(staged[i], files[i].path, error);
    if (error) {
      staged.erase(staged.begin(), staged.begin() + static_cast<std::ptrdiff_t>(i));
      discard();
      throw OutputError(files[i].path.string() + ": cannot write file (" + error.message() + ")");
    }
  }
}

void make_directory(const std::filesystem::path& dir) {
  std::error_code error;
  std::filesystem::create_directories(dir, error);
  if (error || !std::filesystem::is_directory(dir))
    throw OutputError(dir.string() + ": cannot create folder" +
                      (error ? " (" + error.message() + ")" : std::string(" (a file is in the way)")));
}

}  // namespace origamic
