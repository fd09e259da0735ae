// SPDX-License-Identifier: Apache-2.0
// toml_bounds.hpp: input bounds of the TOML files the tools read (scenario and campaign),
// checked on the raw text before toml++ sees it: toml++ recurses on nesting and dotted keys,
// and a 50,000-part dotted key overflows its stack. Header-only (the scenario reader and the
// campaign library both use it); errors are returned as text, each caller throws its own type.
#pragma once

#include <sys/stat.h>

#include <algorithm>
#include <cctype>
#include <cerrno>
#include <cstdint>
#include <cstring>
#include <fstream>
#include <string>
#include <string_view>

namespace uvms::sil {

constexpr std::size_t kMaxTomlBytes = 1u << 20;  ///< a scenario or campaign file: 1 MiB
constexpr int kMaxTomlNesting = 32;              ///< arrays and inline tables inside each other
constexpr int kMaxDottedParts = 32;              ///< parts of one dotted key (a.b.c: 3)

namespace toml_bounds_detail {

/// The raw-text scan: nesting depth of [ and {, and the parts of a dotted chain
/// (key.key.key, quoted parts included), outside strings and comments.
class Scan {
 public:
  Scan(std::string_view t, const std::string &source) : t_(t), source_(source) {}

  /// "" when within bounds, else "SOURCE:LINE: what (input bounds, checked before parsing)".
  std::string Run() {
    while (err_.empty() && i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '"' || c == '\'') {
        SkipString(c);
        continue;
      }
      Char(c);
      if (c == '\n') ++line_;
      ++i_;
    }
    return err_;
  }

 private:
  void Fail(const std::string &what) {
    if (err_.empty())
      err_ = source_ + ":" + std::to_string(line_) + ": " + what +
             " (input bounds, checked before parsing)";
  }
  void Char(char c) {
    if (c == '\0') {
      Fail("a NUL byte (expected UTF-8 text)");
    } else if (c == '#') {
      while (i_ + 1 < t_.size() && t_[i_ + 1] != '\n') ++i_;
      chain_ = 0;
    } else if (c == '.') {
      if (++chain_ >= kMaxDottedParts)
        Fail("a dotted key of more than " + std::to_string(kMaxDottedParts) + " parts");
    } else if (c == '[' || c == '{') {
      chain_ = 0;
      if (++depth_ > kMaxTomlNesting)
        Fail("nesting deeper than " + std::to_string(kMaxTomlNesting) + " arrays/tables");
    } else if (c == ']' || c == '}') {
      chain_ = 0;
      depth_ = depth_ > 0 ? depth_ - 1 : 0;
    } else if (!(std::isalnum(static_cast<unsigned char>(c)) || c == '_' || c == '-' || c == ' ' ||
                 c == '\t' || c == '+')) {
      chain_ = 0;
    }
  }
  /// From an opening quote q to after its closing quote(s); lines counted.
  void SkipString(char q) {
    const std::string triple(3, q);
    const bool multi = t_.substr(i_, 3) == triple;
    i_ += multi ? 3 : 1;
    while (i_ < t_.size()) {
      const char c = t_[i_];
      if (c == '\0') return Fail("a NUL byte (expected UTF-8 text)");
      if (c == '\n' && !multi) return;  // unterminated: toml++ reports it
      if (c == '\n') ++line_;
      if (c == '\\' && q == '"') {
        if (i_ + 1 < t_.size() && t_[i_ + 1] == '\n') ++line_;
        i_ += 2;
        continue;
      }
      if (c == q && (!multi || t_.substr(i_, 3) == triple)) {
        i_ += multi ? 3 : 1;
        return;
      }
      ++i_;
    }
  }

  std::string_view t_;
  const std::string &source_;
  std::string err_;
  std::size_t i_{0};
  int line_{1};
  int depth_{0};
  int chain_{0};
};

}  // namespace toml_bounds_detail

/// "" when `text` is within the bounds above (size, nesting, dotted-key parts, no NUL byte),
/// else the error, placed at SOURCE or SOURCE:LINE.
inline std::string TomlBoundsError(std::string_view text, const std::string &source) {
  if (text.size() > kMaxTomlBytes)
    return source + ": the file has " + std::to_string(text.size()) + " bytes (expected at most " +
           std::to_string(kMaxTomlBytes) + "; input bounds, checked before parsing)";
  return toml_bounds_detail::Scan(text, source).Run();
}

/// Read a TOML input: a regular file (not a directory, a device such as /dev/urandom, a FIFO)
/// of at most kMaxTomlBytes. False with *err "PATH: why" otherwise.
inline bool ReadBoundedFile(const std::string &path, std::string *bytes, std::string *err) {
  struct stat st {};
  if (::stat(path.c_str(), &st) != 0) {
    *err = path + ": cannot read the file (" + std::strerror(errno) + ")";
    return false;
  }
  if (!S_ISREG(st.st_mode)) {
    *err = path + ": not a regular file (" +
           (S_ISDIR(st.st_mode) ? std::string("a directory")
                                : std::string("a device, FIFO or socket")) +
           "; expected a TOML file)";
    return false;
  }
  std::ifstream in(path, std::ios::binary);
  if (!in) {
    *err = path + ": cannot read the file (" + std::strerror(errno) + ")";
    return false;
  }
  // In chunks up to one byte past the bound, the first sized by the file's size at stat():
  // only the memory the file needs is touched (filling the whole bound for every file cost
  // each campaign run 256 page faults), and a file that grew since is still refused past it.
  bytes->clear();
  std::size_t chunk = std::min<std::size_t>(std::size_t(st.st_size) + 1, kMaxTomlBytes + 1);
  while (bytes->size() <= kMaxTomlBytes) {
    const std::size_t have = bytes->size();
    const std::size_t want = std::min(chunk, kMaxTomlBytes + 1 - have);
    bytes->resize(have + want);
    in.read(bytes->data() + have, static_cast<std::streamsize>(want));
    if (in.bad()) {
      *err = path + ": cannot read the file (read error)";
      return false;
    }
    bytes->resize(have + static_cast<std::size_t>(in.gcount()));
    if (static_cast<std::size_t>(in.gcount()) < want) break;  // the end of the file
    chunk = std::size_t(64) * 1024;
  }
  if (bytes->size() > kMaxTomlBytes) {
    *err = path + ": the file has more than " + std::to_string(kMaxTomlBytes) +
           " bytes (expected at most that; input bounds, checked before parsing)";
    return false;
  }
  return true;
}

}  // namespace uvms::sil
