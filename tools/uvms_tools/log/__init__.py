# SPDX-License-Identifier: Apache-2.0
"""log: UVMS run logs (`uvms run` writes RUN_DIR/run.lcmlog) read and checked.

records.py: the LCM event log read record by record, every record checked (framing, event
numbers, CRC-32, fingerprints, one run in order, complete); standard library only.
runlog.py: a checked log as numpy arrays per channel and field (load, ee_error), the names of
array components, the listing, --plot and CSV export of tools/uvmslog.py.
"""
