// SPDX-License-Identifier: Apache-2.0
// campaign_lock.hpp: the lock of a campaign's --out DIR (docs/SCENARIOS.md "Campaigns",
// docs/CAMPAIGNS.md "Shards").
//
// A campaign, a merge and tools/campaign-dask hold an exclusive flock(2) on DIR/.campaign.lock;
// the shards of one campaign hold it shared, so that they run side by side while a whole
// campaign or a merge waits for none of them (it is refused at once), and each shard holds an
// exclusive flock on DIR/.shard-<I>-of-<N>.lock as well (the same shard twice, or a shard of
// another N or another campaign beside running shards, is refused). The
// kernel drops a flock when its holder's last descriptor closes, however the process ends: a
// crash leaves no stale lock. The lock file stays (removing it would race with a campaign that
// has just opened it) and holds the pid of the holder, for the message of a refused campaign.
//
// Hand-over: a process that holds DIR/.campaign.lock exclusively (tools/campaign-dask) runs
// `uvms campaign` with the descriptor inherited and its number in UVMS_CAMPAIGN_LOCK_FD; uvms
// then checks that the descriptor is DIR/.campaign.lock and that its lock is exclusive, and
// works under it instead of locking again.
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>

namespace uvms::sil {

/// How a lock attempt ended (the message, if any, went to the error stream).
enum class LockResult {
  kHeld,    ///< the lock is held by this object
  kBusy,    ///< another campaign holds it
  kFailed,  ///< the lock file could not be created, locked or written
  kBadFd,   ///< UVMS_CAMPAIGN_LOCK_FD names no descriptor of DIR/.campaign.lock held exclusively
};

/// The name of the environment variable of the hand-over (see above).
inline constexpr const char *kLockFdEnv = "UVMS_CAMPAIGN_LOCK_FD";

/// One lock file of DIR, held for this object's lifetime (close-on-exec: no run inherits it).
class CampaignLock {
 public:
  CampaignLock() = default;
  CampaignLock(const CampaignLock &) = delete;
  CampaignLock &operator=(const CampaignLock &) = delete;
  ~CampaignLock();

  /// DIR/.campaign.lock, exclusive (a campaign, a merge) or shared (a shard); exclusive takes
  /// over the descriptor of UVMS_CAMPAIGN_LOCK_FD when it is set.
  LockResult AcquireCampaign(const std::filesystem::path &root, bool shared, std::ostream &err);

  /// DIR/.shard-<index>-of-<count>.lock, exclusive, holding `identity` (the campaign's);
  /// refused (kBusy) while a shard of another count or another identity runs in DIR.
  LockResult AcquireShard(const std::filesystem::path &root, unsigned index, unsigned count,
                          const std::string &identity, std::ostream &err);

 private:
  LockResult Acquire(const std::filesystem::path &path, const std::filesystem::path &root,
                     bool shared, const char *what, const std::string &second_line,
                     std::ostream &err);
  LockResult TakeOver(const std::filesystem::path &path, const char *fd_text, std::ostream &err);

  int fd_{-1};
  bool owned_{true};  ///< false for a handed-over descriptor (left open: its owner's)
};

}  // namespace uvms::sil
