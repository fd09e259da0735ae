// campaign_cli.cpp: `uvms campaign` (campaign_cli.hpp).
#include "campaign_cli.hpp"

#include <fcntl.h>
#include <sys/prctl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <toml++/toml.h>

#include <algorithm>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <iomanip>
#include <iostream>
#include <map>
#include <set>
#include <sstream>
#include <thread>

#include <nlohmann/json.hpp>

#include "scenario.hpp"

namespace uvms::sil {
namespace fs = std::filesystem;
namespace {

using json = nlohmann::ordered_json;

const char *kHelp =
    "usage: uvms campaign FILE.toml --out DIR [-j N] [--transport memq|udpm]\n"
    "                     [--set section.key=value]...\n\n"
    "Expands a campaign (a base scenario, fixed overrides in [set], and [[sweep]] axes whose\n"
    "keys vary together; axes combine as a Cartesian product) into runs, checks every run's\n"
    "scenario first, then runs them N at a time (default: all cores). Finished runs (a\n"
    "summary.json with the same overrides) are kept, so an interrupted campaign resumes.\n"
    "--set adds an override to every run, after the campaign's [set] and before the sweep\n"
    "values (so a sweep still wins), e.g. to shorten every run for a smoke test.\n"
    "Writes DIR/plan.json, DIR/runs/<id>/..., DIR/results.csv and DIR/results.json.\n"
    "Exit status: 0 every run finished, 1 bad campaign or scenario, 2 usage, 3 some run failed\n"
    "(its row says why).\n";

struct CampaignError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

struct Axis {
  std::vector<std::string> keys;                  // dotted scenario keys
  std::vector<std::vector<std::string>> values;   // values[i][k]: TOML text of key k at index i
  std::vector<std::string> labels;                // one per index
};

struct Run {
  std::string id;
  std::vector<std::string> overrides;            // "key=value", [set] first, then the axes
  std::vector<std::pair<std::string, std::string>> swept;  // key, TOML value text
};

struct Campaign {
  std::string name, description, base, transport{"memq"};
  std::vector<std::string> fixed;  // [set] overrides
  std::vector<Axis> axes;
  std::vector<Run> runs;
};

std::string Where(const std::string &file, const toml::node &n) {
  return file + ":" + std::to_string(n.source().begin.line);
}

// A TOML value as TOML text (strings quoted, arrays in brackets).
std::string TomlText(const toml::node &n) {
  std::ostringstream s;
  n.visit([&](const auto &v) {
    if constexpr (toml::is_string<decltype(v)>) {
      s << std::quoted(v.get());
    } else if constexpr (toml::is_table<decltype(v)>) {
      throw CampaignError("tables cannot be sweep values");
    } else {
      s << toml::toml_formatter(v);
    }
  });
  return s.str();
}

std::string LabelPart(const std::string &text) {
  std::string out;
  for (char c : text) {
    if (std::isalnum(static_cast<unsigned char>(c)) || c == '.' || c == '-') out += c;
    else if (!out.empty() && out.back() != '_') out += '_';
  }
  while (!out.empty() && out.back() == '_') out.pop_back();
  return out.empty() ? "v" : out;
}

Campaign LoadCampaign(const std::string &path, const std::vector<std::string> &extra_sets) {
  toml::table root;
  try {
    root = toml::parse_file(path);
  } catch (const toml::parse_error &e) {
    throw CampaignError(path + ":" + std::to_string(e.source().begin.line) + ": " +
                        std::string(e.description()));
  }
  Campaign c;
  c.name = fs::path(path).stem().string();
  for (const auto &[k, v] : root) {
    const std::string key(k.str());
    const std::string at = Where(path, v);
    if (key == "name" || key == "description" || key == "base" || key == "transport") {
      if (!v.is_string()) throw CampaignError(at + ": key \"" + key + "\": expected a string");
      const std::string s = *v.value<std::string>();
      if (key == "name") c.name = s;
      else if (key == "description") c.description = s;
      else if (key == "transport") c.transport = s;
      else c.base = (fs::path(path).parent_path() / s).lexically_normal().string();
    } else if (key == "set") {
      if (!v.is_table()) throw CampaignError(at + ": key \"set\": expected a table");
      for (const auto &[sk, sv] : *v.as_table())
        c.fixed.push_back(std::string(sk.str()) + "=" + TomlText(sv));
    } else if (key == "sweep") {
      const toml::array *arr = v.as_array();
      if (arr == nullptr || !arr->is_array_of_tables())
        throw CampaignError(at + ": key \"sweep\": expected [[sweep]] tables");
      for (const toml::node &tn : *arr) {
        Axis axis;
        const toml::table &t = *tn.as_table();
        size_t n = 0;
        for (const auto &[ak, av] : t) {
          const std::string akey(ak.str());
          const std::string aat = Where(path, av);
          const toml::array *vals = av.as_array();
          if (vals == nullptr || vals->empty())
            throw CampaignError(aat + ": sweep key \"" + akey + "\": expected a non-empty array");
          if (akey == "labels") {
            for (const auto &l : *vals) {
              if (!l.is_string()) throw CampaignError(aat + ": sweep labels must be strings");
              axis.labels.push_back(*l.value<std::string>());
            }
            continue;
          }
          if (n != 0 && vals->size() != n)
            throw CampaignError(aat + ": sweep key \"" + akey + "\" has " +
                                std::to_string(vals->size()) + " values, the axis has " +
                                std::to_string(n) + " (keys of one [[sweep]] vary together)");
          n = vals->size();
          axis.keys.push_back(akey);
          if (axis.values.size() < n) axis.values.resize(n);
          for (size_t i = 0; i < n; ++i) axis.values[i].push_back(TomlText((*vals)[i]));
        }
        if (axis.keys.empty())
          throw CampaignError(Where(path, tn) + ": a [[sweep]] needs at least one key");
        if (!axis.labels.empty() && axis.labels.size() != n)
          throw CampaignError(Where(path, tn) + ": sweep labels: " +
                              std::to_string(axis.labels.size()) + " labels for " +
                              std::to_string(n) + " values");
        if (axis.labels.empty())
          for (size_t i = 0; i < n; ++i) axis.labels.push_back(LabelPart(axis.values[i][0]));
        c.axes.push_back(std::move(axis));
      }
    } else {
      throw CampaignError(at + ": unknown key \"" + key +
                          "\" (expected name, description, base, transport, set, sweep)");
    }
  }
  c.fixed.insert(c.fixed.end(), extra_sets.begin(), extra_sets.end());
  if (c.base.empty()) throw CampaignError(path + ": key \"base\" (the base scenario) is required");
  if (c.transport != "memq" && c.transport != "udpm")
    throw CampaignError(path + ": key \"transport\": expected \"memq\" or \"udpm\"");
  // Expand the Cartesian product of the axes (the last axis varies fastest).
  size_t total = 1;
  for (const Axis &ax : c.axes) total *= ax.values.size();
  for (size_t r = 0; r < total; ++r) {
    std::vector<size_t> idx(c.axes.size());
    size_t rest = r;
    for (size_t a = c.axes.size(); a-- > 0;) {
      idx[a] = rest % c.axes[a].values.size();
      rest /= c.axes[a].values.size();
    }
    Run run;
    std::ostringstream id;
    id << std::setw(3) << std::setfill('0') << r;
    run.overrides = c.fixed;
    for (size_t a = 0; a < c.axes.size(); ++a) {
      const Axis &ax = c.axes[a];
      id << '_' << LabelPart(ax.labels[idx[a]]);
      for (size_t k = 0; k < ax.keys.size(); ++k) {
        run.overrides.push_back(ax.keys[k] + "=" + ax.values[idx[a]][k]);
        run.swept.emplace_back(ax.keys[k], ax.values[idx[a]][k]);
      }
    }
    run.id = id.str();
    c.runs.push_back(std::move(run));
  }
  return c;
}

json ReadJson(const fs::path &p) {
  std::ifstream f(p);
  json j;
  if (!f) return j;
  try {
    f >> j;
  } catch (const std::exception &) {
    return json();
  }
  return j;
}

bool RunIsDone(const fs::path &dir, const Run &r) {
  const json ov = ReadJson(dir / "overrides.json");
  const json sum = ReadJson(dir / "summary.json");
  return ov.is_array() && ov.get<std::vector<std::string>>() == r.overrides && sum.is_object() &&
         sum.contains("status");
}

pid_t SpawnRun(const std::string &self, const Campaign &c, const Run &r, const fs::path &dir) {
  std::vector<std::string> argv = {self, "run", c.base, "--out", dir.string(), "--transport",
                                   c.transport};
  for (const auto &o : r.overrides) {
    argv.push_back("--set");
    argv.push_back(o);
  }
  std::vector<char *> cargs;
  for (auto &a : argv) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  const std::string log = (dir / "run.out").string();
  const pid_t parent = getpid();
  const pid_t pid = fork();
  if (pid == 0) {
    prctl(PR_SET_PDEATHSIG, SIGTERM);
    if (getppid() != parent) _exit(127);
    const int fd = open(log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    if (fd >= 0) {
      dup2(fd, 1);
      dup2(fd, 2);
      close(fd);
    }
    execv(cargs[0], cargs.data());
    _exit(127);
  }
  return pid;
}

std::string Clock(double s) {
  const long t = long(s + 0.5);
  std::ostringstream o;
  o << std::setfill('0') << std::setw(2) << t / 60 << ':' << std::setw(2) << t % 60;
  return o.str();
}

std::string CsvField(const std::string &s) {
  if (s.find_first_of(",\"\n") == std::string::npos) return s;
  std::string o = "\"";
  for (char ch : s) o += ch == '"' ? std::string("\"\"") : std::string(1, ch);
  return o + "\"";
}

// The summary fields that go into the results table (in this order), after id and swept keys.
const char *const kResultKeys[] = {
    "status", "failure", "ticks", "missed_ticks", "duration_s", "mean_ee_error_m",
    "max_ee_error_m", "final_ee_error_m", "thruster_energy_J", "thruster_energy_signed_J",
    "manipulator_energy_J", "max_attitude_error_rad", "min_clearance_m", "final_ee_position_m",
    "final_barycenter_m", "initial_barycenter_m", "final_vehicle_position_m",
    "initial_vehicle_position_m", "integrator_rhs_evals", "wall_time_s", "real_time_factor",
    "reason"};

std::string JsonCell(const json &v) {
  if (v.is_null()) return "";
  if (v.is_string()) return v.get<std::string>();
  if (v.is_array()) {
    std::string s;
    for (size_t i = 0; i < v.size(); ++i) s += (i ? " " : "") + JsonCell(v[i]);
    return s;
  }
  if (v.is_number_float()) {
    std::ostringstream o;
    o << std::setprecision(17) << v.get<double>();
    return o.str();
  }
  return v.dump();
}

}  // namespace

int RunCampaignCli(const std::vector<std::string> &args, std::ostream &out, std::ostream &err) {
  std::string file, out_dir, transport;
  std::vector<std::string> extra_sets;
  unsigned jobs = std::max(1u, std::thread::hardware_concurrency());
  for (size_t i = 0; i < args.size(); ++i) {
    const std::string &a = args[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= args.size()) {
        err << "uvms campaign: error: " << a << " needs a value\n";
        throw 2;
      }
      return args[++i];
    };
    try {
      if (a == "-h" || a == "--help") {
        out << kHelp;
        return 0;
      } else if (a == "--out") {
        out_dir = value();
      } else if (a == "-j" || a == "--jobs") {
        const std::string v = value();
        char *end = nullptr;
        const long n = std::strtol(v.c_str(), &end, 10);
        if (end == v.c_str() || *end != '\0' || n < 1 || n > 256) {
          err << "uvms campaign: error: -j needs a count 1..256, got " << v << '\n';
          return 2;
        }
        jobs = unsigned(n);
      } else if (a == "--transport") {
        transport = value();
      } else if (a == "--set") {
        extra_sets.push_back(value());
      } else if (!a.empty() && a[0] == '-') {
        err << "uvms campaign: error: unknown option " << a << "\n(see uvms campaign --help)\n";
        return 2;
      } else if (file.empty()) {
        file = a;
      } else {
        err << "uvms campaign: error: unexpected argument " << a << '\n';
        return 2;
      }
    } catch (int code) {
      return code;
    }
  }
  if (file.empty() || out_dir.empty()) {
    err << "uvms campaign: error: needs FILE.toml and --out DIR\n(see uvms campaign --help)\n";
    return 2;
  }
  Campaign c;
  try {
    c = LoadCampaign(file, extra_sets);
    if (!transport.empty()) {
      if (transport != "memq" && transport != "udpm")
        throw CampaignError("--transport must be memq or udpm");
      c.transport = transport;
    }
    // Every run's scenario is checked before anything starts.
    for (const Run &r : c.runs) {
      try {
        (void)LoadScenario(c.base, r.overrides);
      } catch (const ScenarioError &e) {
        throw CampaignError("run " + r.id + ": " + e.what());
      }
    }
  } catch (const CampaignError &e) {
    err << "uvms campaign: error: " << e.what() << '\n';
    return 1;
  }

  const fs::path root(out_dir);
  std::error_code ec;
  fs::create_directories(root / "runs", ec);
  if (ec) {
    err << "uvms campaign: error: cannot create " << (root / "runs") << ": " << ec.message() << '\n';
    return 1;
  }
  {
    json plan;
    plan["campaign"] = fs::absolute(file).lexically_normal().string();
    plan["name"] = c.name;
    plan["description"] = c.description;
    plan["base"] = c.base;
    plan["transport"] = c.transport;
    plan["runs"] = json::array();
    for (const Run &r : c.runs) plan["runs"].push_back({{"id", r.id}, {"overrides", r.overrides}});
    std::ofstream(root / "plan.json") << std::setw(2) << plan << '\n';
  }

  std::error_code sec;
  const std::string self = fs::read_symlink("/proc/self/exe", sec).string();
  std::vector<const Run *> todo;
  for (const Run &r : c.runs) {
    if (!RunIsDone(root / "runs" / r.id, r)) todo.push_back(&r);
  }
  const size_t total = c.runs.size(), skipped = total - todo.size();
  out << "uvms campaign: " << c.name << ": " << total << " runs (" << skipped
      << " already done), " << jobs << " at a time, transport " << c.transport << '\n';
  const bool tty = isatty(fileno(stdout)) != 0;
  const auto t0 = std::chrono::steady_clock::now();
  std::map<pid_t, const Run *> running;
  size_t next = 0, done = 0;
  auto progress = [&](const Run *finished, int rc) {
    const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    const double eta = done > 0 ? el / double(done) * double(todo.size() - done) : 0.0;
    std::ostringstream line;
    line << "[" << (skipped + done) << "/" << total << "] elapsed " << Clock(el) << ", ETA "
         << (done > 0 ? Clock(eta) : std::string("--:--"));
    if (tty) {
      out << "\r" << line.str() << "   " << std::flush;
    } else if (finished != nullptr) {
      out << line.str() << "  " << finished->id << (rc == 0 ? " finished" : " FAILED") << '\n';
    }
  };
  while (next < todo.size() || !running.empty()) {
    while (next < todo.size() && running.size() < jobs) {
      const Run *r = todo[next++];
      const fs::path dir = root / "runs" / r->id;
      fs::create_directories(dir, ec);
      fs::remove(dir / "summary.json", ec);
      std::ofstream(dir / "overrides.json") << json(r->overrides).dump(2) << '\n';
      const pid_t pid = SpawnRun(self, c, *r, dir);
      if (pid < 0) {
        err << "uvms campaign: error: cannot start run " << r->id << '\n';
        return 3;
      }
      running[pid] = r;
    }
    int st = 0;
    const pid_t pid = waitpid(-1, &st, 0);
    if (pid < 0) {
      if (errno == EINTR) continue;
      break;
    }
    const auto it = running.find(pid);
    if (it == running.end()) continue;
    ++done;
    progress(it->second, WIFEXITED(st) ? WEXITSTATUS(st) : 128);
    running.erase(it);
  }
  if (tty) out << '\n';

  // Results: one row per run, in plan order.
  json rows = json::array();
  std::set<std::string> swept_keys_seen;
  std::vector<std::string> swept_keys;
  for (const Axis &ax : c.axes)
    for (const auto &k : ax.keys)
      if (swept_keys_seen.insert(k).second) swept_keys.push_back(k);
  std::ofstream csv(root / "results.csv");
  csv << "id";
  for (const auto &k : swept_keys) csv << ',' << CsvField(k);
  for (const char *k : kResultKeys) csv << ',' << k;
  csv << '\n';
  int failed = 0;
  for (const Run &r : c.runs) {
    const json sum = ReadJson(root / "runs" / r.id / "summary.json");
    json row;
    row["id"] = r.id;
    for (const auto &[k, v] : r.swept) {
      try {
        row[k] = json::parse(v);  // numbers, booleans, strings, arrays read as JSON
      } catch (const std::exception &) {
        row[k] = v;
      }
    }
    if (!sum.is_object()) {
      row["status"] = "failed";
      row["reason"] = "no summary.json (see runs/" + r.id + "/run.out)";
    }
    for (const auto &[k, v] : sum.items()) row[k] = v;
    if (row.value("status", std::string()) != "finished") ++failed;
    csv << CsvField(r.id);
    for (const auto &k : swept_keys) csv << ',' << CsvField(JsonCell(row.value(k, json())));
    for (const char *k : kResultKeys) csv << ',' << CsvField(JsonCell(row.value(k, json())));
    csv << '\n';
    rows.push_back(row);
  }
  json results;
  results["name"] = c.name;
  results["description"] = c.description;
  results["base"] = c.base;
  results["swept_keys"] = swept_keys;
  results["runs"] = rows;
  std::ofstream(root / "results.json") << std::setw(2) << results << '\n';
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  out << "uvms campaign: " << c.name << ": " << (total - size_t(failed)) << "/" << total
      << " runs finished in " << std::fixed << std::setprecision(1) << el << " s; "
      << (root / "results.csv").string() << '\n';
  return failed == 0 ? 0 : 3;
}

}  // namespace uvms::sil
