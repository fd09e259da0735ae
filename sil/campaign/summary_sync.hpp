// SPDX-License-Identifier: Apache-2.0
// summary_sync.hpp: how the summaries of a campaign's runs reach the disk (docs/CAMPAIGNS.md,
// "How a run is executed", step 3).
#pragma once

#include <filesystem>
#include <iosfwd>
#include <string>
#include <vector>

namespace uvms::sil {

/// A campaign's runs put their summary.json in place without an fsync (`uvms run
/// --no-summary-fsync`) where one syncfs of DIR/runs' file system after the runs makes them
/// durable and reports a failed write: Linux 5.8 or later (syncfs reports write-back errors
/// since then) and not a FUSE file system (its syncfs reaches the storage only on virtiofs).
/// Elsewhere every run syncs its own summary, as `uvms run` does by default.
///
/// DIR/runs is opened before the first run, so that the syncfs after the last one reports every
/// write-back error its file system met in between, the kernel's own write-back of the summaries
/// included. syncfs reports errors of the whole file system, any file's: on an error each
/// summary of the campaign is synced alone (every file keeps its own error), and one that fails
/// is removed, so its run runs again; an error in no summary is only noted.
class SummarySync {
 public:
  /// Opens `runs_dir` (DIR/runs, which must exist); OpenError() says if that failed.
  explicit SummarySync(const std::filesystem::path &runs_dir);
  SummarySync(const SummarySync &) = delete;
  SummarySync &operator=(const SummarySync &) = delete;
  ~SummarySync();

  /// "" when runs_dir is open, else why not ("cannot open DIR/runs: ...").
  const std::string &OpenError() const { return open_error_; }

  /// Whether the runs may leave their summaries unsynced (see the class).
  bool Deferred() const { return deferred_; }

  /// After the runs, when Deferred(): one syncfs; on an error, the summary.json of each run of
  /// `ids` (directories under runs_dir) fsync'd alone and, if that fails, removed. "" when every
  /// summary that exists is on disk (an error elsewhere on the file system is noted on `note`),
  /// else why not, with the number of summaries removed; OpenError() when runs_dir is not open.
  std::string Sync(const std::vector<std::string> &ids, std::ostream &note) const;

 private:
  std::filesystem::path runs_dir_;
  std::string open_error_;
  int fd_{-1};
  bool deferred_{false};
};

}  // namespace uvms::sil
