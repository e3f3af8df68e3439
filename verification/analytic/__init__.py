"""Closed-form references for vdec's verification problems. Independent of the solver."""
