"""Finite elements: matrices (scikit-fem) and Newmark time stepping."""
