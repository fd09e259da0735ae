# SPDX-License-Identifier: Apache-2.0
"""tools/uvmslog.py on a freshly recorded short run: per-channel tick counts against the
summary, the final truth sample against the summary's final EE position, the SPEC §10 EE error
recomputed from the log against the plant's mean (an independent recomputation: Python from the
logged messages vs the C++ plant node's running sum), and the CLI (list, --plot, --csv, errors).

Usage: test_uvmslog.py UVMS_EXE SOURCE_DIR
"""
import json
import math
import os
import shutil
import subprocess
import sys
import tempfile

UVMS, SRC = sys.argv[1], sys.argv[2]
sys.path.insert(0, os.path.join(SRC, "tools"))
import uvmslog  # noqa: E402

PY = sys.executable
TOOL = os.path.join(SRC, "tools", "uvmslog.py")
TMP = tempfile.mkdtemp(prefix="uvms-uvmslog-")
# The plant sums ε over ticks in double; numpy's sum and norm differ from it only by rounding
# (a few ulps per tick over 50 ticks), far below 1e-12 relative.
REL_TOL_MEAN = 1e-12
PNG_MAGIC = b"\x89PNG\r\n\x1a\n"

failures = []


def check(cond, msg):
    print(("ok   " if cond else "FAIL ") + msg)
    if not cond:
        failures.append(msg)


out = os.path.join(TMP, "run")
cmd = [UVMS, "run", os.path.join(SRC, "sil/scenarios/paper/case_VII_stagnant.toml"),
       "--out", out, "--set", "run.duration_s=1.5", "--set", "trajectory.duration_s=1.5",
       "--transport", "memq"]
p = subprocess.run(cmd, capture_output=True, text=True)
check(p.returncode == 0, f"uvms run exits 0 ({p.returncode}: {p.stderr.strip()[-300:]})")
summary = json.load(open(os.path.join(out, "summary.json")))
n = summary["ticks"]
check(summary["status"] == "finished" and n == 50, f"run finished with 50 ticks ({n})")

log = uvmslog.load(os.path.join(out, "run.lcmlog"))
tm, tr = log["UVMS_TELEMETRY"], log["UVMS_TRUTH"]
check(log["UVMS_SENSORS"].count == n, f"UVMS_SENSORS: {log['UVMS_SENSORS'].count} == ticks")
check(log["UVMS_ACTUATORS"].count == n, f"UVMS_ACTUATORS: {log['UVMS_ACTUATORS'].count} == ticks")
check(int((tm["tick"] >= 0).sum()) == n and int((tm["tick"] == -1).sum()) == 1,
      "UVMS_TELEMETRY: one per tick plus the configuration acknowledgement (tick -1)")
check(tr.count == n + 1 and int(tr["tick"][-1]) == n, "UVMS_TRUTH: one per tick plus the final")
check(log["UVMS_CONFIG"].count == 1 and log["UVMS_STATUS"].count == 2,
      "UVMS_CONFIG once, UVMS_STATUS at start and end")
check(list(log["UVMS_SENSORS"]["tick"]) == list(range(n)), "sensor ticks are 0..n-1 in order")
tick_s = float(log["UVMS_CONFIG"]["tick_s"][0])
check(all(abs(t - k * tick_s) < 1e-6 for t, k in zip(tr["t_s"], tr["tick"])),
      "truth t_s == tick · tick_s (µs resolution)")
check((tr["log_utime"] == tr["utime"]).all(), "event timestamps == message utime (simulated time)")
check(tr["ee_position_m"].shape == (n + 1, 3) and tr["closest_pair"].dtype.kind == "U",
      "field shapes: ee_position_m (n, 3); strings as str")
check(log["UVMS_STATUS"]["state"][-1] == 2 and log["UVMS_STATUS"]["reason"][-1] == "",
      "final status FINISHED with an empty reason")

final = tr.select(tr["tick"] == n)["ee_position_m"][0]
check(list(final) == list(summary["final_ee_position_m"]),
      f"final truth ee_position_m {final.tolist()} == summary {summary['final_ee_position_m']}")

# EE error, twice: by hand from the raw messages (dict by tick, math.fsum) and by the helper.
est = {int(k): e for k, e in zip(tm["tick"], tm["ee_estimate_m"]) if k >= 0}
eps = [math.dist(p, est[int(k)]) for k, p in zip(tr["tick"], tr["ee_position_m"]) if int(k) in est]
mean_by_hand = math.fsum(eps) / len(eps)
ref = summary["mean_ee_error_m"]
check(len(eps) == n, f"{len(eps)} ticks have both truth and telemetry")
check(abs(mean_by_hand - ref) <= REL_TOL_MEAN * abs(ref),
      f"mean EE error from the log {mean_by_hand!r} vs summary {ref!r}")
_, _, eps2 = uvmslog.ee_error(log)
check(abs(eps2.mean() - ref) <= REL_TOL_MEAN * abs(ref), f"uvmslog.ee_error mean {eps2.mean()!r}")
check(abs(max(eps) - summary["max_ee_error_m"]) <= REL_TOL_MEAN * summary["max_ee_error_m"],
      "max EE error from the log == summary max")

# CLI.
lg = os.path.join(out, "run.lcmlog")
p = subprocess.run([PY, TOOL, lg], capture_output=True, text=True)
check(p.returncode == 0 and "UVMS_TRUTH  (truth_t): 51 messages" in p.stdout
      and "ee_position_m" in p.stdout and "[rad/s]" in p.stdout,
      "CLI listing names channels, counts, fields and units")
png = os.path.join(TMP, "fig.png")
p = subprocess.run([PY, TOOL, lg, "--plot", "UVMS_TRUTH.ee_position_m[0]", "--plot",
                    "UVMS_TELEMETRY.force_des_N", "--plot", "UVMS_TRUTH.motor_speed_rad_s",
                    "--out", png], capture_output=True, text=True)
check(p.returncode == 0 and os.path.getsize(png) > 1000 and open(png, "rb").read(8) == PNG_MAGIC,
      f"--plot writes a PNG ({p.stderr.strip()[-200:]})")
csv_path = os.path.join(TMP, "truth.csv")
p = subprocess.run([PY, TOOL, lg, "--csv", "UVMS_TRUTH", "--out", csv_path],
                   capture_output=True, text=True)
rows = open(csv_path).read().splitlines() if p.returncode == 0 else []
check(len(rows) == n + 2 and "ee_position_m[2]" in rows[0].split(","),
      "--csv writes a header and one row per message")
last = dict(zip(rows[0].split(","), rows[-1].split(","))) if rows else {}
check(float(last.get("ee_position_m[0]", "nan")) == final[0], "CSV values round-trip exactly")
p = subprocess.run([PY, TOOL, lg, "--plot", "UVMS_TRUTH.no_such_field", "--out", png],
                   capture_output=True, text=True)
check(p.returncode == 1 and "no_such_field" in p.stderr and "ee_position_m" in p.stderr,
      "an unknown field is an error naming it and listing the fields")

# Without generated types anywhere: a clear error that says where it looked.
iso = os.path.join(TMP, "iso", "tools")
os.makedirs(iso)
for name in ("uvmslog.py", "toolenv.py"):
    shutil.copy(os.path.join(SRC, "tools", name), iso)
env = {k: v for k, v in os.environ.items() if k not in ("UVMS_LCM_PYTHON_PATH", "PYTHONPATH")}
p = subprocess.run([PY, os.path.join(iso, "uvmslog.py"), lg], capture_output=True, text=True,
                   env=env)
check(p.returncode == 1 and "not found" in p.stderr and "UVMS_LCM_PYTHON_PATH" in p.stderr,
      f"missing types: clear error ({p.stderr.strip()[:160]})")

shutil.rmtree(TMP, ignore_errors=True)
print(f"{len(failures)} failure(s)")
sys.exit(1 if failures else 0)
