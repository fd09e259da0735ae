# SPDX-License-Identifier: Apache-2.0
"""dashboard: one PNG page per run, to see at a glance what a run did (tools/uvmslog.py
RUN... --dashboard). page.py: the page's data, panels and header, and the runs of a campaign
drawn N at a time.
"""
