# SPDX-License-Identifier: Apache-2.0
"""The Java LCM types (lcmgen/uvms_lcmtypes.jar) decode fresh run logs completely, as the
Python decoder does, and tools/lcm-spy launches lcm-spy with them.

Why: lcm-spy and any Java LCM tool decode with this jar; a type missing from it, or generated
from other lcmtypes/*.lcm than the logs', shows channels as undecodable. Checked against
independent things: the jar's classes against lcmtypes/*.lcm, LCM's Java API
(tests/tools/java/UvmsLogCount.java, compiled here: no build step) against tools/uvmslog.py
(Python lcm) per channel, every field of the last message (UVMS_TRUTH; UVMS_SCENE with an
obstacle: strings and variable-length arrays) bit for bit, and foreign, truncated and
non-LCM input reported as errors. tools/lcm-spy is run against a stand-in `java` that records
its command line (no display needed).

Usage: test_lcm_java.py UVMS_EXE SOURCE_DIR UVMS_LCM_JAR [LCM_JAVA_JAR]
(LCM_JAVA_JAR: LCM's Java library, default /usr/share/java/lcm.jar)
"""
import math
import os
import re
import signal
import subprocess
import sys
import time
import zipfile

UVMS, SRC, JAR = sys.argv[1], sys.argv[2], sys.argv[3]
LCM_JAR = sys.argv[4] if len(sys.argv) > 4 else "/usr/share/java/lcm.jar"
sys.path.insert(0, os.path.join(SRC, "tools"))
import lcm  # noqa: E402
from uvms_tools.log import runlog  # noqa: E402

sys.path.insert(0, os.path.dirname(os.path.abspath(__file__)))
import checklist  # noqa: E402

sys.path.insert(0, os.path.join(os.path.dirname(os.path.abspath(__file__)), os.pardir, "support"))
from scratch import scratch_dir  # noqa: E402  (tests/support/scratch.py)

JAVA_SRC = os.path.join(SRC, "tests", "tools", "java", "UvmsLogCount.java")
SPY = os.path.join(SRC, "tools", "lcm-spy")
URL = "udpm://239.255.76.67:7667?ttl=0"
FOREIGN_FINGERPRINT = bytes.fromhex("0123456789abcdef")
TMP = scratch_dir("uvms-lcm-java-")  # removed at exit (tests/support/scratch.py)
CLASSES = os.path.join(TMP, "classes")


def make_run(scenario, duration_s, name):
    """A fresh run (memq: no multicast needed); returns its log path."""
    out = os.path.join(TMP, name)
    p = subprocess.run([UVMS, "run", scenario, "--set", f"run.duration_s={duration_s}",
                        "--transport", "memq", "--out", out],
                       cwd=SRC, capture_output=True, text=True)
    assert p.returncode == 0, f"uvms run {scenario}: exit {p.returncode}: {p.stderr[-300:]}"
    return os.path.join(out, "run.lcmlog")


def compile_checker():
    os.makedirs(CLASSES)
    p = subprocess.run(["javac", "-Xlint:all", "-Werror", "-cp", f"{LCM_JAR}:{JAR}", "-d",
                        CLASSES, JAVA_SRC], capture_output=True, text=True)
    assert p.returncode == 0 and not p.stderr, f"javac UvmsLogCount.java: {p.stderr[-500:]}"


def java_count(log_path, *last):
    """UvmsLogCount on a log: (CompletedProcess, {channel: count}, {(channel, field): text})."""
    cmd = ["java", "-cp", f"{LCM_JAR}:{JAR}:{CLASSES}", "UvmsLogCount", JAR, log_path]
    for ch in last:
        cmd += ["--last", ch]
    p = subprocess.run(cmd, capture_output=True, text=True, timeout=60)
    counts, fields = {}, {}
    for line in p.stdout.splitlines():
        if line.startswith("LAST\t"):
            _, ch, field, text = line.split("\t", 3)
            fields[(ch, field)] = text
        elif line:
            ch, n = line.split(" ")
            counts[ch] = int(n)
    return p, counts, fields


def same_values(java_text, py_value):
    """Java's flattened text of one field == the uvmslog value, exactly (NaN == NaN)."""
    flat = list(py_value.ravel()) if hasattr(py_value, "ravel") else [py_value]
    if py_value.dtype.kind == "U":
        return java_text == " ".join(str(v) for v in flat)
    parts = java_text.split()
    if len(parts) != len(flat):
        return False
    for t, v in zip(parts, flat):
        if py_value.dtype.kind == "f":
            x = float(t)  # Java's shortest round-trip form ("1.0E-5", "Infinity", "NaN")
            if not (x == v or (math.isnan(x) and math.isnan(v))):
                return False
        elif int(t) != int(v):
            return False
    return True


def compare_last(log, fields, channel):
    """Every field of `channel`'s last message: Java's text vs uvmslog's row."""
    ch = log[channel]
    java_names = {f for (c, f) in fields if c == channel}
    assert java_names == set(ch.fields), \
        f"{channel}: Java fields {sorted(java_names ^ set(ch.fields))} differ from uvmslog's"
    bad = [f for f in ch.fields if not same_values(fields[(channel, f)], ch[f][-1])]
    assert not bad, f"{channel}: last message differs in {bad} " \
                    f"(Java {[fields[(channel, f)][:80] for f in bad]})"


def copy_log(src, dst, edit):
    """Copy an LCM log event by event; edit(event index, channel, data) -> data or None."""
    r, w = lcm.EventLog(src, "r"), lcm.EventLog(dst, "w", overwrite=True)
    for i, ev in enumerate(r):
        data = edit(i, ev.channel, bytes(ev.data))
        if data is not None:
            w.write_event(ev.timestamp, ev.channel, data)
    r.close()
    return w


def fake_java(record, awt=True):
    """A stand-in Java home whose bin/java writes its arguments, one per line, to `record`; with
    `awt`, it has the AWT/X11 library tools/lcm-spy looks for (a full runtime, not a headless
    one). Returns its bin directory."""
    home = os.path.join(TMP, "fakejdk-awt" if awt else "fakejdk-headless")
    os.makedirs(os.path.join(home, "bin"), exist_ok=True)
    os.makedirs(os.path.join(home, "lib"), exist_ok=True)
    if awt:
        open(os.path.join(home, "lib", "libawt_xawt.so"), "w").close()
    path = os.path.join(home, "bin", "java")
    with open(path, "w") as fh:
        fh.write(f"#!/bin/sh\nprintf '%s\\n' \"$@\" > '{record}'\nexit 0\n")
    os.chmod(path, 0o755)
    return os.path.join(home, "bin")


def spy(args, env_jar, record, display=":99", awt=True):
    """tools/lcm-spy with the stand-in java; display None: DISPLAY unset."""
    env = dict(os.environ, PATH=fake_java(record, awt) + ":/usr/bin:/bin", UVMS_LCM_JAR=env_jar,
               DISPLAY=display or "")
    if display is None:
        del env["DISPLAY"]
    return subprocess.run([SPY] + args, capture_output=True, text=True, env=env, timeout=20)


# ----------------------------------------------------------------------------------------------
# Checks


def check_jar_has_one_class_per_lcm_file():
    with zipfile.ZipFile(JAR) as z:
        classes = {n[len("uvms/"):-len(".class")] for n in z.namelist()
                   if n.startswith("uvms/") and n.endswith(".class")}
    lcm_files = {f[:-len(".lcm")] for f in os.listdir(os.path.join(SRC, "lcmtypes"))
                 if f.endswith(".lcm")}
    assert classes == lcm_files, f"jar classes {sorted(classes)} != lcmtypes/*.lcm " \
                                 f"{sorted(lcm_files)}"


def check_counts_and_last_truth_match_uvmslog():
    p, counts, fields = java_count(RUN_LOG, "UVMS_TRUTH")
    assert p.returncode == 0 and not p.stderr, f"UvmsLogCount: exit {p.returncode}: {p.stderr}"
    log = runlog.load(RUN_LOG)
    assert not log.skipped, f"uvmslog skipped events of unknown type: {log.skipped}"
    py_counts = {ch: c.count for ch, c in log.items()}
    assert counts == py_counts, f"Java counts {counts} != uvmslog counts {py_counts}"
    assert counts["UVMS_SENSORS"] == 50, f"a 1.5 s run has 50 ticks ({counts})"
    compare_last(log, fields, "UVMS_TRUTH")
    assert fields[("UVMS_TRUTH", "tick")] == "50", "the last truth sample is tick 50"


def check_scene_with_obstacle_matches_uvmslog():
    p, counts, fields = java_count(SCENE_LOG, "UVMS_SCENE")
    assert p.returncode == 0 and not p.stderr, f"UvmsLogCount: exit {p.returncode}: {p.stderr}"
    log = runlog.load(SCENE_LOG)
    assert counts == {ch: c.count for ch, c in log.items()}, f"counts differ: {counts}"
    assert fields[("UVMS_SCENE", "num_obstacles")] == "1", "the scene has one obstacle"
    compare_last(log, fields, "UVMS_SCENE")


def check_foreign_event_is_reported():
    path = os.path.join(TMP, "foreign.lcmlog")
    w = copy_log(RUN_LOG, path, lambda i, ch, d: d)
    w.write_event(10**9, "NOT_UVMS", FOREIGN_FINGERPRINT + b"\0" * 16)
    w.close()
    p, counts, _ = java_count(path)
    err = p.stderr.strip().splitlines()
    assert p.returncode == 1 and not counts and len(err) == 1, \
        f"exit {p.returncode}, counts {counts}, stderr {p.stderr!r}"
    assert err[0].startswith("UvmsLogCount: error: ") and "NOT_UVMS" in err[0] \
        and "fingerprint 0x123456789abcdef" in err[0], err[0]
    assert runlog.load(path).skipped == {"NOT_UVMS": 1}, "uvmslog also finds it foreign"


def check_corrupted_events_are_reported():
    cases = [  # (channel, how the first message of it is damaged, expected text)
        ("UVMS_TRUTH", lambda d: d[:100], "cannot decode as uvms.truth_t"),
        ("UVMS_SENSORS", lambda d: d[:3] + bytes([d[3] ^ 0x10]) + d[4:],
         "no uvms type has fingerprint"),
    ]
    for k, (channel, damage, expected) in enumerate(cases):
        path = os.path.join(TMP, f"corrupt{k}.lcmlog")
        seen = []

        def edit(i, ch, d):
            if ch == channel and not seen:
                seen.append(i)
                return damage(d)
            return d
        copy_log(RUN_LOG, path, edit).close()
        p, counts, _ = java_count(path)
        assert p.returncode == 1 and not counts and expected in p.stderr \
            and f"event {seen[0]} on {channel}" in p.stderr, \
            f"{channel}: exit {p.returncode}, stderr {p.stderr.strip()!r}"


def check_not_a_log_is_reported():
    path = os.path.join(TMP, "text.lcmlog")
    with open(path, "w") as fh:
        fh.write("not an LCM log\n" * 100)
    p, _, _ = java_count(path)
    assert p.returncode == 1 and "no LCM events" in p.stderr, p.stderr


def check_lcm_spy_help_starts_no_java():
    record = os.path.join(TMP, "help.args")
    p = spy(["--help"], JAR, record)
    assert p.returncode == 0 and not p.stderr, f"exit {p.returncode}, stderr {p.stderr!r}"
    assert not os.path.exists(record), "--help started java"
    lines = p.stdout.splitlines()
    assert lines[0].startswith("tools/lcm-spy:") and "SPDX" not in p.stdout, lines[:2]
    for words in ("--lcm-url", "--url", "link.publish_truth=true", "lcm-logplayer", "memq"):
        assert words in p.stdout, f"--help does not mention {words}"


def check_lcm_spy_without_jar_names_the_build():
    record = os.path.join(TMP, "nojar.args")
    p = spy(["--lcm-url=" + URL], os.path.join(TMP, "missing.jar"), record)
    err = p.stderr.strip().splitlines()
    assert p.returncode == 1 and len(err) == 1 and err[0].startswith("lcm-spy: error: ") \
        and "cmake --build --preset host" in err[0], f"exit {p.returncode}: {p.stderr!r}"
    assert not os.path.exists(record), "java started without the jar"


def check_lcm_spy_without_display_says_so():
    record = os.path.join(TMP, "nodisplay.args")
    p = spy(["--lcm-url=" + URL], JAR, record, display=None)
    assert p.returncode == 1 and p.stderr.startswith("lcm-spy: error: no display") \
        and len(p.stderr.strip().splitlines()) == 1, f"exit {p.returncode}: {p.stderr!r}"
    assert not os.path.exists(record), "java started without a display"


def check_lcm_spy_command_line():
    record = os.path.join(TMP, "spy.args")
    p = spy(["--lcm-url=" + URL], JAR, record)
    assert p.returncode == 0, f"exit {p.returncode}: {p.stderr!r}"
    args = open(record).read().splitlines()
    assert "-Xincgc" not in args and "-Djava.net.preferIPv4Stack=true" in args, args
    cp = args[args.index("-cp") + 1].split(":")
    assert JAR in cp and LCM_JAR in cp, f"class path {cp}"
    assert args[-2:] == ["lcm.spy.Spy", "--lcm-url=" + URL], f"arguments {args[-3:]}"


def check_lcm_spy_with_a_headless_runtime_says_so():
    record = os.path.join(TMP, "spy-headless.args")
    p = spy([], JAR, record, awt=False)
    err = p.stderr.strip().splitlines()
    assert p.returncode == 1 and len(err) == 1 and "headless" in err[0] \
        and "default-jre" in err[0] and not os.path.exists(record), (p.returncode, p.stderr)


def check_lcm_spy_starts_with_the_real_java():
    """The real JVM under a virtual X server (xvfb-run): lcm-spy finds every UVMS type in the
    jar, opens its window and is still running 4 s later, with no exception printed."""
    lcm_files = [f for f in os.listdir(os.path.join(SRC, "lcmtypes")) if f.endswith(".lcm")]
    # TMPDIR: xvfb-run's own temporary folder, which SIGTERM leaves behind, goes to our scratch.
    env = dict(os.environ, UVMS_LCM_JAR=JAR, TMPDIR=TMP)
    env.pop("DISPLAY", None)
    p = subprocess.Popen(["xvfb-run", "-a", SPY, "--lcm-url=" + URL], stdout=subprocess.PIPE,
                         stderr=subprocess.STDOUT, text=True, env=env, start_new_session=True)
    try:
        found = None
        deadline = time.time() + 30
        while found is None and time.time() < deadline:
            line = p.stdout.readline()
            if not line:
                break
            m = re.match(r"Found (\d+) LCM types", line)
            found = int(m.group(1)) if m else None
        time.sleep(4)
        alive = p.poll() is None
    finally:
        os.killpg(p.pid, signal.SIGTERM)
        out = p.communicate(timeout=20)[0]
    assert found == len(lcm_files), f"lcm-spy found {found} types, lcmtypes/ has {len(lcm_files)}"
    assert alive and "Exception" not in out, f"lcm-spy ended or failed: {out[-500:]!r}"


CHECKS = [check_jar_has_one_class_per_lcm_file, check_counts_and_last_truth_match_uvmslog,
          check_scene_with_obstacle_matches_uvmslog, check_foreign_event_is_reported,
          check_corrupted_events_are_reported, check_not_a_log_is_reported,
          check_lcm_spy_help_starts_no_java, check_lcm_spy_without_jar_names_the_build,
          check_lcm_spy_without_display_says_so, check_lcm_spy_command_line,
          check_lcm_spy_with_a_headless_runtime_says_so, check_lcm_spy_starts_with_the_real_java]


def setup():
    global RUN_LOG, SCENE_LOG
    RUN_LOG = make_run("sil/scenarios/paper/case_VII_stagnant.toml", 1.5, "vii")
    SCENE_LOG = make_run("sil/scenarios/scene/vent_chimney_VII.toml", 0.3, "scene")
    compile_checker()


def main():
    return checklist.run(CHECKS, TMP, setup)


if __name__ == "__main__":
    sys.exit(main())
