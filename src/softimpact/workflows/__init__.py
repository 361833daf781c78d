"""Workflows: the paper's steps, composed from models and fem, returning results."""
