// SPDX-License-Identifier: Apache-2.0
// summary_sync.cpp: see summary_sync.hpp.
#include "campaign/summary_sync.hpp"

#include <fcntl.h>
#include <linux/magic.h>
#include <sys/statfs.h>
#include <sys/utsname.h>
#include <unistd.h>

#include <cerrno>
#include <cstdio>
#include <cstring>
#include <ostream>

namespace uvms::sil {
namespace fs = std::filesystem;

namespace {

// Whether this kernel's syncfs reports write-back errors (Linux 5.8 and later).
bool SyncfsReportsErrors() {
  utsname u{};
  int major = 0, minor = 0;
  if (uname(&u) != 0 || std::sscanf(u.release, "%d.%d", &major, &minor) != 2) return false;
  return major > 5 || (major == 5 && minor >= 8);
}

// Whether the file system of `fd` passes syncfs on to its storage (not FUSE).
bool SyncfsReachesStorage(int fd) {
  struct statfs s {};
  return fstatfs(fd, &s) == 0 && static_cast<unsigned long>(s.f_type) != FUSE_SUPER_MAGIC;
}

// fsync of one summary: false if it failed (a write-back error of that file); true if it is on
// disk or there is none.
bool SummaryOnDisk(const fs::path &summary) {
  const int fd = open(summary.c_str(), O_RDONLY | O_CLOEXEC);
  if (fd < 0) return errno == ENOENT;
  const bool ok = fsync(fd) == 0 || errno == EINVAL;
  close(fd);
  return ok;
}

}  // namespace

SummarySync::SummarySync(const fs::path &runs_dir) : runs_dir_(runs_dir) {
  fd_ = open(runs_dir.c_str(), O_RDONLY | O_DIRECTORY | O_CLOEXEC);
  if (fd_ < 0) {
    open_error_ = "cannot open " + runs_dir.string() + ": " + std::strerror(errno);
    return;
  }
  deferred_ = SyncfsReportsErrors() && SyncfsReachesStorage(fd_);
}

SummarySync::~SummarySync() {
  if (fd_ >= 0) close(fd_);
}

std::string SummarySync::Sync(const std::vector<std::string> &ids, std::ostream &note) const {
  if (fd_ < 0) return open_error_;
  if (!deferred_ || syncfs(fd_) == 0) return "";
  const std::string why = std::strerror(errno);
  size_t removed = 0, failed_removal = 0;
  for (const std::string &id : ids) {
    const fs::path summary = runs_dir_ / id / "summary.json";
    if (SummaryOnDisk(summary)) continue;
    if (unlink(summary.c_str()) == 0) ++removed;
    else ++failed_removal;
  }
  if (removed == 0 && failed_removal == 0) {
    note << "uvms campaign: note: syncfs on " << runs_dir_.string() << " reported a write-back "
         << "error on its file system (" << why << "); every summary of this campaign was then "
         << "synced alone without an error\n";
    return "";
  }
  return std::to_string(removed + failed_removal) + " of " + std::to_string(ids.size()) +
         " runs' summaries could not be written to disk (syncfs on " + runs_dir_.string() +
         ": " + why + ", then an fsync of each); " +
         (failed_removal == 0 ? std::string("they were removed, so those runs run again")
                              : std::to_string(failed_removal) + " of them could not be removed "
                                "either and would count as done: check the disk");
}

}  // namespace uvms::sil
