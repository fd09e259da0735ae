# SPDX-License-Identifier: Apache-2.0
"""vehicle: describing your own vehicle (uvms vehicle): the arm from URDF (urdf.py)."""
