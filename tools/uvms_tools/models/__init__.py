# SPDX-License-Identifier: Apache-2.0
"""models: closed-form and fitted models that stand beside the simulation.

analytic.py: the paper's simplified analytic model of SPEC §9 item 8 ([87–89]), the drag /
reaction ratio and its limits (tools/analytic.py, uvms-analytic; the report uses it).
thruster_fit.py: SPEC §5's propeller and motor model fitted to a published bollard datasheet
(tools/thruster_fit.py, uvms-thruster-fit; the "t200" motor set of sil/scenario/motor_sets.cpp).
"""
