# SPDX-License-Identifier: Apache-2.0
"""Text: the report's Markdown. Each section module reads the runs (load), computes with the
analyses, draws with the figures and writes its lines."""
