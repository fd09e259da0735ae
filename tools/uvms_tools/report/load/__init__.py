# SPDX-License-Identifier: Apache-2.0
"""Loading: the configuration schema (`uvms scenario schema`), the campaign outputs
(results.json, plan.json, summary.json, overrides) and the run logs (tools/uvmslog.py)."""
