# SPDX-License-Identifier: Apache-2.0
"""Float build vs double build of the controller over the same tick sequence.

Runs ctrl_sequence built against the double and the float firmware for the given cases and
compares every output column. The error measure is |float − double| relative to the
column's peak magnitude over the run (so a quantity passing through zero is not judged by its
own tiny value). Usage: compare_float_double.py DOUBLE_EXE FLOAT_EXE TOL [CASES...]"""
import subprocess
import sys

GROUPS = [("motor_voltage_V", 8), ("joint_accel_cmd_rad_s2", 7), ("force_des_N", 3),
          ("moment_des_Nm", 3), ("ee_estimate_m", 3), ("thrust_des_N", 8),
          ("motor_current_cmd_A", 8), ("motor_current_rate_A_s", 8)]
# Tolerance factor per group (× TOL). The current rate İ* = KB·(Î − I) [66] inherits the error of
# the desired speed ω̂ = √(|T|/|c1|) [57–63], whose slope 1/(2·√(|c1|·|T|)) is unbounded as the
# thrust crosses zero: an input error δT gives δω̂ ≈ √(δT/|c1|) there. With δT = 4.4e-4 of a
# ~2 N peak thrust (the thrust_des_N row) and c1 = −8.1e-5 N·s², δω̂ ≈ 3 rad/s at worst, i.e.
# δİ* = KB·J·KA·δω̂/km ≈ 0.08 A/s, about 1e-2 of İ*'s peak. The same error is in V through
# Lm·İ*, where V's peak (km·ω) hides it, and the integrated command I* averages it out.
TOL_FACTOR = {"motor_current_rate_A_s": 10.0}


def run(exe, case):
    out = subprocess.run([exe, str(case), "2000"], check=True, capture_output=True, text=True)
    return [list(map(float, line.split())) for line in out.stdout.splitlines()]


def main():
    dbl, flt, tol = sys.argv[1], sys.argv[2], float(sys.argv[3])
    cases = [int(c) for c in sys.argv[4:]] or [4, 7]
    worst_all = 0.0
    for case in cases:
        a, b = run(dbl, case), run(flt, case)
        assert len(a) == len(b) == 2000, "tick count differs"
        status_diff = sum(1 for ra, rb in zip(a, b) if ra[1] != rb[1])
        col = 2
        for name, width in GROUPS:
            worst = 0.0
            for c in range(col, col + width):
                peak = max(abs(r[c]) for r in a)
                if peak == 0.0:
                    continue
                err = max(abs(ra[c] - rb[c]) for ra, rb in zip(a, b)) / peak
                worst = max(worst, err)
            print(f"case {case}: {name:24s} max |float-double| / peak = {worst:.2e}")
            worst_all = max(worst_all, worst / TOL_FACTOR.get(name, 1.0))
            col += width
        print(f"case {case}: ticks whose status differs: {status_diff}")
        if status_diff:
            worst_all = float("inf")
    print(f"float vs double: worst relative error {worst_all:.2e} of the tolerance scale "
          f"(tolerance {tol:.1e}; motor_current_rate_A_s judged against 10× that)")
    return 0 if worst_all <= tol else 1


if __name__ == "__main__":
    sys.exit(main())
