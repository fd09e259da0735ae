// SPDX-License-Identifier: Apache-2.0
// campaign_lock.cpp: the lock of a campaign's --out DIR (campaign_lock.hpp).
#include "campaign/campaign_lock.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <cerrno>
#include <cstdio>
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
  return Acquire(path, root, shared, "another campaign (or shards of one)", "", err);
}

namespace {

// "I/N" of a shard lock file's name ".shard-I-of-N.lock", or "" when it is not one.
std::string ShardOfLockName(const std::string &name, unsigned *count) {
  unsigned i = 0, n = 0;
  int end = 0;
  if (std::sscanf(name.c_str(), ".shard-%u-of-%u.lock%n", &i, &n, &end) != 2 ||
      size_t(end) != name.size())
    return "";
  *count = n;
  return std::to_string(i) + "/" + std::to_string(n);
}

// The campaign identity in a shard lock file's second line ("" when there is none).
std::string IdentityInLock(int fd) {
  char buf[512] = {};
  const ssize_t n = pread(fd, buf, sizeof buf - 1, 0);
  const std::string text = n > 0 ? std::string(buf, size_t(n)) : std::string();
  const size_t nl = text.find('\n');
  if (nl == std::string::npos) return "";
  std::string id = text.substr(nl + 1);
  while (!id.empty() && std::isspace(static_cast<unsigned char>(id.back()))) id.pop_back();
  return id;
}

// Why a shard I/`count` of campaign `identity` may not start beside the running shards of DIR
// ("" when it may): a running shard (its lock file held: a shared lock on it cannot be taken)
// of another N, or of another campaign (another identity: an edited campaign file, other
// --set), would run some of the same runs, or other runs into the same directories, at once.
std::string ConflictingShard(const fs::path &root, unsigned count, const std::string &identity) {
  std::error_code ec;
  for (const auto &e : fs::directory_iterator(root, ec)) {
    unsigned n = 0;
    const std::string shard = ShardOfLockName(e.path().filename().string(), &n);
    if (shard.empty()) continue;
    const int fd = open(e.path().c_str(), O_RDONLY | O_CLOEXEC);
    if (fd < 0) continue;
    const bool held = flock(fd, LOCK_SH | LOCK_NB) != 0 && errno == EWOULDBLOCK;
    const std::string other = held ? IdentityInLock(fd) : "";
    close(fd);
    if (held && n != count)
      return "has shard " + shard + " running: the shards of one DIR must all split the plan "
             "the same way (the same N)";
    if (held && other != identity)
      return "has shard " + shard + " of another campaign running (identity " +
             (other.empty() ? std::string("unknown") : other) +
             "): the shards of one DIR must all run the same campaign (the same files and "
             "--set)";
  }
  return "";
}

}  // namespace

// The shards of one DIR must split one campaign's plan the same way: a shard I/N is refused
// while a shard of another N, or of another campaign identity, runs there (ConflictingShard).
// The shard's lock file holds "<pid> on <host>" and its identity. The check and the taking of
// the shard's own lock happen under DIR/.shard-setup.lock (exclusive, held for that moment
// only), so two conflicting shards starting together cannot both pass it.
LockResult CampaignLock::AcquireShard(const fs::path &root, unsigned index, unsigned count,
                                      const std::string &identity, std::ostream &err) {
  const fs::path setup_path = root / ".shard-setup.lock";
  const int setup = open(setup_path.c_str(), O_RDWR | O_CREAT | O_CLOEXEC, 0644);
  if (setup < 0 || flock(setup, LOCK_EX) != 0) {
    err << "uvms campaign: error: cannot lock " << setup_path.string() << ": "
        << std::strerror(errno) << '\n';
    if (setup >= 0) close(setup);
    return LockResult::kFailed;
  }
  const std::string conflict = ConflictingShard(root, count, identity);
  LockResult r = LockResult::kBusy;
  if (!conflict.empty()) {
    err << "uvms campaign: error: " << root.string() << " " << conflict << "; shard " << index
        << "/" << count << " would run into the same run directories at the same time\n";
  } else {
    const fs::path path =
        root / (".shard-" + std::to_string(index) + "-of-" + std::to_string(count) + ".lock");
    const std::string what = "another process running shard " + std::to_string(index) + "/" +
                             std::to_string(count);
    r = Acquire(path, root, false, what.c_str(), identity, err);
  }
  close(setup);
  return r;
}

// Opens `path` (created if needed) and locks it without waiting; the holder's pid (and
// `second_line`, if any) go into an exclusive lock's file (a shared one leaves it empty: it has
// several holders).
LockResult CampaignLock::Acquire(const fs::path &path, const fs::path &root, bool shared,
                                 const char *what, const std::string &second_line,
                                 std::ostream &err) {
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
    char buf[300] = {};
    const ssize_t n = pread(fd_, buf, sizeof buf - 1, 0);
    std::string holder = n > 0 ? std::string(buf, size_t(n)) : std::string();
    holder = holder.substr(0, holder.find('\n'));  // the first line: "<pid> on <host>"
    while (!holder.empty() && std::isspace(static_cast<unsigned char>(holder.back())))
      holder.pop_back();
    err << "uvms campaign: error: " << root.string() << " is in use by " << what
        << (holder.empty() ? std::string() : " (process " + holder + ")") << ": it holds the lock "
        << path.string()
        << ". One campaign at a time per --out: wait until it ends, or give another --out\n";
    return LockResult::kBusy;
  }
  // "<pid> on <host>": a pid alone means little across machines or containers.
  char host[256] = {};
  if (gethostname(host, sizeof host - 1) != 0) host[0] = '\0';
  const std::string pid =
      shared ? std::string()
             : std::to_string(getpid()) + (host[0] ? std::string(" on ") + host : "") + "\n" +
                   (second_line.empty() ? "" : second_line + "\n");
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
