"""Loading: the configuration schema (`uvms scenario schema`), the campaign outputs
(results.json, plan.json, summary.json, overrides) and the run logs (tools/uvmslog.py)."""
