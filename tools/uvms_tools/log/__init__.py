# SPDX-License-Identifier: Apache-2.0
"""log: UVMS run logs (`uvms run` writes RUN_DIR/run.lcmlog) read and checked.

records.py: the LCM event log read record by record, every record checked (framing, event
numbers, CRC-32, fingerprints, one run in order, complete); standard library only.
runlog.py: a checked log as numpy arrays per channel and field (load, ee_error), the names of
array components, the listing, plots and CSV export that tools/uvmslog.py offers.
Imports nothing of uvms_tools but env.py: every other subpackage reads logs through this one.
"""
