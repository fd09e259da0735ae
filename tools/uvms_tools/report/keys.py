# SPDX-License-Identifier: Apache-2.0
"""keys: scenario keys, case names, metric names and the experiments' conditions shared by the
report's modules (the keys are those of `uvms scenario schema`; the cases are SPEC §9's
Table X). Names only: no values of configuration settings live here."""

# The experiments of SPEC §9, by campaign name (sil/campaigns/paper/<name>.toml).
EXPERIMENTS = [
    ("exp1_cases", "1. The eight cases of Table X"),
    ("exp2_payload", "2. Payload sweep"),
    ("exp3_tracking", "3. Thruster tracking"),
    ("exp4_fidelity", "4. Model fidelity"),
    ("exp5_travel", "5. Travel distance"),
    ("exp6_duration", "6. Trajectory duration"),
    ("exp7_energy_split", "7. Energy split"),
    ("exp8_analytic", "8. Simplified analytic model: energies of the full system"),
    ("exp8b_analytic_like", "8b. Simplified analytic model, like for like"),
]

# Beyond the paper (sil/campaigns/beyond/<file>.toml, name = "beyond_<file>"): gravity, the
# minimum-power allocation, the feedforward lead and a second vehicle (docs/MODEL.md §6.3,
# §7.3, §7.5, §12). Not part of the scorecard or headline.
BEYOND = [
    ("beyond_gravity", "Earth and Europa gravity: vehicle vs barycenter, both allocators"),
    ("beyond_allocation", "Minimum-power allocation on the paper's experiment 1, with the lead"),
    ("beyond_lead", "Feedforward lead at Europa and Earth gravity"),
    ("beyond_bluerov2", "A second vehicle: BlueROV2 Heavy + Reach Alpha 5, vehicle vs barycenter"),
]

CASES = ["I", "II", "III", "IV", "V", "VI", "VII", "VIII"]
VEH, BARY = "IV", "VII"  # vehicle and barycenter stabilization (SPEC §9 Table X)
# Cases that differ only in the position reference (same attitude, feedforward and feedback
# switches of Table X): (vehicle, barycenter).
MATCHED_PAIRS = [("VI", "III"), ("IV", "VII"), ("V", "VIII")]
FEEDBACK_PAIRS = [("IV", "VII"), ("V", "VIII")]

KEY_CASE = "control.case"
KEY_UNSTEADY = "environment.unsteady_flow.enabled"
KEY_DENSITY = "environment.density_error"
KEY_AOA = "environment.angle_of_attack"
KEY_VARC = "environment.variable_coefficients"
KEY_PAYLOAD = "payload.mass_kg"
KEY_DIST = "trajectory.cartesian.distance_m"
KEY_TRAJ_DUR = "trajectory.duration_s"
KEY_SEED = "run.seed"
KEY_RHO = "environment.density_kg_m3"
KEY_COEFF_TABLE = "environment.coeff_table"
KEY_GRAVITY = "environment.gravity_m_s2"
KEY_TRIM_PAYLOAD = "environment.trim_payload_kg"
KEY_ALLOC = "thrusters.allocation"
KEY_KPN = "control.kpn_Nm_rad"
KEY_LEAD = "control.feedforward_lead"

# Metrics of summary.json / results.json.
E_EL, E_P, E_MAN, ERR = ("thruster_energy_J", "propulsive_energy_J", "manipulator_energy_J",
                         "mean_ee_error_m")
ATT = "max_attitude_error_rad"
# Tick analyses of summary.json / results.json (sil/run/tick_analyses.hpp, docs/MODEL.md §10).
# Task-space error |p_EE - p_ref(t)| [m]; p_ref is metrics.ee_target_m ("target") or the
# commanded cosine line ("line"), named by TASK_REF.
TASK_REF = "task_error_reference"
TASK_MEAN, TASK_MAX, TASK_FINAL, TASK_AT_TF, TASK_HOLD = (
    "task_error_mean_m", "task_error_max_m", "task_error_final_m", "task_error_at_tf_m",
    "task_error_hold_mean_m")
KEY_EE_TARGET = "metrics.ee_target_m"
# E_p split exactly [J]: ff + fb + unsplit = pos + att + unsplit = x + y + z = E_P.
E_P_FF, E_P_FB, E_P_FF_FB_UNSPLIT = ("propulsive_energy_ff_J", "propulsive_energy_fb_J",
                                     "propulsive_energy_ff_fb_unsplit_J")
E_P_POS, E_P_ATT, E_P_POS_ATT_UNSPLIT = ("propulsive_energy_pos_J", "propulsive_energy_att_J",
                                         "propulsive_energy_pos_att_unsplit_J")
E_P_SPLIT_INEXACT, E_P_POS_ATT_INEXACT = ("propulsive_split_inexact_ticks",
                                          "propulsive_pos_att_inexact_ticks")
E_P_GROUPS = {"x": "propulsive_energy_group_x_J", "y": "propulsive_energy_group_y_J",
              "z": "propulsive_energy_group_z_J"}
E_P_GROUP_MEMBERS = "propulsive_energy_groups"  # summary.json only: {"x": [1, 2, 3, 4], ...}
# Motor energies [J]: shaft ∫ΣQ·ω dt, friction ∫Σb·ω² dt, copper ∫ΣRm·I² dt.
E_SHAFT, E_FRICTION, E_COPPER = "shaft_energy_J", "friction_energy_J", "copper_energy_J"
# Allocation modes (thrusters.allocation): the paper's pseudoinverse (least Σ T²) and the
# minimum-power allocation (least Σ|T|^1.5 delivering the pseudoinverse's wrench, §7.3).
ALLOC_PINV, ALLOC_MINPOW = "pseudoinverse", "min_power"
# The allocation's cost ∫Σ_j|T_j|^1.5 dt [N^1.5·s] of each run's own commanded wrenches
# (summary.json, docs/MODEL.md §7.3): of the pseudoinverse thrusts P, of the optimum T*, of the
# thrusts the run commanded; the static potential 1 − optimal/pinv, the realised saving
# 1 − commanded/pinv, and the ticks on which the optimum was not found.
ALLOC_COST_PINV, ALLOC_COST_OPT, ALLOC_COST_CMD = ("alloc_cost_pinv", "alloc_cost_optimal",
                                                   "alloc_cost_commanded")
ALLOC_POTENTIAL, ALLOC_REALISED = "alloc_static_potential", "alloc_realised_saving"
ALLOC_UNSOLVED = "alloc_potential_unsolved_ticks"

# Condition labels (SPEC §9 items 1, 2) and the override values that define them.
COND_EXP1_TEXT = {"stagnant": "(a) stagnant flow, no density error",
                  "unsteady": "(b) unsteady flow + density error"}
COND_EXP1_KEYS = {"stagnant": {KEY_UNSTEADY: False, KEY_DENSITY: False},
                  "unsteady": {KEY_UNSTEADY: True, KEY_DENSITY: True}}
COND_EXP2_TEXT = {"A": "(A) stagnant, no density error", "B": "(B) stagnant, density error",
                  "C": "(C) unsteady, density error"}
COND_EXP2_KEYS = {"A": {KEY_UNSTEADY: False, KEY_DENSITY: False},
                  "B": {KEY_UNSTEADY: False, KEY_DENSITY: True},
                  "C": {KEY_UNSTEADY: True, KEY_DENSITY: True}}
# Experiment 4's model options, in the order of its labels "U/ρ/α/C".
FIDELITY_KEYS = [KEY_UNSTEADY, KEY_DENSITY, KEY_AOA, KEY_VARC]
