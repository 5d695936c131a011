"""Beam-to-beam contact on fixed node pairs (small sliding): laws, kinematics, assembly."""
