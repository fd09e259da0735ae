// SPDX-License-Identifier: Apache-2.0
// campaign_lock.cpp: the lock of a campaign's --out DIR (campaign_lock.hpp).
#include "campaign_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdlib>
#include <cstring>
#include <ostream>
#include <string>

namespace uvms::sil {
namespace fs = std::filesystem;

CampaignLock::~CampaignLock() {
  if (fd_ >= 0 && owned_) close(fd_);
}

LockResult CampaignLock::AcquireCampaign(const fs::path &root, bool shared, std::ostream &err) {
  const fs::path path = root / ".campaign.lock";
  const char *fd_text = std::getenv(kLockFdEnv);
  if (!shared && fd_text != nullptr && *fd_text != '\0') return TakeOver(path, fd_text, err);
  return Acquire(path, root, shared, "another campaign (or shards of one)", err);
}

LockResult CampaignLock::AcquireShard(const fs::path &root, unsigned index, unsigned count,
                                      std::ostream &err) {
  const fs::path path =
      root / (".shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".lock");
  const std::string what = "another process running shard " + std::to_string(index) + "/" +
                           std::to_string(count);
  return Acquire(path, root, false, what.c_str(), err);
}

// Opens `path` (created if needed) and locks it without waiting; the holder's pid goes into an
// exclusive lock's file (a shared one leaves it empty: it has several holders).
LockResult CampaignLock::Acquire(const fs::path &path, const fs::path &root, bool shared,
                                 const char *what, std::ostream &err) {
  fd_ = open(path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (fd_ < 0) {
    err << "uvms campaign: error: cannot create the lock file " << path.string() << ": "
        << std::strerror(errno) << '\n';
    return LockResult::kFailed;
  }
  if (flock(fd_, (shared ? LOCK_SH : LOCK_EX) | LOCK_NB) != 0) {
    const int e = errno;
    if (e != EWOULDBLOCK) {
      err << "uvms campaign: error: cannot lock " << path.string() << ": " << std::strerror(e)
          << '\n';
      return LockResult::kFailed;
    }
    char buf[32] = {};
    const ssize_t n = pread(fd_, buf, sizeof buf - 1, 0);
    std::string holder = n > 0 ? std::string(buf, size_t(n)) : std::string();
    while (!holder.empty() && !std::isdigit(static_cast<unsigned char>(holder.back())))
      holder.pop_back();
    err << "uvms campaign: error: " << root.string() << " is in use by " << what
        << (holder.empty() ? std::string() : " (process " + holder + ")") << ": it holds the lock "
        << path.string()
        << ". One campaign at a time per --out: wait until it ends, or give another --out\n";
    return LockResult::kBusy;
  }
  const std::string pid = shared ? std::string() : std::to_string(getpid()) + "\n";
  if (ftruncate(fd_, 0) != 0 ||
      (!pid.empty() && pwrite(fd_, pid.data(), pid.size(), 0) != ssize_t(pid.size()))) {
    err << "uvms campaign: error: cannot write " << path.string() << ": " << std::strerror(errno)
        << '\n';
    return LockResult::kFailed;
  }
  return LockResult::kHeld;
}

// UVMS_CAMPAIGN_LOCK_FD: the descriptor must be `path` (the same device and inode); flock on
// it then succeeds at once when its open file description holds the exclusive lock already
// (and takes it when the caller had opened it without locking), and fails when another
// campaign holds it.
LockResult CampaignLock::TakeOver(const fs::path &path, const char *fd_text, std::ostream &err) {
  char *end = nullptr;
  errno = 0;
  const long fd = std::strtol(fd_text, &end, 10);
  struct stat given {}, file {};
  const bool number = end != fd_text && *end == '\0' && errno == 0 && fd >= 0 && fd < 1 << 20;
  if (!number || fstat(int(fd), &given) != 0 || stat(path.c_str(), &file) != 0 ||
      given.st_dev != file.st_dev || given.st_ino != file.st_ino) {
    err << "uvms campaign: error: " << kLockFdEnv << "=" << fd_text
        << " is not an open descriptor of " << path.string()
        << " (it hands over the lock of a program that runs uvms campaign; unset it)\n";
    return LockResult::kBadFd;
  }
  if (flock(int(fd), LOCK_EX | LOCK_NB) != 0) {
    err << "uvms campaign: error: " << kLockFdEnv << "=" << fd_text << ": the lock "
        << path.string() << " is held by another campaign: " << std::strerror(errno) << '\n';
    return LockResult::kBusy;
  }
  fd_ = int(fd);
  owned_ = false;
  return LockResult::kHeld;
}

}  // namespace uvms::sil
